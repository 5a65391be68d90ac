"""Timing is part of style: a take that limps (a long step, then a short one) gives its own step
period at weight 1, whichever walk is the reference.

The limp is made from a bundled walk by slowing every other step (no limping take is published
with the data); it is passed in as arrays, as a caller holding animation in memory would.
"""
import numpy as np

import mostyle
from test_module import asset

# Every other step plays this many times slower.
LIMP_STRETCH = 1.5
# A period read from the output's strikes is within this fraction of the one it should have: a
# cycle is whole frames at the working rate, and the clean-up moves a strike by a frame or so.
PERIOD_TOLERANCE = 0.08


def retimed(take, source_frames):
    """take played at the (fractional, increasing) source frames: root positions linear,
    rotations normalized linear (neighbouring frames at 120 fps are close)."""
    i = np.minimum(np.floor(source_frames).astype(int), take.rotations.shape[0] - 2)
    u = (source_frames - i)[:, None]
    root = take.root_positions[i] * (1 - u) + take.root_positions[i + 1] * u
    q0, q1 = take.rotations[i], take.rotations[i + 1]
    q1 = np.where((np.sum(q0 * q1, axis=2) < 0)[:, :, None], -q1, q1)
    q = q0 * (1 - u[:, :, None]) + q1 * u[:, :, None]
    q /= np.linalg.norm(q, axis=2, keepdims=True)
    return mostyle.Take(joint_names=list(take.joint_names), parents=list(take.parents), offsets=take.offsets,
                        rotations=q, root_positions=root, fps=take.fps)


def limp_frames(cycles, frames):
    """Source frames of the limp: every cycle's second half LIMP_STRETCH times as many frames."""
    knots_t, knots_f, t, last = [0.0], [0.0], 0.0, 0
    for c in cycles:
        s, e = c["start"], c["end"]
        m = (s + e) / 2
        for a, b, k in ((last, s, 1.0), (s, m, 1.0), (m, e, LIMP_STRETCH)):
            if b > a:
                t += (b - a) * k
                knots_t.append(t)
                knots_f.append(b)
        last = e
    if frames - 1 > last:
        knots_t.append(t + frames - 1 - last)
        knots_f.append(frames - 1)
    return np.interp(np.arange(int(knots_t[-1]) + 1), knots_t, knots_f)


def period(take, tmp_path, name):
    path = tmp_path / f"{name}.bvh"
    take.write(str(path))
    return mostyle.info(str(path))["cycles"]["period_s"]


def test_a_limp_keeps_its_step_period_at_weight_1(tmp_path):
    walk = mostyle.read(asset("cmu142_walk_marching.bvh"))
    cycles = mostyle.info(asset("cmu142_walk_marching.bvh"))["cycles"]["cycles"]
    limp = retimed(walk, limp_frames(cycles, walk.rotations.shape[0]))
    limp_period = period(limp, tmp_path, "limp")
    walk_period = mostyle.info(asset("cmu142_walk_marching.bvh"))["cycles"]["period_s"]
    # The limp is slower by half of every other step: a quarter longer cycles.
    assert limp_period > 1.15 * walk_period
    for reference in ("cmu142_walk_marching.bvh", "cmu142_walk_clumsy.bvh"):
        a = mostyle.read(asset(reference))
        at_1 = mostyle.blend(a, limp, alpha=1.0)
        assert abs(period(at_1, tmp_path, "at_1") - limp_period) <= PERIOD_TOLERANCE * limp_period, reference
        at_0 = mostyle.blend(a, limp, alpha=0.0)
        a_period = mostyle.info(asset(reference))["cycles"]["period_s"]
        assert abs(period(at_0, tmp_path, "at_0") - a_period) <= PERIOD_TOLERANCE * a_period, reference
