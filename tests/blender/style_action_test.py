"""The mostyle add-on in Blender against mostyle-cli: takes imported into Blender are styled with
bpy.ops.mostyle.style_action, the styled action is played by Blender, and its bones' heads are
compared with mostyle-cli's --positions-out of the same files.

usage: blender -b --factory-startup --python tests/blender/style_action_test.py -- CASE
         --cli MOSTYLE_CLI --addon BLENDER_DIR [--module DIR] [--motions DIR] [--assets DIR]

CASE:
  bvh_pair  two CMU walks of one skeleton (assets/motions), read by the add-on's importer, mixed
  fbx_gltf  a Mixamo FBX walk (Blender's FBX importer) mixed with a CMU glTF clip (Blender's glTF
            importer): two skeletons
  transfer  the CMU joy walk's change from the CMU happy walk onto an Aalto walk (another rig)
  action    actions, not walks: a good-bye mixed with its active style, then the active wave's
            change from the normal wave put on the good-bye (a style across actions)
--addon is the folder holding mostyle_blender; --module the folder holding the mostyle module
(a build's python/); --motions the shared motions, or MOSTYLE_SHARED_MOTIONS_DIR when set
(fbx_gltf, transfer and action skip without them).
Exit status 0: passed; 1: failed; 77: skipped (no module, or no shared motions), saying why.
"""
import argparse
import csv
import os
import subprocess
import sys
import tempfile

import bpy
import numpy as np

SKIP = 77
# The styled action, played by Blender, against the CLI's positions: Blender keeps keys and bone
# matrices in float32, and the takes it reads are sampled at the scene's frames.
MAX_ERROR_HEIGHTS = 1e-3


def arguments():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="style_action_test.py")
    p.add_argument("case", choices=["bvh_pair", "fbx_gltf", "transfer", "action"])
    p.add_argument("--cli", required=True)
    p.add_argument("--addon", required=True)
    p.add_argument("--module", default="")
    p.add_argument("--motions", default="")
    p.add_argument("--assets", default="")
    args = p.parse_args(argv)
    # As the C++ tests do: CI names a folder that does not exist, to run as a clone alone.
    if os.environ.get("MOSTYLE_SHARED_MOTIONS_DIR") is not None:
        args.motions = os.environ["MOSTYLE_SHARED_MOTIONS_DIR"]
    return args


def skip(why):
    print("style_action_test: SKIPPED: " + why)
    sys.stdout.flush()
    os._exit(SKIP)


def fail(why):
    print("style_action_test: FAILED: " + why)
    sys.stdout.flush()
    os._exit(1)


def load_addon(args):
    if args.module:
        sys.path.insert(0, args.module)
    try:
        import mostyle  # noqa: F401
    except ImportError as e:
        skip("the mostyle Python module is not built (%s)" % e)
    sys.path.insert(0, args.addon)
    import mostyle_blender
    mostyle_blender.register()
    return mostyle_blender


def fresh_scene(fps):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.fps, scene.render.fps_base = fps, 1.0
    return scene


def import_with_mostyle(path):
    before = set(bpy.data.objects)
    bpy.ops.mostyle.import_take(filepath=path)
    return next(o for o in bpy.data.objects if o not in before and o.type == 'ARMATURE')


def import_with_blender(path):
    before = set(bpy.data.objects)
    if path.lower().endswith(".fbx"):
        bpy.ops.import_scene.fbx(filepath=path)
    else:
        if not hasattr(np, "bool"):  # Debian's Blender 3.4 glTF importer asks numpy for numpy.bool
            np.bool = bool
        bpy.ops.import_scene.gltf(filepath=path)
    return next(o for o in bpy.data.objects if o not in before and o.type == 'ARMATURE')


def cli_positions(cli, args):
    """mostyle-cli's --positions-out: joint names, (frames, joints, 3) in the reference's units."""
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "positions.csv")
        run = subprocess.run([cli] + args + ["--positions-out", out], capture_output=True, text=True)
        if run.returncode != 0:
            fail("mostyle-cli %s: %s" % (" ".join(args), run.stderr.strip()))
        rows = list(csv.reader(open(out)))[1:]
    joints = list(dict.fromkeys(r[1] for r in rows))
    values = np.array([[float(v) for v in r[2:]] for r in rows]).reshape(-1, len(joints), 3)
    return joints, values


def played_heads(obj, joints, frame_start, count):
    """World heads of obj's bones named `joints`, (count, joints, 3), Y up, as Blender plays it."""
    scene = bpy.context.scene
    out = np.empty((count, len(joints), 3))
    for f in range(count):
        scene.frame_set(int(frame_start) + f)
        world = obj.matrix_world
        for j, name in enumerate(joints):
            p = world @ obj.pose.bones[name].head
            out[f, j] = (p.x, p.z, -p.y)
    return out


def compare(name, blender, cli, scale_known=None):
    """Max distance per joint and frame, in body heights (the CLI's first frame's height). The
    file's units are Blender's times `scale_known` (FBX: the armature's unit scale), else the
    least-squares scale."""
    if blender.shape != cli.shape:
        fail("%s: Blender plays %d frames of %d joints, the CLI wrote %d of %d"
             % (name, blender.shape[0], blender.shape[1], cli.shape[0], cli.shape[1]))
    scale = scale_known if scale_known else float(np.sum(blender * cli) / np.sum(blender * blender))
    height = float(np.ptp(cli[0, :, 1]))
    error = np.linalg.norm(blender * scale - cli, axis=-1) / height
    worst = np.unravel_index(np.argmax(error), error.shape)
    print("style_action_test: %s: %d frames, max error %.2e body heights (mean %.2e) at frame %d, "
          "scale %.6g" % (name, cli.shape[0], error.max(), error.mean(), worst[0], scale))
    if error.max() > MAX_ERROR_HEIGHTS:
        fail("%s: the styled action is %.4f body heights from mostyle-cli's positions at frame %d"
             % (name, error.max(), worst[0]))


def action_curves(action):
    from mostyle_blender import action_curves as curves  # the add-on's, for every Blender's API
    return curves.curves(action)


def action_keys(action):
    return {(c.data_path, c.array_index): [tuple(k.co) for k in c.keyframe_points] for c in action_curves(action)}


def check_operator(obj, source, originals, frames):
    """The styled action is new, named after the reference's, on its armature, keyed on every
    frame; the originals' keys are unchanged."""
    styled = obj.animation_data.action
    if styled is None or styled.name != source.name + "_styled":
        fail("the reference armature plays %s, not %s_styled" % (styled and styled.name, source.name))
    for curve in action_curves(styled):
        keys = [k.co.x for k in curve.keyframe_points]
        if len(keys) != frames or any(abs(b - a - 1) > 1e-4 for a, b in zip(keys, keys[1:])):
            fail("%s[%d] is not keyed on each of %d frames" % (curve.data_path, curve.array_index, frames))
    for action, keys in originals.items():
        if action_keys(action) != keys:
            fail("action '%s' changed" % action.name)


def check_bad_input():
    """Bad input cancels with one line in the status bar."""
    try:
        bpy.ops.mostyle.style_action(takes="NoSuchArmature,Other", weights="0.5,0.5")
    except RuntimeError as e:
        text = str(e).strip()
        if "NoSuchArmature" not in text or len(text.replace("Error: ", "").strip().splitlines()) != 1:
            fail("a missing armature's error is not one line naming it: %r" % text)
        return
    fail("a missing armature was not refused")


def style_and_compare(name, takes, kwargs, cli, cli_args, scale_known=None):
    obj, source = takes[0]
    originals = {a: action_keys(a) for _, a in takes}
    take_text = ",".join("%s:%s" % (o.name, a.name) for o, a in takes)
    result = bpy.ops.mostyle.style_action(takes=take_text, **kwargs)
    if result != {'FINISHED'}:
        fail("%s: style_action returned %s" % (name, result))
    joints, expected = cli_positions(cli, cli_args)
    check_operator(obj, source, originals, len(expected))
    compare(name, played_heads(obj, joints, source.frame_range[0], len(expected)), expected, scale_known)


def case_bvh_pair(args):
    assets = os.path.join(args.assets, "motions")
    happy, joy = (os.path.join(assets, "cmu142_walk_%s.bvh" % s) for s in ("happy", "joy"))
    fresh_scene(30)
    a, b = import_with_mostyle(happy), import_with_mostyle(joy)
    takes = [(a, a.animation_data.action), (b, b.animation_data.action)]
    style_and_compare("bvh_pair", takes, {"weights": "0.3,0.7", "mode": 'MIX'}, args.cli,
                      ["mix", happy, joy, "--weights", "0.3,0.7", "--fps", "30"], scale_known=1.0)
    check_bad_input()


def need_motions(args, *names):
    paths = [os.path.join(args.motions, n) for n in names]
    missing = [p for p in paths if not os.path.exists(p)]
    if not args.motions or missing:
        skip("the shared motions are absent (%s)" % (missing[0] if missing else "no --motions"))
    return paths


def case_fbx_gltf(args):
    fbx, glb = need_motions(args, "wild/fbx_mixamo_walking.fbx", "formats/cmu142_walks_30fps.glb")
    fresh_scene(30)
    mixamo = import_with_blender(fbx)
    cmu = import_with_blender(glb)
    joy = next(a for a in bpy.data.actions if a.name.startswith("cmu142_walk_joy"))
    takes = [(mixamo, mixamo.animation_data.action), (cmu, joy)]
    style_and_compare("fbx_gltf", takes, {"weights": "0.6,0.4", "mode": 'MIX'}, args.cli,
                      ["mix", fbx, glb + "#cmu142_walk_joy", "--weights", "0.6,0.4", "--fps", "30"],
                      scale_known=1.0 / mixamo.matrix_world.to_scale()[0])


def case_transfer(args):
    content, style, neutral = need_motions(args, "wild/aalto_k_walk_slow.bvh", "cmu142_walk_joy.bvh",
                                           "cmu142_walk_happy.bvh")
    fresh_scene(30)
    c, s, n = (import_with_mostyle(p) for p in (content, style, neutral))
    takes = [(c, c.animation_data.action), (s, s.animation_data.action)]
    kwargs = {"mode": 'TRANSFER', "neutral": n.name, "strength": 0.8}
    style_and_compare("transfer", takes, kwargs, args.cli,
                      ["transfer", content, "--style", style, "--neutral", neutral, "--strength", "0.8",
                       "--fps", "30"], scale_known=1.0)


def case_action(args):
    bye, bye_active, wave, wave_active = need_motions(
        args, "actions/bandai_bye_normal.bvh", "actions/bandai_bye_active.bvh",
        "actions/bandai2_wave-left-hand_normal.bvh", "actions/bandai2_wave-left-hand_active.bvh")
    fresh_scene(30)
    b, ba, w, wa = (import_with_mostyle(p) for p in (bye, bye_active, wave, wave_active))
    style_and_compare("action mix", [(b, b.animation_data.action), (ba, ba.animation_data.action)],
                      {"weights": "0.4,0.6", "mode": 'MIX'}, args.cli,
                      ["mix", bye, bye_active, "--weights", "0.4,0.6", "--fps", "30"], scale_known=1.0)
    # The good-bye's styled action is the reference's now: style its source action again.
    source = bpy.data.actions[b.animation_data.action.name[:-len("_styled")]]
    b.animation_data.action = source
    style_and_compare("action transfer", [(b, source), (wa, wa.animation_data.action)],
                      {"mode": 'TRANSFER', "neutral": w.name, "strength": 1.0}, args.cli,
                      ["transfer", bye, "--style", wave_active, "--neutral", wave, "--strength", "1",
                       "--fps", "30"], scale_known=1.0)


def main():
    args = arguments()
    load_addon(args)
    try:
        {"bvh_pair": case_bvh_pair, "fbx_gltf": case_fbx_gltf, "transfer": case_transfer,
         "action": case_action}[args.case](args)
    except SystemExit:
        raise
    except Exception:
        import traceback
        traceback.print_exc()
        fail("an exception")
    print("style_action_test: %s passed" % args.case)
    sys.stdout.flush()
    os._exit(0)


main()
