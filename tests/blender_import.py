#!/usr/bin/env python3
"""share/blender/import_surfaces.py in Debian's Blender, headless: a small dam break's surfaces
(dump/surface, .ply) load as an animation that shows one mesh per frame, and the .blend is saved.

    blender_import.py --binary build/pbfengine [--blender blender]

Exits 77 (skipped, for ctest) when Blender is not installed: .ci/run installs it.
"""
import argparse
import os
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)

CHECK = """
import bpy, sys
scene = bpy.context.scene
meshes = sorted(o.name for o in bpy.data.objects if o.type == "MESH")
shown = []
for frame in range(scene.frame_start, scene.frame_end + 1):
    scene.frame_set(frame)
    shown.append([o.name for o in bpy.data.objects if o.type == "MESH" and not o.hide_render])
print("CHECK", scene.frame_start, scene.frame_end, len(meshes), shown, len(bpy.data.objects[meshes[-1]].data.polygons))
"""


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--binary", required=True)
    ap.add_argument("--blender", default="blender")
    args = ap.parse_args()
    if not shutil.which(args.blender):
        print("blender_import.py: no Blender here (Debian's package 'blender'): skipped")
        return 77
    with tempfile.TemporaryDirectory(prefix="pbf-blender-") as work:
        out = os.path.join(work, "out")
        subprocess.run([args.binary, "run", os.path.join(ROOT, "scenarios", "dambreak.lua"), "-v", "particles=2000",
                        "-v", "t_end=0.2", "-v", f"out={out}", "-v", "surface=0.05", "-v", "restart_interval=0",
                        "-v", "interval=1", "--log", "none"], check=True, stdout=subprocess.DEVNULL)
        plys = sorted(f for f in os.listdir(os.path.join(out, "surface")) if f.endswith(".ply"))
        saved = os.path.join(work, "water.blend")
        run = subprocess.run([args.blender, "--background", "--python",
                              os.path.join(ROOT, "share", "blender", "import_surfaces.py"), "--",
                              os.path.join(out, "surface", "surface_*.ply"), "--save", saved],
                             capture_output=True, text=True, timeout=300)
        if run.returncode != 0 or not os.path.exists(saved):
            print(run.stdout, run.stderr)
            print("blender_import.py: FAIL: the import did not save a .blend")
            return 1
        check = subprocess.run([args.blender, "--background", saved, "--python-expr", CHECK],
                               capture_output=True, text=True, timeout=300)
        line = next((l for l in check.stdout.splitlines() if l.startswith("CHECK")), "")
        words = line.split(" ", 4)
        if len(words) < 5:
            print(check.stdout, check.stderr)
            print("blender_import.py: FAIL: the saved .blend could not be read back")
            return 1
        start, end, meshes = int(words[1]), int(words[2]), int(words[3])
        shown = eval(words[4].rsplit(" ", 1)[0])
        polygons = int(words[4].rsplit(" ", 1)[1])
        expected = [[os.path.splitext(p)[0]] for p in plys]
        problems = []
        if (start, end, meshes) != (1, len(plys), len(plys)):
            problems.append(f"frames {start}..{end} with {meshes} meshes, expected 1..{len(plys)} with {len(plys)}")
        if shown != expected:
            problems.append(f"meshes shown per frame {shown}, expected {expected}")
        with open(os.path.join(out, "surface", plys[-1]), "rb") as f:
            faces = int(next(l for l in f.read(2048).split(b"\n") if l.startswith(b"element face")).split()[2])
        if polygons != faces:
            problems.append(f"the last mesh has {polygons} polygons in Blender, {faces} in its .ply")
        for p in problems:
            print("blender_import.py: FAIL:", p)
        if not problems:
            print(f"blender_import.py: {len(plys)} surfaces loaded as frames 1..{len(plys)}, one shown on each, "
                  f"{faces} triangles in the last")
        return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
