"""How long the Blender add-on's live preview takes from a weight change to the new pose: four
one-minute takes on armatures, a preview session over them, weights changed again and again.

usage: blender -b --factory-startup --python tests/bench/blender_preview_bench.py --
         --addon BLENDER_DIR --module DIR [--motions DIR] [--repeats N]

The takes are the four CMU walks (the shared motions', else assets/motions'), each played on to
one minute by repeating it from where its root ended. Prints, in milliseconds: reading the four
armatures' actions (once per set of takes), then per weight change the module's call on the
worker thread, writing its result into the preview action, and Blender posing the armature at a
frame, each as a median and the worst of N changes.
"""
import argparse
import os
import statistics
import sys
import time

import bpy
import numpy as np

ONE_MINUTE_S = 60.0


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
        obj.animation_data_create().action = action
        take_io.write_take_action(take, obj, action, 1, 30.0)
        refs.append((obj, action))
    t = time.perf_counter()
    session = preview.Session(mostyle, refs[0][0], refs[0][1], refs, None, 'MIX', 30.0)
    read_s = time.perf_counter() - t
    print("blender_preview_bench: %s, 4 takes of %.0f s at their own rate, mixed at 30 fps; reading the armatures' actions: %.0f ms (once per set of takes)"
          % (folder, ONE_MINUTE_S, ms(read_s)))
    module_s, write_s, pose_s, total_s = [], [], [], []
    rng = np.random.default_rng(1)
    for _ in range(args.repeats):
        w = rng.dirichlet(np.ones(4))
        asked = time.perf_counter()
        session.request(list(w), None, 1.0)
        while session.busy():
            time.sleep(0.0005)
        computed = time.perf_counter()
        error = session.take_up()
        if error:
            print("blender_preview_bench: the mix failed: " + error)
            os._exit(1)
        written = time.perf_counter()
        scene.frame_set(scene.frame_current)
        posed = time.perf_counter()
        module_s.append(computed - asked)
        write_s.append(written - computed)
        pose_s.append(posed - written)
        total_s.append(posed - asked)
    session.stop()
    how = "prepared handle (mostyle.prepare)" if hasattr(mostyle, "prepare") else "whole mostyle.mix calls"
    for label, values in (("module (%s)" % how, module_s), ("write the preview action", write_s),
                          ("pose at a frame", pose_s), ("weight change to pose", total_s)):
        print("blender_preview_bench: %-45s median %7.1f ms, worst %7.1f ms"
              % (label, ms(statistics.median(values)), ms(max(values))))
    sys.stdout.flush()
    os._exit(0)


main()
