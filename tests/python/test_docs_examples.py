"""The Python examples of docs/python.md run as shown: each ```python block (but those marked
`<!-- not run: REASON -->`) runs in a fresh interpreter, in a scratch directory that sees the
repository's scenarios/ and share/, and must end without an error."""
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
PAGE = REPO / "docs" / "python.md"


def examples():
    text = PAGE.read_text()
    found = []
    for match in re.finditer(r"(<!-- not run: [^>]*-->\n)?```python\n(.*?)```", text, re.S):
        if not match.group(1):
            line = text.count("\n", 0, match.start(2)) + 1
            found.append(pytest.param(match.group(2), id=f"python.md:{line}"))
    return found


@pytest.mark.parametrize("code", examples())
def test_example_runs(code, tmp_path):
    for folder in ("scenarios", "share"):
        (tmp_path / folder).symlink_to(REPO / folder)
    module_dir = os.path.dirname(os.path.dirname(os.path.abspath(__import__("pbfengine").__file__)))
    env = dict(os.environ, PYTHONPATH=module_dir)
    result = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, env=env, capture_output=True, text=True,
                            timeout=300)
    assert result.returncode == 0, result.stderr[-3000:]
    assert "Traceback" not in result.stderr


def test_every_example_is_found():
    assert len(examples()) >= 5
