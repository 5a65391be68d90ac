"""How long the Blender add-on's live preview takes from a weight change to the new pose: four
one-minute takes on armatures, a preview session over them, weights changed again and again.

usage: blender -b --factory-startup --python tests/bench/blender_preview_bench.py --
         --addon BLENDER_DIR --module DIR [--motions DIR] [--repeats N]

The takes are the four CMU walks (the shared motions', else assets/motions'), each played on to
one minute by repeating it from where its root ended. Prints, in milliseconds: reading the four
armatures' actions and the first change (which prepares the takes), once per set of takes; then
per weight change, as a median and the worst of N changes, its parts: the module's call on the
worker thread (and reading its arrays there), handing the result over, taking it up (posing the
armature's bones at the current frame), and Blender evaluating the new pose; then a frame change
with and without the preview (the bones posed from the result held), and the solved result once
the weights stay still. In Blender's UI the timer that takes results up looks every
preview._POLL_S on top.
"""
import argparse
import os
import statistics
import sys
import time

import bpy
import numpy as np

ONE_MINUTE_S = 60.0
# A weight change's parts, as change() times them.
PARTS = ("module's call, its arrays read (worker)", "result handed over", "take up and pose",
         "Blender evaluates the pose", "weight change to pose")


def arguments():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="blender_preview_bench.py")
    p.add_argument("--addon", required=True)
    p.add_argument("--module", default="")
    p.add_argument("--motions", default="")
    p.add_argument("--assets", default=os.path.join(os.path.dirname(__file__), "..", "..", "assets"))
    p.add_argument("--repeats", type=int, default=20)
    return p.parse_args(argv)


def one_minute(mostyle, take):
    """The take repeated to a minute, each repeat starting where the last one's root ended."""
    rotations = np.asarray(take.rotations)
    root = np.asarray(take.root_positions)
    fps = float(take.fps)
    need = int(ONE_MINUTE_S * fps)
    rows, roots, shift = [], [], np.zeros(3)
    step = root[-1] - root[0]
    step[1] = 0.0  # up stays up
    while sum(len(r) for r in rows) < need:
        rows.append(rotations)
        roots.append(root + shift)
        shift = shift + step
    return mostyle.Take(joint_names=take.joint_names, parents=take.parents, offsets=take.offsets,
                        rotations=np.concatenate(rows)[:need], root_positions=np.concatenate(roots)[:need], fps=fps)


def ms(seconds):
    return seconds * 1000.0


def report(label, values):
    print("blender_preview_bench: %-45s median %7.1f ms, worst %7.1f ms" % (label, ms(statistics.median(values)),
                                                                             ms(max(values))))


def change(session, scene, rng):
    """One weight change as the preview makes it, to the new pose evaluated: its parts' seconds."""
    asked = time.perf_counter()
    session.request(list(rng.dirichlet(np.ones(4))), None, 1.0)
    while session.busy():
        time.sleep(0.0002)
    ready = time.perf_counter()
    if not session.take_up(scene) or session.error:
        print("blender_preview_bench: the mix failed: %s" % session.error)
        os._exit(1)
    shown = time.perf_counter()
    bpy.context.view_layer.update()
    posed = time.perf_counter()
    call = session.shown.seconds
    return dict(zip(PARTS, (call, ready - asked - call, shown - ready, posed - shown, posed - asked)))


def frame_changes(scene, count):
    """The seconds of `count` frame changes, ten frames apart."""
    out = []
    for f in range(count):
        t = time.perf_counter()
        scene.frame_set(scene.frame_start + 10 * (f + 1))
        out.append(time.perf_counter() - t)
    return out


def main():
    args = arguments()
    if args.module:
        sys.path.insert(0, args.module)
    sys.path.insert(0, args.addon)
    import mostyle
    import mostyle_blender
    from mostyle_blender import importer, preview, takes as take_io
    mostyle_blender.register()
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.fps, scene.render.fps_base = 30, 1.0
    folder = args.motions if args.motions and os.path.isdir(args.motions) else os.path.join(args.assets, "motions")
    names = ["cmu142_walk_%s.bvh" % s for s in ("happy", "joy", "clumsy", "marching")]
    refs = []
    for n in names:
        take = one_minute(mostyle, mostyle.read(os.path.join(folder, n)))
        obj = importer.build_armature(bpy.context, take, n[:-4])
        action = bpy.data.actions.new(n[:-4])
        take_io.write_take_action(take, obj, action, 1, 30.0)
        obj.animation_data_create().action = action
        refs.append((obj, action))
    print("blender_preview_bench: %s, 4 takes of %.0f s at their own rate, mixed at 30 fps" % (folder, ONE_MINUTE_S))
    playing = frame_changes(scene, args.repeats)
    t = time.perf_counter()
    session = preview.Session(mostyle, refs[0][0], refs[0][1], refs, None, 'MIX', 30.0)
    read_s = time.perf_counter() - t
    preview.run(session)
    rng = np.random.default_rng(1)
    t = time.perf_counter()
    change(session, scene, rng)
    report("reading the armatures' actions (once)", [read_s])
    report("first change, preparing the takes (once)", [time.perf_counter() - t])
    parts = {name: [] for name in PARTS}
    for _ in range(args.repeats):
        for name, seconds in change(session, scene, rng).items():
            parts[name].append(seconds)
    for name, values in parts.items():
        report(name, values)
    report("frame change, the reference playing its action", playing)
    while not session.settled():  # the solve would run beside the frame changes
        time.sleep(0.001)
    session.take_up(scene)
    report("frame change while previewing", frame_changes(scene, args.repeats))
    solved, solve_call = [], []
    for _ in range(max(3, args.repeats // 4)):
        asked = time.perf_counter()
        session.request(list(rng.dirichlet(np.ones(4))), None, 1.0)
        while not session.settled():
            time.sleep(0.0005)
        session.take_up(scene)
        bpy.context.view_layer.update()
        solved.append(time.perf_counter() - asked)
        solve_call.append(session.shown.seconds)
    report("solved result shown (settle %.0f ms)" % ms(preview._SETTLE_S), solved)
    report("the solving call", solve_call)
    preview.stop()
    sys.stdout.flush()
    os._exit(0)


main()
