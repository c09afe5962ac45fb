"""A quick look at one surface (.ply from dump/surface): Blender's Workbench renderer, solid
light blue with studio light, from a camera you place; no materials, no waiting for Cycles.

    blender --background --python share/blender/render_surface.py -- SURFACE.ply OUT.png \\
            [CAMERA_X CAMERA_Y CAMERA_Z [LOOK_X LOOK_Y LOOK_Z]] [--size 1200x700]

The camera looks from CAMERA at LOOK (metres, the scene's coordinates; default: from in front
of and above the dam break's tank at its middle). docs/validation/surface.md's pictures were
made with it.
"""
import sys

import bpy
import mathutils


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    size = (1200, 700)
    if "--size" in argv:
        k = argv.index("--size")
        size = tuple(int(v) for v in argv[k + 1].split("x"))
        del argv[k:k + 2]
    if len(argv) < 2:
        sys.exit("render_surface.py: give SURFACE.ply OUT.png after '--'")
    ply, out = argv[0], argv[1]
    camera = [float(v) for v in argv[2:5]] if len(argv) >= 5 else [0.25, -0.35, 0.25]
    look = [float(v) for v in argv[5:8]] if len(argv) >= 8 else [0.25, 0.025, 0.05]
    for obj in list(bpy.data.objects):
        if obj.type == "MESH":
            bpy.data.objects.remove(obj, do_unlink=True)
    bpy.ops.import_mesh.ply(filepath=ply)
    mesh = bpy.context.selected_objects[0]
    for polygon in mesh.data.polygons:
        polygon.use_smooth = True
    cam = bpy.data.objects["Camera"]
    cam.location = camera
    cam.rotation_euler = (mathutils.Vector(look) - mathutils.Vector(camera)).to_track_quat("-Z", "Y").to_euler()
    cam.data.lens = 50
    scene = bpy.context.scene
    scene.render.engine = "BLENDER_WORKBENCH"
    scene.display.shading.light = "STUDIO"
    scene.display.shading.color_type = "SINGLE"
    scene.display.shading.single_color = (0.5, 0.7, 1.0)
    scene.render.resolution_x, scene.render.resolution_y = size
    scene.render.filepath = out
    bpy.ops.render.render(write_still=True)


main()
