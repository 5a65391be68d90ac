"""Imports a motion file mostyle wrote into Blender and compares what Blender makes of it with our
own forward kinematics of the source.

usage: mostyle-cli fk SOURCE --out fk.csv
       blender -b --factory-startup --python tests/tools/blender_check.py -- FILE.glb|FILE.gltf|FILE.fbx fk.csv FPS

FILE is imported with Blender's own importer and default settings (bpy.ops.import_scene.gltf or
.fbx) into an empty scene (for glTF, which states no rate, the scene's rate set to FPS first, as
the importer keys at the scene's rate). Checked: exactly one armature, exactly one action, and that action is
the armature's, keying its bones. Then, at every frame f of fk.csv (time f / FPS from the
action's first key), the world position of each bone's head is compared with fk.csv's position of
the joint of that name, after fitting one similarity (rotation, uniform scale, translation:
Blender converts axes and units) over all frames and joints. Errors are fractions of the body's
height (the vertical extent of the source's first frame). Prints one line of results and exits 0
when the mean error is at most 1e-3 and the largest at most 5e-3 of the height, 1 otherwise, and
2 when the file could not be imported or compared.
"""
import csv
import math
import sys

import bpy
import numpy as np

MEAN_BOUND = 1e-3
MAX_BOUND = 5e-3


def arguments():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if len(argv) != 3:
        print(__doc__.split("\n\n")[1])
        sys.exit(2)
    return argv[0], argv[1], float(argv[2])


def read_fk(path):
    """{frame: {joint: (x, y, z)}} from mostyle-cli fk's CSV."""
    frames = {}
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            frames.setdefault(int(row["frame"]), {})[row["joint"]] = (float(row["x"]), float(row["y"]), float(row["z"]))
    return frames


def import_file(path, fps):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    lower = path.lower()
    if lower.endswith(".fbx"):
        bpy.ops.import_scene.fbx(filepath=path)  # sets the scene's rate to the file's
    elif lower.endswith(".glb") or lower.endswith(".gltf"):
        # glTF states no rate: its importer keys at the scene's, which an animator sets first.
        scene = bpy.context.scene
        scene.render.fps = max(1, round(fps))
        scene.render.fps_base = scene.render.fps / fps
        bpy.ops.import_scene.gltf(filepath=path)
    else:
        raise ValueError("not a .fbx, .glb or .gltf file: " + path)


def umeyama(src, dst):
    """The similarity (s, R, t) taking src (n x 3) closest to dst (n x 3): dst ~ s R src + t."""
    mu_s, mu_d = src.mean(axis=0), dst.mean(axis=0)
    a, b = src - mu_s, dst - mu_d
    cov = b.T @ a / len(src)
    u, d, vt = np.linalg.svd(cov)
    sign = np.eye(3)
    if np.linalg.det(u) * np.linalg.det(vt) < 0:
        sign[2, 2] = -1
    rotation = u @ sign @ vt
    scale = np.trace(np.diag(d) @ sign) / (a ** 2).sum(axis=1).mean()
    return scale, rotation, mu_d - scale * rotation @ mu_s


def main():
    path, fk_path, fps = arguments()
    fk = read_fk(fk_path)
    try:
        import_file(path, fps)
    except Exception as e:  # the importer's own error, as one line
        print("blender_check: %s: Blender could not import it: %s" % (path, str(e).splitlines()[0] if str(e) else e))
        sys.exit(2)
    armatures = [o for o in bpy.data.objects if o.type == "ARMATURE"]
    actions = list(bpy.data.actions)
    others = sorted(set(o.type for o in bpy.data.objects if o.type != "ARMATURE"))
    summary = "%s: %d armature(s), %d action(s)" % (path, len(armatures), len(actions))
    if others:
        summary += ", other objects: " + ", ".join(others)
    if len(armatures) != 1 or len(actions) != 1:
        print(summary + ": expected one armature and one action")
        sys.exit(1)
    arm = armatures[0]
    action = actions[0]
    bone_curves = sum(1 for c in action.fcurves if c.data_path.startswith("pose.bones["))
    if arm.animation_data is None or arm.animation_data.action != action or bone_curves == 0:
        print(summary + ": the action is not the armature's, or keys no bone")
        sys.exit(1)
    scene = bpy.context.scene
    scene_fps = scene.render.fps / scene.render.fps_base
    start = min(c.keyframe_points[0].co.x for c in action.fcurves if len(c.keyframe_points))
    names = [b.name for b in arm.pose.bones if b.name in fk[min(fk)]]
    if not names:
        print(summary + ": no bone is named as a joint of the source")
        sys.exit(2)
    ours, theirs = [], []
    for f in sorted(fk):
        frame = start + f / fps * scene_fps
        whole = math.floor(frame)
        scene.frame_set(int(whole), subframe=frame - whole)
        for name in names:
            if name not in fk[f]:
                continue
            theirs.append(tuple(arm.matrix_world @ arm.pose.bones[name].head))
            ours.append(fk[f][name])
    ours, theirs = np.array(ours), np.array(theirs)
    first = np.array([fk[min(fk)][n] for n in fk[min(fk)]])
    height = first[:, 1].max() - first[:, 1].min()
    scale, rotation, translation = umeyama(theirs, ours)
    err = np.linalg.norm((scale * (rotation @ theirs.T)).T + translation - ours, axis=1) / height
    ok = err.mean() <= MEAN_BOUND and err.max() <= MAX_BOUND
    print("%s, %d bones (%d compared), %d frames at %g fps (Blender: %g fps, first key at frame %g), "
          "scale %.6g: mean %.3g, max %.3g of the height: %s"
          % (summary, len(arm.pose.bones), len(names), len(fk), fps, scene_fps, start, 1.0 / scale, err.mean(),
             err.max(), "ok" if ok else "TOO FAR"))
    sys.exit(0 if ok else 1)


main()
