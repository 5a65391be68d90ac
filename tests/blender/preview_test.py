"""The add-on's live preview in Blender: after a weight change the reference armature, posed by the
preview at a few frames, stands where the module's mix (or transfer) of the same takes at those
weights puts its joints; no action is made or changed while it previews, and once it stops the
armature is posed as before.

usage: blender -b --factory-startup --python tests/blender/preview_test.py -- CASE
         --addon BLENDER_DIR [--module DIR] [--assets DIR]

CASE:
  mix       two CMU walks (assets/motions) mixed, the weights moved on the panel's sliders
  transfer  the joy walk's style onto the happy walk (its own neutral), the strength moved
Both the quick result (the mix's positions on the reference's own rotations) and the solved one
that replaces it once the weights stay still are checked. Background Blender runs no timers:
the test calls the preview's timer function itself, as Blender's UI would.
Exit status 0: passed; 1: failed; 77: skipped (no module), saying why.
"""
import argparse
import os
import sys
import time

import bpy
import numpy as np

SKIP = 77
# As style_action_test.py: Blender keeps bone matrices in float32.
MAX_ERROR_HEIGHTS = 1e-3
# How long a result may take on a busy machine before the test gives up.
WAIT_S = 120.0


def arguments():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="preview_test.py")
    p.add_argument("case", choices=["mix", "transfer"])
    p.add_argument("--addon", required=True)
    p.add_argument("--module", default="")
    p.add_argument("--assets", default=os.path.join(os.path.dirname(__file__), "..", "..", "assets"))
    return p.parse_args(argv)


def finish(status, text):
    print("preview_test: " + text)
    sys.stdout.flush()
    os._exit(status)


def fail(why):
    finish(1, "FAILED: " + why)


def load_addon(args):
    if args.module:
        sys.path.insert(0, args.module)
    try:
        import mostyle
    except ImportError as e:
        finish(SKIP, "SKIPPED: the mostyle Python module is not built (%s)" % e)
    sys.path.insert(0, args.addon)
    import mostyle_blender
    mostyle_blender.register()
    return mostyle


def import_take(path):
    before = set(bpy.data.objects)
    bpy.ops.mostyle.import_take(filepath=path)
    return next(o for o in bpy.data.objects if o not in before and o.type == 'ARMATURE')


def action_curves(action):
    from mostyle_blender import action_curves as curves  # the add-on's, for every Blender's API
    return curves.curves(action)


def action_keys():
    """Every action's keys, by action name."""
    return {a.name: {(c.data_path, c.array_index): [tuple(k.co) for k in c.keyframe_points] for c in action_curves(a)}
            for a in bpy.data.actions}


def wait_until(done, what):
    from mostyle_blender import preview
    end = time.perf_counter() + WAIT_S
    while not done():
        if time.perf_counter() > end:
            fail("no %s within %.0f s" % (what, WAIT_S))
        time.sleep(0.002)
    preview._tick()  # what Blender's timer does
    if preview.status()["error"]:
        fail("the preview reports: %s" % preview.status()["error"])


def posed_heads(obj, joints, frame):
    """World heads of obj's bones named `joints` (joints, 3), Y up, at `frame` as Blender shows it."""
    bpy.context.scene.frame_set(frame)
    world = obj.matrix_world
    out = np.empty((len(joints), 3))
    for j, name in enumerate(joints):
        p = world @ obj.pose.bones[name].head
        out[j] = (p.x, p.z, -p.y)
    return out


def check_frames(stage, obj, expected, frame_start):
    """The armature at its first, a middle and its last frame, and past its end (where the last
    holds), against the module's result positions."""
    positions = np.asarray(expected.positions)
    joints = list(expected.position_joints)
    height = float(np.ptp(positions[0, :, 1]))
    last = len(positions) - 1
    worst = 0.0
    for index, frame in ((0, 0), (last // 2, last // 2), (last, last), (last, last + 5)):
        error = np.linalg.norm(posed_heads(obj, joints, int(frame_start) + frame) - positions[index], axis=-1) / height
        worst = max(worst, float(error.max()))
        if error.max() > MAX_ERROR_HEIGHTS:
            fail("%s: at frame %d %s is %.4f body heights from the module's result"
                 % (stage, frame, joints[int(np.argmax(error))], error.max()))
    print("preview_test: %s: max error %.2e body heights at 4 frames" % (stage, worst))


def main():
    args = arguments()
    mostyle = load_addon(args)
    from mostyle_blender import preview, takes as take_io
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.fps, scene.render.fps_base = 30, 1.0
    paths = [os.path.join(args.assets, "motions", "cmu142_walk_%s.bvh" % s) for s in ("happy", "joy")]
    ref, other = (import_take(p) for p in paths)
    source = ref.animation_data.action
    # A bone the reference's action does not key, posed by hand: the preview poses it too, and
    # gives the hand's pose back when it stops.
    for curve in [c for c in action_curves(source) if c.data_path.startswith('pose.bones["LeftForeArm"]')]:
        action_curves(source).remove(curve)
    ref.pose.bones["LeftForeArm"].rotation_quaternion = (0.9, 0.1, 0.3, 0.0)
    bpy.context.view_layer.objects.active = ref
    settings = ref.mostyle
    settings.mode = 'MIX' if args.case == "mix" else 'TRANSFER'
    for obj in (ref, other):
        t = settings.takes.add()
        t.object, t.action = obj, obj.animation_data.action
    before = action_keys()
    takes = [take_io.armature_take(mostyle, t.object, t.action) for t in settings.takes]
    played = posed_heads(ref, [b.name for b in ref.pose.bones], 40)

    def expected(weights, strength):
        if args.case == "mix":
            return mostyle.mix(takes, weights=weights, fps=30.0)
        return mostyle.transfer(takes[0], takes[1], strength=strength * weights[1], fps=30.0)

    def move(weights, strength):
        for t, w in zip(settings.takes, weights):
            t.weight = w
        settings.strength = strength
        wait_until(lambda: not preview.session().busy(), "quick result")
        if ref.animation_data.action is not None:
            fail("the reference armature plays action '%s' while previewing" % ref.animation_data.action.name)
        result = expected(weights, strength)
        check_frames("weights %s, quick result" % weights, ref, result, source.frame_range[0])
        wait_until(lambda: preview.session().settled(), "solved result")
        if not preview.session().shown.solved:
            fail("the result shown once the weights stayed still is not the solved one")
        check_frames("weights %s, solved result" % weights, ref, result, source.frame_range[0])

    settings.use_preview = True
    move([0.5, 0.5], 1.0)
    move([0.2, 0.8], 0.7)
    after = action_keys()
    if after != before:
        made = sorted(set(after) ^ set(before))
        fail("the preview made or changed an action: %s" % (", ".join(made) if made else "keys changed"))
    settings.use_preview = False
    if ref.animation_data.action != source:
        fail("the reference armature does not play '%s' again once the preview is off" % source.name)
    moved = np.max(np.abs(posed_heads(ref, [b.name for b in ref.pose.bones], 40) - played))
    if moved > 1e-6:
        fail("once the preview is off the armature is %.3g from where its action posed it" % moved)
    if bpy.app.handlers.frame_change_pre:
        fail("the preview left a frame change handler behind")
    finish(0, "%s passed" % args.case)


try:
    main()
except SystemExit:
    raise
except Exception:
    import traceback
    traceback.print_exc()
    fail("an exception")
