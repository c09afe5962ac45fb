#!/usr/bin/env python3
"""Tests of tests/check_docs.py as a change detector: --update rewrites wording freely but
changes a number only with --because REASON, which it records in the ledger.

    python3 tests/test_check_docs.py [-v]

Each test writes a small Markdown page and a fake pbfengine (a script that prints fixed
output) into a temporary directory, and runs check_docs there, its ledger there too: no
built engine, nothing written into the repository. Standard library only.
"""

import contextlib
import io
import shutil
import sys
import tempfile
import textwrap
import unittest
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import check_docs  # noqa: E402

PAGE = """\
# A page

<!-- check: run scene.lua -->
```
pbfengine 0.3.1 on 4 OpenMP threads (4 cores)
step 10 t 0.5 energy 1.25
done
```

Text after the block.
"""


class ChangeDetector(unittest.TestCase):
    def setUp(self):
        self.dir = Path(tempfile.mkdtemp(prefix="test_check_docs."))
        self.addCleanup(shutil.rmtree, self.dir, ignore_errors=True)
        self.page = self.dir / "page.md"
        self.page.write_text(PAGE)
        self.binary = self.dir / "pbfengine"
        self.ledger = self.dir / "changed-numbers.md"

    def prints(self, output):
        """Makes the fake pbfengine print `output` (the same, whatever the command)."""
        self.binary.write_text(f"#!{sys.executable}\nimport sys\nsys.stdout.write({output!r})\n")
        self.binary.chmod(0o755)

    def check(self, *options, real="float"):
        """Runs check_docs on the page as a `real` build would; (exit status, what it printed)."""
        argv = ["--binary", str(self.binary), "--real", real, "--ledger", str(self.ledger), *options,
                str(self.page)]
        out = io.StringIO()
        with contextlib.redirect_stdout(out):
            code = check_docs.run(argv)
        return code, out.getvalue()

    def test_the_page_as_printed_passes(self):
        self.prints("pbfengine 0.3.1 on 2 OpenMP threads (2 cores)\nstep 10 t 0.5 energy 1.25\ndone\n")
        code, out = self.check()
        self.assertEqual(code, 0, out)  # the thread count is masked: it may differ

    def test_a_wording_change_updates_without_a_reason(self):
        self.prints("pbfengine 0.3.1 on 4 OpenMP threads (4 cores)\nstep 10 t 0.5 energy 1.25\nfinished\n"
                    "wrote 3 files\n")
        code, out = self.check("--update")
        self.assertEqual(code, 0, out)
        self.assertIn("no number changed", out)
        self.assertIn("+finished", out)  # says what it updated
        self.assertIn("finished\nwrote 3 files\n```", self.page.read_text())  # a new line may bring numbers
        self.assertFalse(self.ledger.exists())

    def test_a_version_is_not_a_result(self):
        self.prints("pbfengine 0.4.0 on 4 OpenMP threads (4 cores)\nstep 10 t 0.5 energy 1.25\ndone\n")
        code, out = self.check("--update")
        self.assertEqual(code, 0, out)
        self.assertIn("pbfengine 0.4.0", self.page.read_text())

    def test_a_changed_number_fails_the_check_as_a_result_change(self):
        self.prints("pbfengine 0.3.1 on 4 OpenMP threads (4 cores)\nstep 10 t 0.5 energy 1.26\ndone\n")
        code, out = self.check()
        self.assertEqual(code, 1, out)
        self.assertIn("these are numbers, a result changed (not wording): 1 number changed, "
                      "by at most 0.8% (relative)", out)
        self.assertIn(f"{self.page}:6: 1.25 → 1.26", out)
        self.assertIn("--update --because", out)

    def test_a_changed_number_is_not_updated_without_a_reason(self):
        self.prints("pbfengine 0.3.1 on 4 OpenMP threads (4 cores)\nstep 10 t 0.5 energy 1.26\nfinished\n")
        code, out = self.check("--update")
        self.assertEqual(code, 1, out)
        self.assertIn(f"{self.page}:4: NOT UPDATED", out)
        self.assertIn("1.25 → 1.26", out)
        self.assertIn("--update --because 'THE PHYSICAL REASON'", out)  # the command to accept it
        self.assertEqual(self.page.read_text(), PAGE)  # not even its wording
        self.assertFalse(self.ledger.exists())

    def test_a_number_gone_is_a_change(self):
        self.prints("pbfengine 0.3.1 on 4 OpenMP threads (4 cores)\ndone\n")
        code, out = self.check("--update")
        self.assertEqual(code, 1, out)
        self.assertIn("3 numbers gone", out)
        self.assertEqual(self.page.read_text(), PAGE)

    def test_a_changed_number_with_a_reason_is_updated_and_recorded(self):
        self.prints("pbfengine 0.3.1 on 4 OpenMP threads (4 cores)\nstep 10 t 0.5 energy 1.26\ndone\n")
        code, out = self.check("--update", "--because", "kinetic energy | now counts z")
        self.assertEqual(code, 0, out)
        self.assertIn("energy 1.26", self.page.read_text())
        ledger = self.ledger.read_text()
        self.assertTrue(ledger.startswith(check_docs.LEDGER_HEADER), ledger)
        rows = ledger[len(check_docs.LEDGER_HEADER):].splitlines()
        self.assertEqual(len(rows), 1, ledger)
        self.assertRegex(rows[0], r"^\| \d{4}-\d\d-\d\d \d\d:\d\d \| \S+ \| ")
        self.assertIn(f"| {self.page}:4 | 1.25 → 1.26; 1 number changed, by at most 0.8% (relative) |", rows[0])
        self.assertTrue(rows[0].endswith("| kinetic energy \\| now counts z |"), rows[0])

        # The ledger is appended to: the next accepted change goes after the first.
        self.prints("pbfengine 0.3.1 on 4 OpenMP threads (4 cores)\nstep 20 t 0.5 energy 1.26\ndone\n")
        code, out = self.check("--update", "--because", "twice the steps")
        self.assertEqual(code, 0, out)
        rows2 = self.ledger.read_text()[len(check_docs.LEDGER_HEADER):].splitlines()
        self.assertEqual(rows2[0], rows[0])
        self.assertIn("| 10 → 20; 1 number changed, by at most 100% (relative) | twice the steps |", rows2[1])

    def test_the_ledger_gives_each_block_its_line_in_the_updated_page(self):
        # The first block gains a line (wording: no number it showed changes); the second,
        # at line 7 before and 8 after, changes its energy.
        self.page.write_text(textwrap.dedent("""\
            <!-- check: run a.lua -->
            ```
            done
            ```

            <!-- check: run b.lua -->
            ```
            step 10 t 0.5 energy 1.25
            done
            ```
            """))
        self.prints("step 10 t 0.5 energy 1.27\ndone\n")
        code, out = self.check("--update", "--because", "a reason")
        self.assertEqual(code, 0, out)
        self.assertEqual(self.page.read_text().splitlines()[7], "```")
        self.assertIn(f"| {self.page}:8 | 1.25 → 1.27;", self.ledger.read_text())

    def test_masked_numbers_change_freely(self):
        self.page.write_text("<!-- check: run a.lua; mask -->\n```\nTiming: 1.5 s\nsteps\n```\n")
        self.prints("Timing: 2.5 s\nsteps per second\n")
        code, out = self.check("--update")
        self.assertEqual(code, 0, out)
        self.assertIn("steps per second", self.page.read_text())

    def test_a_build_of_the_other_precision_updates_wording_but_not_the_numbers_it_skips(self):
        # An each-check: every script runs alone as e.lua, the block shows its last line. The
        # fake echoes the script to stderr, with this build's digits in the number.
        scripts = self.dir / "scripts.txt"
        scripts.write_text("error: no such style 'pfb'\nerror: h is 0.25\n")
        self.page.write_text(f"<!-- check: each {scripts} -->\n```\nerror: no such style 'pbf'\n"
                             "error: h is 0.25\n```\n")
        self.binary.write_text(f"#!{sys.executable}\nimport sys\n"
                               "sys.stderr.write(open('e.lua').read().replace('0.25', '0.2500000001'))\n"
                               "sys.exit(1)\n")
        self.binary.chmod(0o755)
        code, out = self.check("--update", real="double")
        self.assertEqual(code, 0, out)
        self.assertIn("'pfb'\nerror: h is 0.25\n```", self.page.read_text())

    def test_because_goes_with_update_and_says_something(self):
        self.prints("done\n")
        with contextlib.redirect_stderr(io.StringIO()):
            with self.assertRaises(SystemExit):
                self.check("--because", "a reason")
            with self.assertRaises(SystemExit):
                self.check("--update", "--because", " ")


class NumberChanges(unittest.TestCase):
    def test_pairs_each_number_with_the_one_in_its_place(self):
        changes = check_docs.number_changes(["a 1 b 2", "c 3"], ["a 1 b 2", "c 4"])
        self.assertEqual(changes, [check_docs.NumberChange(1, "3", "4")])

    def test_reworded_lines_still_pair_their_numbers(self):
        changes = check_docs.number_changes(["a 1 b 2"], ["a 1 bee 5"])
        self.assertEqual(changes, [check_docs.NumberChange(0, "2", "5")])

    def test_added_lines_and_masked_figures_are_no_changes(self):
        shown = ["Timing: 10 steps of 100 particles in 3.2 s", "  pbf 1.2 s 40%", "c 3"]
        new = ["Timing: 10 steps of 100 particles in 3.9 s", "  pbf 1.7 s 45%", "new 7", "c 3"]
        self.assertEqual(check_docs.number_changes(shown, new), [])

    def test_summary_says_how_many_and_how_much(self):
        changes = [check_docs.NumberChange(0, "2", "3"), check_docs.NumberChange(0, "10", "10.5"),
                   check_docs.NumberChange(1, "7", None)]
        self.assertEqual(check_docs.summarise_changes(changes),
                         "2 numbers changed, by at most 50% (relative) and 1 number gone")


if __name__ == "__main__":
    unittest.main()
