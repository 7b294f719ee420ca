# Imports an exported .glb/.gltf/.vrm into Blender headless and prints what a rigger sees:
# bones (direction vs. their child), shape keys, and the height of the mesh at zero weights.
#
#   blender -b --factory-startup --python-exit-code 1 -P tools/blender_inspect.py -- FILE [OUT.png]
#       [--bone-dir TEMPERANCE|BLENDER|FORTUNE] [--rig-check OUTDIR]
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
if "--rig-check" in argv:  # handled at the end
    i = argv.index("--rig-check")
    del argv[i : i + 2]
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


# --rig-check OUTDIR: what the rigger does with the built-in models: a fist (every
# finger bone 80 degrees), the left arm raised to 80 degrees from hanging, the left knee bent
# 130 degrees, and a checkerboard on the texture layout, front and back; Cycles renders.
def rig_check(outdir):
    import os

    scene = bpy.context.scene
    scene.render.engine = "CYCLES"
    scene.cycles.samples = 24
    scene.cycles.use_denoising = False
    scene.view_layers[0].cycles.use_denoising = False
    scene.render.resolution_x, scene.render.resolution_y = 400, 440
    # A grey sky lights every side (the back view was black under the sun alone).
    world = bpy.data.worlds.new("rig_world")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (0.5, 0.5, 0.52, 1.0)
    scene.world = world
    cam = bpy.data.objects.new("rig_cam", bpy.data.cameras.new("rig_cam"))
    cam.data.type = "ORTHO"
    scene.collection.objects.link(cam)
    scene.camera = cam
    sun = bpy.data.objects.new("rig_sun", bpy.data.lights.new("rig_sun", "SUN"))
    sun.rotation_euler = (math.radians(50), 0.0, math.radians(-30))
    scene.collection.objects.link(sun)

    def look(centre, scale, yaw_deg):
        yaw = math.radians(yaw_deg)
        cam.data.ortho_scale = scale
        cam.location = mathutils.Vector(centre) + mathutils.Vector(
            (5.0 * math.sin(yaw), -5.0 * math.cos(yaw), 0.0))
        cam.rotation_euler = (math.radians(90), 0.0, yaw)

    def render(name, note):
        scene.render.filepath = os.path.join(outdir, name)
        bpy.ops.render.render(write_still=True)
        print(f"rendered {scene.render.filepath}: {note}")

    def reset():
        for pb in arm.pose.bones:
            pb.matrix_basis = mathutils.Matrix.Identity(4)
        bpy.context.view_layer.update()

    def turn_bone(name_options, world_rotation):
        # Turns a bone by a rotation given in world (armature) axes, about its head.
        pb = next((arm.pose.bones[n] for n in name_options if n in arm.pose.bones), None)
        if pb is None:
            print(f"no bone {name_options}")
            return None
        m = pb.matrix.copy()
        head = m.translation.copy()
        r = world_rotation.to_4x4()
        new = r @ m
        new.translation = head
        pb.matrix = new
        bpy.context.view_layer.update()
        return pb

    def head_of(name_options):
        for n in name_options:
            if n in arm.pose.bones:
                return arm.matrix_world @ arm.pose.bones[n].head
        return mathutils.Vector((0, 0, 1))

    finger_words = ("index", "middle", "ring", "pinky", "thumb", "Index", "Middle", "Ring",
                    "Little", "Thumb")
    fingers = [pb for pb in arm.pose.bones if any(w in pb.name for w in finger_words)]
    print(f"finger bones: {len(fingers)}")
    # A fist: each finger bone turns 80 degrees (the thumb's 50) towards the palm, about the
    # axis across the finger in the palm's plane, found from the rest skeleton: the palm faces
    # s (h x w), h the wrist-to-middle-knuckle direction, w the little-to-index knuckle one,
    # s = +1 on the left hand, -1 on the right.
    reset()

    def rest_head(name):
        b = arm.data.bones.get(name)
        return b.head_local if b else None

    for side, names in (
        (1.0, ("left_wrist", "left_middle1", "left_pinky1", "left_index1")),
        (-1.0, ("right_wrist", "right_middle1", "right_pinky1", "right_index1")),
        (1.0, ("leftHand", "leftMiddleProximal", "leftLittleProximal", "leftIndexProximal")),
        (-1.0, ("rightHand", "rightMiddleProximal", "rightLittleProximal", "rightIndexProximal")),
    ):
        heads = [rest_head(n) for n in names]
        if any(h is None for h in heads):
            continue
        h = (heads[1] - heads[0]).normalized()
        w = (heads[3] - heads[2]).normalized()
        palm = side * h.cross(w).normalized()
        prefix = names[0].replace("_wrist", "_").replace("Hand", "")
        for pb in fingers:
            if not pb.name.startswith(prefix):
                continue
            d = (pb.bone.tail_local - pb.bone.head_local).normalized()
            axis = d.cross(palm)
            if axis.length < 1e-6:
                continue
            local = pb.bone.matrix_local.to_3x3().inverted() @ axis.normalized()
            angle = 50 if "thumb" in pb.name.lower() else 80
            pb.rotation_mode = "QUATERNION"
            pb.rotation_quaternion = mathutils.Quaternion(local.normalized(), math.radians(angle))
    bpy.context.view_layer.update()
    hand = head_of(("left_wrist", "leftHand", "hand_l"))
    look(hand, 0.3, 30)
    render("fist.png", f"{len(fingers)} finger bones at 80 degrees (thumbs 50), left hand")
    # The left arm raised to 80 degrees from hanging, in the frontal plane.
    reset()
    shoulder = head_of(("left_shoulder", "leftUpperArm", "upperarm_l"))
    elbow = head_of(("left_elbow", "leftLowerArm", "lowerarm_l"))
    now = (elbow - shoulder).normalized()
    target = mathutils.Vector((math.sin(math.radians(80)), 0.0, -math.cos(math.radians(80))))
    turn_bone(("left_shoulder", "leftUpperArm", "upperarm_l"),
              now.rotation_difference(target).to_matrix())
    look(shoulder, 0.9, 0)
    render("arm_raise_80.png", "left upper arm 80 degrees from hanging, front")
    # The left knee bent 130 degrees (the shin backwards: Blender's +Y is the body's back).
    reset()
    knee = head_of(("left_knee", "leftLowerLeg", "calf_l"))
    turn_bone(("left_knee", "leftLowerLeg", "calf_l"),
              mathutils.Matrix.Rotation(math.radians(130), 3, "X"))
    look(knee, 1.0, 90)
    render("knee_130.png", "left knee bent 130 degrees, seen from the left side")
    # A checkerboard on the UVs, front and back.
    reset()
    if mesh.data.uv_layers:
        img = bpy.data.images.new("checker", 1024, 1024)
        img.generated_type = "UV_GRID"
        mat = bpy.data.materials.new("checker")
        mat.use_nodes = True
        tex = mat.node_tree.nodes.new("ShaderNodeTexImage")
        tex.image = img
        bsdf = mat.node_tree.nodes["Principled BSDF"]
        mat.node_tree.links.new(tex.outputs["Color"], bsdf.inputs["Base Color"])
        for o in bpy.data.objects:
            if o.type == "MESH":
                o.data.materials.clear()
                o.data.materials.append(mat)
        lo, hi = height()
        centre = (0.0, 0.0, (lo + hi) / 2)
        look(centre, 2.1, 0)
        render("checker_front.png", "UV grid texture, front")
        look(centre, 2.1, 180)
        render("checker_back.png", "UV grid texture, back")
    else:
        print("no texture coordinates: no checkerboard render")


if "--rig-check" in sys.argv:
    rig_check(sys.argv[sys.argv.index("--rig-check") + 1])
