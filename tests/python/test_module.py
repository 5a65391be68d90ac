"""The Python module against mostyle-cli: the same takes and options give the same result.

Run by ctest (python:module) with PYTHONPATH at build/python and MOSTYLE_CLI naming the built
mostyle-cli. Tests on ../shared/motions skip, saying so, when it is absent (MOSTYLE_SHARED_MOTIONS_DIR
names another folder); the walks in assets/ are always there.
"""
import csv
import json
import os
import pathlib
import subprocess
import threading

import numpy as np
import pytest

import mostyle

ROOT = pathlib.Path(__file__).resolve().parents[2]
ASSETS = ROOT / "assets" / "motions"
SHARED = pathlib.Path(os.environ.get("MOSTYLE_SHARED_MOTIONS_DIR", ROOT.parent / "shared" / "motions"))
CLI = os.environ.get("MOSTYLE_CLI", str(ROOT / "build" / "app" / "mostyle-cli"))

# Results equal the CLI's to this, file units: both run one code path, so any difference is a
# different input, not rounding.
SAME = 1e-9
# A take rebuilt from its arrays has other Euler channels (ZXY, angles from quaternions): its
# joints land within rounding of the file's, and so does what is made of it.
REBUILT = 1e-9


def asset(name):
    return str(ASSETS / name)


def shared(name):
    path = SHARED / name
    if not SHARED.is_dir():
        pytest.skip(f"{SHARED} is absent (tests use assets/ instead)")
    if not path.exists():
        pytest.skip(f"{path} is absent")
    return str(path)


def run_cli(args, tmp_path):
    """Runs mostyle-cli with --positions-out, --report and --out; returns (positions, report, out bytes)."""
    positions_csv, report, out = tmp_path / "cli.csv", tmp_path / "cli.json", tmp_path / "cli.bvh"
    subprocess.run([CLI, *args, "--positions-out", str(positions_csv), "--report", str(report), "--out", str(out)],
                   check=True, capture_output=True)
    return read_positions(positions_csv), json.loads(report.read_text()), out.read_bytes()


def read_positions(path):
    """A --positions-out CSV as frames x joints x 3."""
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    frames = int(rows[-1]["frame"]) + 1
    values = np.array([[float(r["x"]), float(r["y"]), float(r["z"])] for r in rows])
    return values.reshape(frames, -1, 3)


def without_timings(report):
    report = dict(report)
    report.pop("timings_ms")
    return report


def assert_same_as_cli(result, cli, tmp_path):
    positions, report, out = cli
    assert result.positions.shape == positions.shape
    assert np.max(np.abs(result.positions - positions)) <= SAME
    assert without_timings(result.report) == without_timings(report)
    assert result.position_joints == report["joints"]
    written = tmp_path / "module.bvh"
    result.write(str(written))
    assert written.read_bytes() == out



def assert_same_in_threads(make, inputs):
    """make(x) for every input, one thread each at once, equals make(x) called one at a time."""
    alone = [make(x) for x in inputs]
    together = [None] * len(inputs)

    def run(i):
        together[i] = make(inputs[i])

    threads = [threading.Thread(target=run, args=(i,)) for i in range(len(inputs))]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for x, y in zip(alone, together):
        assert np.array_equal(x, y)

def test_read_gives_a_take_with_its_arrays():
    take = mostyle.read(asset("cmu142_walk_happy.bvh"))
    joints = len(take.joint_names)
    assert take.fps == pytest.approx(120.0)
    assert take.frames > 0
    assert take.parents.shape == (joints,) and take.parents[0] == -1
    assert take.offsets.shape == (joints, 3)
    assert take.rotations.shape == (take.frames, joints, 4)
    assert np.allclose(np.linalg.norm(take.rotations, axis=2), 1.0)
    assert take.root_positions.shape == (take.frames, 3)
    assert take.positions.shape == (take.frames, joints, 3)
    assert take.report is None
    assert take.source == asset("cmu142_walk_happy.bvh")


def test_blend_equals_the_cli(tmp_path):
    a, b = asset("cmu142_walk_happy.bvh"), asset("cmu142_walk_marching.bvh")
    cli = run_cli(["blend", a, b, "--alpha", "0.3", "--timing", "a", "--no-foot-lock"], tmp_path)
    result = mostyle.blend(a, b, alpha=0.3, timing="a", foot_lock=False)
    assert_same_as_cli(result, cli, tmp_path)


def test_blend_of_read_takes_equals_the_cli(tmp_path):
    a, b = asset("cmu142_walk_joy.bvh"), asset("cmu142_walk_clumsy.bvh")
    cli = run_cli(["blend", a, b, "-k", "6", "--part-alpha", "legs:0.8", "--alpha", "0.4"], tmp_path)
    result = mostyle.blend(mostyle.read(a), mostyle.read(b), 0.4, k=6, part_alpha={"legs": 0.8})
    assert_same_as_cli(result, cli, tmp_path)


def test_mix_equals_the_cli(tmp_path):
    takes = [asset("cmu142_walk_happy.bvh"), asset("cmu142_walk_joy.bvh"), asset("cmu142_walk_clumsy.bvh")]
    cli = run_cli(["mix", *takes, "--weights", "0.5,0.3,0.2", "--part-weights", "arms:0.2,0.4,0.4"], tmp_path)
    result = mostyle.mix(takes, weights=[0.5, 0.3, 0.2], part_weights={"arms": [0.2, 0.4, 0.4]})
    assert_same_as_cli(result, cli, tmp_path)


def test_mix_with_keys_equals_the_cli(tmp_path):
    takes = [asset("cmu142_walk_happy.bvh"), asset("cmu142_walk_marching.bvh")]
    cli = run_cli(["mix", *takes, "--weights-at", "0:1,0;4:0,1", "--timing", "reference"], tmp_path)
    result = mostyle.mix(takes, weights_at={0: [1, 0], 4: [0, 1]}, timing="reference")
    assert_same_as_cli(result, cli, tmp_path)


def test_transfer_equals_the_cli(tmp_path):
    content, style = asset("cmu142_walk_happy.bvh"), asset("cmu142_walk_marching.bvh")
    cli = run_cli(["transfer", content, "--style", style, "--strength", "0.7"], tmp_path)
    result = mostyle.transfer(content, style, strength=0.7)
    assert_same_as_cli(result, cli, tmp_path)


def test_transfer_of_two_styles_from_a_neutral_equals_the_cli(tmp_path):
    content, neutral = asset("cmu142_walk_happy.bvh"), asset("cmu142_walk_clumsy.bvh")
    styles = [asset("cmu142_walk_marching.bvh"), asset("cmu142_walk_joy.bvh")]
    cli = run_cli(["transfer", content, "--neutral", neutral, "--style", styles[0], "--style", styles[1],
                   "--strength", "0.5,1/4", "--timing", "mix"], tmp_path)
    result = mostyle.transfer(content, styles, neutral=neutral, strength=[0.5, 0.25], timing="mix")
    assert_same_as_cli(result, cli, tmp_path)


def test_shared_walks_equal_the_cli(tmp_path):
    takes = [shared("bandai_walk_happy.bvh"), shared("bandai_walk_sad.bvh"), shared("bandai_walk_old.bvh")]
    cli = run_cli(["mix", *takes, "--weights", "0.5,0.3,0.2"], tmp_path)
    assert_same_as_cli(mostyle.mix(takes, [0.5, 0.3, 0.2]), cli, tmp_path)
    cli = run_cli(["transfer", shared("bandai_walk_normal.bvh"), "--style", shared("bandai_walk_angry.bvh"),
                   "--neutral", shared("bandai_walk_tired.bvh"), "--strength", "0.8"], tmp_path)
    result = mostyle.transfer(shared("bandai_walk_normal.bvh"), shared("bandai_walk_angry.bvh"),
                              neutral=shared("bandai_walk_tired.bvh"), strength=0.8)
    assert_same_as_cli(result, cli, tmp_path)


def test_an_animation_of_a_gltf_file_equals_the_cli(tmp_path):
    glb = shared("formats/cmu142_walks_30fps.glb")
    a, b = glb + "#cmu142_walk_happy", glb + "#cmu142_walk_joy"
    cli = run_cli(["blend", a, b], tmp_path)
    assert_same_as_cli(mostyle.blend(a, mostyle.read(glb, take="cmu142_walk_joy")), cli, tmp_path)


def test_info_equals_the_cli():
    for path in [asset("cmu142_walk_happy.bvh")]:
        printed = subprocess.run([CLI, "info", "--json", path], check=True, capture_output=True, text=True).stdout
        assert mostyle.info(path) == json.loads(printed)


def arrays_of(take, translations=False):
    arrays = dict(joint_names=take.joint_names, parents=take.parents, offsets=take.offsets,
                  rotations=take.rotations, root_positions=take.root_positions, fps=take.fps)
    if translations:
        arrays["translations"] = take.translations
    return arrays


def test_a_take_from_arrays_gives_its_arrays_back():
    read = mostyle.read(asset("cmu142_walk_joy.bvh"))
    rebuilt = mostyle.Take(**arrays_of(read))
    assert rebuilt.joint_names == read.joint_names
    assert np.array_equal(rebuilt.parents, read.parents)
    assert np.array_equal(rebuilt.offsets, read.offsets)
    assert np.array_equal(rebuilt.root_positions, read.root_positions)
    # The same rotations, each quaternion up to its sign.
    dots = np.abs(np.sum(rebuilt.rotations * read.rotations, axis=2))
    assert np.max(np.abs(dots - 1.0)) <= REBUILT
    assert np.max(np.abs(rebuilt.positions - read.positions)) <= REBUILT


def test_a_take_from_arrays_blends_as_its_file():
    a, b = mostyle.read(asset("cmu142_walk_happy.bvh")), asset("cmu142_walk_marching.bvh")
    from_file = mostyle.blend(a, b, 0.6)
    from_arrays = mostyle.blend(mostyle.Take(**arrays_of(a)), b, 0.6)
    assert from_arrays.positions.shape == from_file.positions.shape
    assert np.max(np.abs(from_arrays.positions - from_file.positions)) <= REBUILT


def test_hips_that_move_below_a_still_root_come_through_translations():
    read = mostyle.read(shared("bandai_walk_happy.bvh"))
    rebuilt = mostyle.Take(**arrays_of(read, translations=True))
    assert np.max(np.abs(rebuilt.translations - read.translations)) <= REBUILT
    assert np.max(np.abs(rebuilt.positions - read.positions)) <= REBUILT
    style = shared("bandai_walk_sad.bvh")
    from_file, from_arrays = mostyle.blend(read, style), mostyle.blend(rebuilt, style)
    assert from_arrays.positions.shape == from_file.positions.shape
    assert np.max(np.abs(from_arrays.positions - from_file.positions)) <= REBUILT


def test_a_result_is_a_take_to_style_again(tmp_path):
    a, b = asset("cmu142_walk_happy.bvh"), asset("cmu142_walk_joy.bvh")
    result = mostyle.blend(a, b)
    assert result.rotations.shape == (result.frames, len(result.joint_names), 4)
    assert result.root_positions.shape == (result.frames, 3)
    again = mostyle.transfer(result, b, strength=0.5)
    assert again.frames == result.frames
    for name in ["out.bvh", "out.glb", "out.fbx"]:
        result.write(str(tmp_path / name))
        assert mostyle.read(str(tmp_path / name)).frames == result.frames


def assert_error(call, *words):
    with pytest.raises(mostyle.Error) as caught:
        call()
    message = str(caught.value)
    assert "\n" not in message
    for w in words:
        assert w in message
    return message


def test_errors_are_one_line_mostyle_errors():
    assert issubclass(mostyle.Error, ValueError)
    walk = asset("cmu142_walk_happy.bvh")
    assert_error(lambda: mostyle.read("/no/such/walk.bvh"), "walk.bvh")
    assert_error(lambda: mostyle.blend(walk, walk, alpha=2.0), "--alpha", "2")
    assert_error(lambda: mostyle.blend(walk, "/no/such/walk.bvh"), "walk.bvh")
    assert_error(lambda: mostyle.blend(walk, walk, colour="red"), "colour", "alpha_at", "foot_lock")
    assert_error(lambda: mostyle.blend(walk, walk, timing="sometimes"), "--timing")
    assert_error(lambda: mostyle.mix([walk]), "2 to 16")
    assert_error(lambda: mostyle.mix([walk, walk], weights=[0.5, 0.2, 0.3]), "weight")
    assert_error(lambda: mostyle.mix([walk, walk], alpha=0.5), "alpha", "weights_at")
    assert_error(lambda: mostyle.transfer(walk, walk, strength=[1, 1]), "strengths")
    assert_error(lambda: mostyle.blend(walk, 42), "take B")
    assert_error(lambda: mostyle.blend(walk, walk, k="many"), "k")
    assert_error(lambda: mostyle.info("/no/such/walk.bvh"), "walk.bvh")
    assert_error(lambda: mostyle.blend(walk, walk).write("/tmp/result.txt"), "result.txt")


def test_arrays_of_the_wrong_shape_are_refused():
    good = arrays_of(mostyle.read(asset("cmu142_walk_happy.bvh")))
    joints, frames = len(good["joint_names"]), good["rotations"].shape[0]
    bad = {
        "offsets": np.zeros((joints, 2)),
        "rotations": np.zeros((frames, joints, 3)),
        "root_positions": np.zeros((frames + 1, 3)),
        "parents": np.zeros(joints - 1),
        "translations": np.zeros((frames, joints, 2)),
    }
    for name, value in bad.items():
        assert_error(lambda: mostyle.Take(**{**good, name: value}), name)
    assert_error(lambda: mostyle.Take(**{**good, "rotations": np.zeros((frames, joints, 4))}), "quaternion")
    assert_error(lambda: mostyle.Take(**{**good, "fps": -1.0}), "frame rate")
    parents = good["parents"].copy()
    parents[3] = 7
    assert_error(lambda: mostyle.Take(**{**good, "parents": parents}), "parent")
    assert_error(lambda: mostyle.Take(**{**good, "offsets": "origin"}), "offsets")


def test_threads_blend_at_once_as_one_at_a_time():
    a, b = asset("cmu142_walk_happy.bvh"), asset("cmu142_walk_marching.bvh")
    alphas = [0.2, 0.5, 0.8]
    assert_same_in_threads(lambda alpha: mostyle.blend(a, b, alpha).positions, alphas)


def test_a_loop_equals_the_cli(tmp_path):
    a, b = asset("cmu142_walk_happy.bvh"), asset("cmu142_walk_joy.bvh")
    cli = run_cli(["blend", a, b, "--loop", "--channels", "as-source"], tmp_path)
    assert_same_as_cli(mostyle.blend(a, b, loop=True, channels="as-source"), cli, tmp_path)


def assert_same_result(prepared, whole):
    """A prepared handle's result against the whole call's: positions, report, rotations."""
    assert prepared.positions.shape == whole.positions.shape
    assert np.max(np.abs(prepared.positions - whole.positions)) <= SAME
    assert without_timings(prepared.report) == without_timings(whole.report)
    assert np.array_equal(prepared.rotations, whole.rotations)
    assert np.array_equal(prepared.root_positions, whole.root_positions)


def test_a_result_says_the_layers_it_was_mixed_with():
    takes = [asset("cmu142_walk_happy.bvh"), asset("cmu142_walk_marching.bvh"), asset("cmu142_walk_joy.bvh")]
    mixed = mostyle.mix(takes, weights=[0.5, 0.3, 0.2]).report["mixed_as"]
    assert [(l["take"], l["weight"]) for l in mixed["layers"]] == [(0, 0.5), (1, 0.3), (2, 0.2)]
    assert mixed["additive"] == []
    blend = mostyle.blend(takes[0], takes[1], alpha=0.25).report["mixed_as"]
    assert [l["weight"] for l in blend["layers"]] == [0.75, 0.25]
    transfer = mostyle.transfer(takes[0], [takes[1], takes[2]], neutral=asset("cmu142_walk_clumsy.bvh"),
                                strength=[0.5, 1.5]).report["mixed_as"]
    # The content (take 0) at 1; each style (takes 2 and 3) added from the neutral (take 1).
    assert [(l["take"], l["weight"]) for l in transfer["layers"]] == [(0, 1.0)]
    assert [(l["take"], l["from"], l["strength"]) for l in transfer["additive"]] == [(2, 1, 0.5), (3, 1, 1.5)]
    parts = mostyle.mix(takes[:2], weights=[0.5, 0.5], part_weights={"legs": [0.0, 1.0]}).report["mixed_as"]
    assert all(len(l["component_weights"]) > 0 for l in parts["layers"])
    assert 1.0 in parts["layers"][1]["component_weights"]  # the legs' components from take 1


def test_a_prepared_mix_equals_the_whole_mix_for_each_weight():
    takes = [mostyle.read(asset("cmu142_walk_%s.bvh" % s)) for s in ("happy", "joy", "clumsy")]
    prepared = mostyle.prepare(takes, k=6, foot_lock=True)
    assert prepared.takes == 3
    for weights, parts in (([0.5, 0.3, 0.2], None), ([0.1, 0.1, 0.8], {"arms": [0.2, 0.4, 0.4]}),
                           ([0.5, 0.3, 0.2], None)):
        whole = mostyle.mix(takes, weights=weights, part_weights=parts, k=6, foot_lock=True)
        assert_same_result(prepared.mix(weights=weights, part_weights=parts), whole)


def test_a_prepared_mix_equals_the_cli(tmp_path):
    takes = [asset("cmu142_walk_happy.bvh"), asset("cmu142_walk_marching.bvh")]
    cli = run_cli(["mix", *takes, "--weights", "0.3,0.7", "--timing", "reference"], tmp_path)
    assert_same_as_cli(mostyle.prepare(takes, timing="reference").mix([0.3, 0.7]), cli, tmp_path)


def test_a_prepared_transfer_equals_the_whole_transfer():
    content, neutral = asset("cmu142_walk_happy.bvh"), asset("cmu142_walk_clumsy.bvh")
    styles = [asset("cmu142_walk_marching.bvh"), asset("cmu142_walk_joy.bvh")]
    prepared = mostyle.prepare([content, *styles], neutral=neutral)
    for strength in ([0.5, 0.25], [1.0, -0.5]):
        whole = mostyle.transfer(content, styles, neutral=neutral, strength=strength)
        assert_same_result(prepared.transfer(strength=strength), whole)
    whole = mostyle.transfer(content, styles, neutral=neutral, part_strength={"legs": [0.2, 0.3]})
    assert_same_result(prepared.transfer(part_strength={"legs": [0.2, 0.3]}), whole)
    assert_error(lambda: prepared.mix([0.25, 0.25, 0.25, 0.25]), "neutral")


def test_takes_prepared_to_mix_transfer_at_their_rate():
    content, style = asset("cmu142_walk_happy.bvh"), asset("cmu142_walk_joy.bvh")
    prepared = mostyle.prepare([content, style], fps=30)
    whole = mostyle.transfer(content, style, strength=0.6, fps=30)
    assert_same_result(prepared.transfer(strength=0.6), whole)


def test_a_prepared_mix_without_the_solve_has_the_same_positions():
    takes = [asset("cmu142_walk_happy.bvh"), asset("cmu142_walk_joy.bvh")]
    prepared = mostyle.prepare(takes)
    solved, cheap = prepared.mix([0.4, 0.6]), prepared.mix([0.4, 0.6], solve=False)
    assert np.max(np.abs(cheap.positions - solved.positions)) <= SAME
    assert without_timings(cheap.report).keys() <= without_timings(solved.report).keys()
    assert cheap.frames == solved.frames and cheap.joint_names == solved.joint_names
    # The reference's own rotations at the frames shown: unit quaternions, continuous.
    q = cheap.rotations
    assert np.allclose(np.linalg.norm(q, axis=-1), 1.0)
    assert np.all(np.sum(q[1:] * q[:-1], -1) >= 0.0)


def test_prepared_takes_refuse_bad_weights_and_options():
    prepared = mostyle.prepare([asset("cmu142_walk_happy.bvh"), asset("cmu142_walk_joy.bvh")])
    assert_error(lambda: prepared.mix([0.5, 0.3, 0.2]), "weights")
    assert_error(lambda: prepared.mix([3.0, -2.0]), "weight")
    assert_error(lambda: mostyle.prepare([asset("cmu142_walk_happy.bvh")]), "2 to")
    assert_error(lambda: mostyle.prepare([asset("cmu142_walk_happy.bvh"), asset("cmu142_walk_joy.bvh")], alpha=1),
                 "unknown option")


def test_threads_mix_one_prepared_set_as_one_at_a_time():
    prepared = mostyle.prepare([asset("cmu142_walk_happy.bvh"), asset("cmu142_walk_marching.bvh")])
    weights = [[0.2, 0.8], [0.5, 0.5], [0.9, 0.1]]
    assert_same_in_threads(lambda w: prepared.mix(w).positions, weights)
