"""What Blender makes of a motion file: imports it with Blender's own importer and default settings
and prints one JSON line, prefixed "import_report: ", for a test or a person to compare with
mostyle's own reading.

usage: blender -b --factory-startup --python tests/blender/import_report.py -- FILE [FPS]

FILE is a .glb, .gltf, .fbx or .bvh. glTF states no rate and its importer keys at the scene's: the
scene's rate is set to FPS (default 30) first, as an animator would. The line holds:
  objects: how many objects of each type the import made ("ARMATURE", "EMPTY", ...);
  bones: the armature's bone names (the first armature's; [] when there is none);
  height: the vertical extent of the bones' heads at the first key of the active action (the rest
    pose when there is none), metres as Blender shows them;
  actions: per action the armature's NLA tracks hold (or the one active action): name (the
    track's: glTF's importer names it after the animation), fps (the rate sampled at), and
    heads: one row per sample, from the action's first key to its last at FPS, each row x, y, z
    per bone in `bones` order, in the file's axes (Y up: Blender's Z-up world turned back,
    (x, y, z) -> (x, z, -y)).
Before each action is sampled every pose bone is put back to the pose the importer gives it
where no animation moves it (glTF: its node's own transform), so a bone the action does not key
holds that pose, not the last action's: Blender evaluates the first action on import and keeps
each bone's last value when another action is made active. That pose is read from an import of
the same file without its animations.
"""
import json
import math
import os
import struct
import sys
import tempfile

import bpy

try:
    import numpy
except ImportError:  # the glTF importer then says so, as the error of the import
    numpy = None

# Debian 12's Blender 3.4 imports glTF meshes with numpy.bool, which numpy 1.24 no longer has: the
# alias it stood for, so that files with a mesh import with the default settings.
if numpy is not None and not hasattr(numpy, "bool"):
    numpy.bool = bool


def arguments():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if len(argv) not in (1, 2):
        print(__doc__.split("\n\n")[1])
        sys.exit(2)
    return argv[0], float(argv[1]) if len(argv) == 2 else 30.0


def import_file(path, fps):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.fps = max(1, round(fps))
    scene.render.fps_base = scene.render.fps / fps
    lower = path.lower()
    if lower.endswith(".fbx"):
        bpy.ops.import_scene.fbx(filepath=path)
    elif lower.endswith(".glb") or lower.endswith(".gltf"):
        bpy.ops.import_scene.gltf(filepath=path)
    elif lower.endswith(".bvh"):
        bpy.ops.import_anim.bvh(filepath=path)
    else:
        raise ValueError("not a .fbx, .glb, .gltf or .bvh file: " + path)


def without_animations(path):
    """A copy of a glTF file without its animations, in a temporary folder; None for other files."""
    lower = path.lower()
    if not (lower.endswith(".glb") or lower.endswith(".gltf")):
        return None
    data = open(path, "rb").read()
    folder = os.path.dirname(os.path.abspath(path))
    if data[:4] == b"glTF":
        length = struct.unpack("<I", data[12:16])[0]
        doc = json.loads(data[20:20 + length])
        rest = data[20 + length:]
    else:
        doc = json.loads(data)
        rest = b""
    doc.pop("animations", None)
    for item in doc.get("buffers", []) + doc.get("images", []):
        uri = item.get("uri")
        if uri and not uri.startswith("data:"):
            item["uri"] = os.path.join(folder, uri)
    text = json.dumps(doc).encode()
    out = tempfile.NamedTemporaryFile(suffix=".glb" if data[:4] == b"glTF" else ".gltf", delete=False)
    if data[:4] == b"glTF":
        text += b" " * (-len(text) % 4)
        out.write(b"glTF" + struct.pack("<II", 2, 20 + len(text) + len(rest)) + struct.pack("<I", len(text)) +
                  b"JSON" + text + rest)
    else:
        out.write(text)
    out.close()
    return out.name


def unanimated_pose(path, fps):
    """Each bone's pose (location, quaternion, Euler angles, scale) as the importer sets it where no
    animation moves it; {} when the file is no glTF file or has no armature."""
    copy = without_animations(path)
    if copy is None:
        return {}
    try:
        import_file(copy, fps)
    finally:
        os.unlink(copy)
    armatures = [o for o in bpy.data.objects if o.type == "ARMATURE"]
    if not armatures:
        return {}
    return {b.name: (b.location.copy(), b.rotation_quaternion.copy(), b.rotation_euler.copy(), b.scale.copy())
            for b in armatures[0].pose.bones}


def heads(arm):
    rows = []
    for bone in arm.pose.bones:
        p = arm.matrix_world @ bone.head
        rows.append((p.x, p.z, -p.y))
    return rows


def main():
    path, fps = arguments()
    try:
        rest = unanimated_pose(path, fps)
        import_file(path, fps)
    except Exception as e:  # the importer's own error, as one line
        print("import_report: " + json.dumps({"error": str(e).splitlines()[0] if str(e) else repr(e)}))
        sys.exit(2)
    objects = {}
    for o in bpy.data.objects:
        objects[o.type] = objects.get(o.type, 0) + 1
    armatures = [o for o in bpy.data.objects if o.type == "ARMATURE"]
    report = {"objects": objects, "bones": [], "height": 0.0, "actions": []}
    if not armatures:
        print("import_report: " + json.dumps(report))
        return
    arm = armatures[0]
    report["bones"] = [b.name for b in arm.pose.bones]
    scene = bpy.context.scene
    scene_fps = scene.render.fps / scene.render.fps_base
    data = arm.animation_data
    actions = []  # (name, action): an NLA track's name (glTF: the animation's), else the action's
    if data is not None:
        for track in data.nla_tracks:
            if track.strips and all(track.strips[0].action is not a for _, a in actions):
                actions.append((track.name, track.strips[0].action))
            track.mute = True
        if not actions and data.action is not None:
            actions.append((data.action.name, data.action))
    first_action = data.action if data is not None else None

    def unanimated():
        for b in arm.pose.bones:
            if b.name in rest:
                b.location, b.rotation_quaternion, b.rotation_euler, b.scale = (v.copy() for v in rest[b.name])

    for name, action in actions:
        unanimated()
        data.action = action
        keys = [k.co.x for c in action.fcurves for k in c.keyframe_points]
        start, end = (min(keys), max(keys)) if keys else (scene.frame_start, scene.frame_start)
        count = int(math.floor((end - start) / scene_fps * fps + 1e-3)) + 1
        rows = []
        for f in range(count):
            frame = start + f * scene_fps / fps
            whole = math.floor(frame)
            scene.frame_set(int(whole), subframe=frame - whole)
            rows.append([c for p in heads(arm) for c in p])
        report["actions"].append({"name": name, "fps": fps, "heads": rows})
    unanimated()
    if data is not None:
        data.action = first_action
    if first_action is not None:
        scene.frame_set(int(math.floor(first_action.frame_range[0])))
    ys = [p[1] for p in heads(arm)]
    report["height"] = max(ys) - min(ys) if ys else 0.0
    print("import_report: " + json.dumps(report))


main()
