# Imports an exported .glb/.gltf/.vrm into Blender headless and prints what a rigger sees:
# bones (direction vs. their child), shape keys, and the height of the mesh at zero weights.
#
#   blender -b --factory-startup --python-exit-code 1 -P tools/blender_inspect.py -- FILE [OUT.png]
#       [--bone-dir TEMPERANCE|BLENDER|FORTUNE]
#   (with OUT.png: also small Cycles renders of the imported body, at rest and posed)
#
# Bone Dir is the importer's heuristic for bone tails. Its default (Temperance) points a bone
# with one child at that child along the nearest local axis, which the exporter's bone
# rotations make exact, but a bone with several children at their centroid (SMPL's pelvis,
# whose hips and spine1 average to a point just in front of it); "Blender" uses each joint's
# local +Y, which the exporter points at the main child (pelvis -> spine1).
#   (tools/blender_check.sh does this for several exports when Blender is installed)
#
# Blender 3.4 (Debian 12) fails every glTF import with the default "Shading" option because
# of a numpy incompatibility (`module 'numpy' has no attribute 'bool'`); Shading = Smooth
# avoids that code path, so it is used here.
import math
import sys

import bpy
import mathutils

argv = sys.argv[sys.argv.index("--") + 1 :]
bone_dir = "TEMPERANCE"  # the importer's default; "BLENDER" uses each node's +Y exactly
if "--bone-dir" in argv:
    i = argv.index("--bone-dir")
    bone_dir = argv[i + 1]
    del argv[i : i + 2]
path = argv[0]
bpy.ops.wm.read_factory_settings(use_empty=True)
if path.lower().endswith(".vrm"):
    # Blender's importer only looks at .glb/.gltf names; a .vrm is a .glb.
    import os
    import shutil
    import tempfile

    copy = os.path.join(tempfile.mkdtemp(), os.path.basename(path)[:-4] + ".glb")
    shutil.copyfile(path, copy)
    path = copy
bpy.ops.import_scene.gltf(filepath=path, import_shading="SMOOTH", bone_heuristic=bone_dir)

arm = next(o for o in bpy.data.objects if o.type == "ARMATURE")
mesh = next(o for o in bpy.data.objects if o.type == "MESH")
print(f"file: {argv[0]} (Bone Dir: {bone_dir})")
print(f"armature: {len(arm.data.bones)} bones; mesh: {len(mesh.data.vertices)} vertices")

worst, worst_name = 0.0, ""
worst_single, worst_single_name = 0.0, ""  # bones with exactly one child
print("bone                 head (m, Blender z up)        bone-to-child angle")
for b in arm.data.bones:
    head = arm.matrix_world @ b.head_local
    d = (b.tail_local - b.head_local).normalized()
    angles = []
    for c in b.children:
        to_child = c.head_local - b.head_local
        if to_child.length > 1e-6:
            angles.append(math.degrees(d.angle(to_child.normalized())))
    angle = min(angles) if angles else None
    if angle is not None and angle > worst:
        worst, worst_name = angle, b.name
    if angle is not None and len(b.children) == 1 and angle > worst_single:
        worst_single, worst_single_name = angle, b.name
    if angle is not None or b.parent is None:
        shown = f"{angle:6.2f} deg" if angle is not None else "(root/leaf)"
        print(f"  {b.name:18s} ({head.x:+.3f}, {head.y:+.3f}, {head.z:+.3f})   {shown}")
print(f"worst bone-to-child angle: {worst:.3f} deg ({worst_name}); "
      f"among bones with one child: {worst_single:.3f} deg ({worst_single_name or '-'})")

keys = mesh.data.shape_keys.key_blocks if mesh.data.shape_keys else []
print(f"shape keys: {len(keys)}")
for k in list(keys)[:6]:
    print(f"  {k.name:16s} value {k.value:.3f}  slider [{k.slider_min:g}, {k.slider_max:g}]")
if len(keys) > 6:
    print(f"  ... {len(keys) - 6} more")


def height():
    deps = bpy.context.evaluated_depsgraph_get()
    ev = mesh.evaluated_get(deps)
    me = ev.to_mesh()
    zs = [(ev.matrix_world @ v.co).z for v in me.vertices]
    ev.to_mesh_clear()
    return min(zs), max(zs)


lo, hi = height()
print(f"height at zero shape-key values (armature applied): {hi - lo:.5f} m, feet at z = {lo:+.5f}")
if len(keys) > 1:
    keys[1].value = 1.0
    bpy.context.view_layer.update()
    lo1, hi1 = height()
    print(f"height with '{keys[1].name}' = 1: {hi1 - lo1:.5f} m")
    keys[1].value = 0.0


if len(argv) > 1:
    out = argv[1]
    scene = bpy.context.scene
    cam_data = bpy.data.cameras.new("cam")
    cam_data.type = "ORTHO"
    cam_data.ortho_scale = 2.2
    cam = bpy.data.objects.new("cam", cam_data)
    scene.collection.objects.link(cam)
    cam.location = mathutils.Vector((0.0, -5.0, (hi + lo) / 2))  # glTF +Z front = Blender -Y
    cam.rotation_euler = (math.radians(90), 0.0, 0.0)
    scene.camera = cam
    light = bpy.data.objects.new("sun", bpy.data.lights.new("sun", "SUN"))
    light.rotation_euler = (math.radians(60), 0.0, math.radians(-30))
    scene.collection.objects.link(light)
    scene.render.engine = "CYCLES"
    scene.cycles.samples = 8
    scene.cycles.use_denoising = False
    scene.view_layers[0].cycles.use_denoising = False
    scene.render.resolution_x, scene.render.resolution_y = 440, 480
    scene.render.filepath = out
    bpy.ops.render.render(write_still=True)
    print(f"rendered {out}")
    # Posing works from the rest pose: bend the left knee and the left elbow (about each
    # bone's local x, which the exporter keeps perpendicular to the bone) and render again.
    for names, angle in ((("left_knee", "leftLowerLeg"), -70), (("left_elbow", "leftLowerArm"), -60)):
        pb = next((arm.pose.bones[n] for n in names if n in arm.pose.bones), None)
        if pb is not None:
            pb.rotation_mode = "XYZ"
            pb.rotation_euler = (math.radians(angle), 0.0, 0.0)
    bpy.context.view_layer.update()
    turn = math.radians(-60)  # the camera looks along (-sin, cos, 0) after turning about z
    cam.location = mathutils.Vector((5.0 * math.sin(turn), -5.0 * math.cos(turn), (hi + lo) / 2))
    cam.rotation_euler = (math.radians(90), 0.0, turn)
    posed = out[:-4] + "_posed.png"
    scene.render.filepath = posed
    bpy.ops.render.render(write_still=True)
    print(f"rendered {posed} (left knee -70 deg, left elbow -60 deg, seen from the front right)")
