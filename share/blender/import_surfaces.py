"""Loads a numbered sequence of pbfengine surfaces (.ply from dump/surface) into Blender as an
animation: one mesh per frame, each shown only on its own frame, shaded smooth, with a water
material (glass-like: transmission 1, index of refraction 1.33). Blender's start-up cube is
removed; the camera and light stay.

    blender --background --python share/blender/import_surfaces.py -- out/surface/surface_*.ply \\
            [--save out/water.blend] [--fps 50] [--start 1] [--no-material]

or, inside Blender, Scripting > Open this file, set SURFACES below and Run Script. The frames
keep their order (their numbers); the scene runs from --start (frame 1) to the last one, at
--fps frames per second (default: one per dump interval, read from the files' "t = ..."
comments, so the animation plays in simulated time). Written for Blender 3.x (Debian 12 has
3.4); it uses only the PLY importer that ships with Blender.
"""
import glob
import os
import re
import sys

import bpy

SURFACES = []  # paths or a glob, for running inside Blender without arguments


def arguments():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    files, options, k = [], {"save": None, "fps": None, "start": 1, "material": True}, 0
    while k < len(argv):
        a = argv[k]
        if a == "--save":
            options["save"], k = argv[k + 1], k + 2
        elif a == "--fps":
            options["fps"], k = float(argv[k + 1]), k + 2
        elif a == "--start":
            options["start"], k = int(argv[k + 1]), k + 2
        elif a == "--no-material":
            options["material"], k = False, k + 1
        else:
            files += sorted(glob.glob(a)) or [a]
            k += 1
    for s in SURFACES:
        files += sorted(glob.glob(s))
    return files, options


def simulated_time(path):
    """The 't = ... s' of the PLY header's comment, or None."""
    with open(path, "rb") as f:
        head = f.read(1024).split(b"end_header")[0].decode("ascii", "replace")
    m = re.search(r"t = ([0-9.eE+-]+) s", head)
    return float(m.group(1)) if m else None


def water_material():
    mat = bpy.data.materials.new("pbfengine water")
    mat.use_nodes = True
    bsdf = mat.node_tree.nodes.get("Principled BSDF")
    bsdf.inputs["Base Color"].default_value = (0.8, 0.9, 1.0, 1.0)
    bsdf.inputs["Transmission"].default_value = 1.0
    bsdf.inputs["IOR"].default_value = 1.33
    bsdf.inputs["Roughness"].default_value = 0.02
    return mat


def show_only_on(obj, frame):
    """Keyframes that hide the object but on `frame`."""
    for f, hidden in ((frame - 1, True), (frame, False), (frame + 1, True)):
        obj.hide_viewport = obj.hide_render = hidden
        obj.keyframe_insert("hide_viewport", frame=f)
        obj.keyframe_insert("hide_render", frame=f)
    for curve in obj.animation_data.action.fcurves:
        for point in curve.keyframe_points:
            point.interpolation = "CONSTANT"


def main():
    files, options = arguments()
    if not files:
        sys.exit("import_surfaces.py: give the .ply files after '--' (e.g. out/surface/surface_*.ply)")
    missing = [f for f in files if not os.path.isfile(f)]
    if missing:
        sys.exit(f"import_surfaces.py: no such file: {missing[0]}")
    # Blender's start-up scene (a cube, a camera, a light): the cube goes, the water takes its place.
    if sorted(o.name for o in bpy.data.objects) == ["Camera", "Cube", "Light"]:
        bpy.data.objects.remove(bpy.data.objects["Cube"], do_unlink=True)
    material = water_material() if options["material"] else None
    collection = bpy.data.collections.new("pbfengine surfaces")
    bpy.context.scene.collection.children.link(collection)
    times = [simulated_time(f) for f in files]
    for k, path in enumerate(files):
        bpy.ops.import_mesh.ply(filepath=path)
        obj = bpy.context.selected_objects[0]
        obj.name = os.path.splitext(os.path.basename(path))[0]
        for c in obj.users_collection:
            c.objects.unlink(obj)
        collection.objects.link(obj)
        for polygon in obj.data.polygons:
            polygon.use_smooth = True
        if material:
            obj.data.materials.append(material)
        show_only_on(obj, options["start"] + k)
    scene = bpy.context.scene
    scene.frame_start, scene.frame_end = options["start"], options["start"] + len(files) - 1
    fps = options["fps"]
    if fps is None and len(files) > 1 and None not in times[:2] and times[1] > times[0]:
        fps = 1 / (times[1] - times[0])
    if fps:
        scene.render.fps, scene.render.fps_base = max(1, round(fps)), max(1, round(fps)) / fps
    print(f"import_surfaces.py: {len(files)} surfaces, frames {scene.frame_start}..{scene.frame_end}"
          + (f" at {fps:g} per second" if fps else ""))
    if options["save"]:
        bpy.ops.wm.save_as_mainfile(filepath=os.path.abspath(options["save"]))
        print(f"import_surfaces.py: saved {options['save']}")


main()
