#!/usr/bin/env python3
"""Outputs before and after a change that must not change them.

  compare_outputs.py snapshot CLI DIR [--quick]   runs every case with mostyle-cli, keeps each
                                                  one's positions CSV in DIR
  compare_outputs.py compare BEFORE AFTER [--tol F]
                                                  per case: same frames and joints, and every
                                                  coordinate within F of the take's height
                                                  (default 1e-9); exit 1 on any difference

The cases: blend, mix and transfer on the bundled pair and on ../shared/motions (when it is
there): both conventions, 30 and 120 fps, alpha 0 / 0.3 / 1, --components-only, paper mode,
--basic/--swap, per-part weights. Plain Python, no packages."""
import csv
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
ASSETS = os.path.join(ROOT, 'assets', 'motions')
SHARED = os.path.join(ROOT, '..', 'shared', 'motions')


def a(name):
    return os.path.join(ASSETS, name)


def s(name):
    return os.path.join(SHARED, name)


def cases(quick):
    happy, marching = a('cmu142_walk_happy.bvh'), a('cmu142_walk_marching.bvh')
    out = [
        ('blend_bundled_a0', ['blend', happy, marching, '--alpha', '0']),
        ('blend_bundled_a03', ['blend', happy, marching, '--alpha', '0.3']),
        ('blend_bundled_a1', ['blend', happy, marching, '--alpha', '1']),
        ('blend_bundled_components_only', ['blend', happy, marching, '--alpha', '0.3', '--components-only']),
        ('blend_bundled_paper', ['blend', happy, marching, '--alpha', '0.3', '--mode', 'paper']),
        ('blend_bundled_basic_swap', ['blend', happy, marching, '--alpha', '0.3', '--mode', 'paper', '--basic', '2',
                                      '--swap', '1']),
        ('blend_bundled_part_alpha', ['blend', happy, marching, '--alpha', '0.3', '--part-alpha', 'legs:0.9']),
        ('blend_bundled_timing_a', ['blend', happy, marching, '--alpha', '0.7', '--timing', 'a']),
        ('blend_bundled_120fps', ['blend', happy, marching, '--alpha', '0.3', '--fps', '120']),
        ('mix_bundled', ['mix', happy, marching, a('cmu142_walk_joy.bvh'), '--weights', '0.2,0.4,0.4']),
    ]
    if quick or not os.path.isdir(SHARED):
        return out
    normal, tired, old = s('bandai_walk_normal.bvh'), s('bandai_walk_tired.bvh'), s('bandai_walk_old.bvh')
    out += [
        ('blend_bandai_a03', ['blend', normal, tired, '--alpha', '0.3']),
        ('blend_bandai_a1', ['blend', normal, tired, '--alpha', '1']),
        ('blend_bandai_paper', ['blend', normal, old, '--alpha', '0.3', '--mode', 'paper']),
        ('blend_mixed_conventions', ['blend', s('cmu142_walk_joy.bvh'), old, '--alpha', '0.3']),
        ('blend_mixed_120fps', ['blend', normal, s('cmu142_walk_marching.bvh'), '--alpha', '0.7', '--fps', '120']),
        ('mix_mixed', ['mix', normal, a('cmu142_walk_happy.bvh'), marching, '--weights', '0.2,0.4,0.4',
                       '--part-weights', 'legs:0,0,1']),
        ('mix_bandai_components_only', ['mix', normal, tired, old, s('bandai_walk_proud.bvh'), '--weights',
                                        '0.25,0.25,0.25,0.25', '--components-only']),
        ('transfer_bandai', ['transfer', s('bandai_walk_happy.bvh'), '--neutral', normal, '--style', old]),
        ('transfer_cmu_content', ['transfer', s('cmu142_walk_clumsy.bvh'), '--neutral', a('cmu142_walk_happy.bvh'),
                                  '--style', marching, '--strength', '0.5']),
    ]
    return out


def snapshot(cli, folder, quick):
    os.makedirs(folder, exist_ok=True)
    failed = 0
    for name, args in cases(quick):
        path = os.path.join(folder, name + '.csv')
        p = subprocess.run([cli, *args, '--positions-out', path, '--report', os.path.join(folder, name + '.json')],
                           capture_output=True, text=True)
        if p.returncode != 0:
            print(f'{name}: exit {p.returncode}: {p.stderr.strip()}')
            failed += 1
        else:
            print(f'{name}: ok')
    return 1 if failed else 0


def read_positions(path):
    rows = {}
    with open(path) as f:
        r = csv.reader(f)
        next(r)
        for frame, joint, x, y, z in r:
            rows[(int(frame), joint)] = (float(x), float(y), float(z))
    return rows


def height(rows):
    ys = [p[1] for p in rows.values()]
    return max(ys) - min(ys) if ys else 1.0


def compare(before, after, tol):
    names = sorted(f[:-4] for f in os.listdir(before) if f.endswith('.csv'))
    bad = 0
    for name in names:
        other = os.path.join(after, name + '.csv')
        if not os.path.exists(other):
            print(f'{name}: missing after'); bad += 1; continue
        x, y = read_positions(os.path.join(before, name + '.csv')), read_positions(other)
        if x.keys() != y.keys():
            print(f'{name}: frames or joints differ ({len(x)} rows before, {len(y)} after)'); bad += 1; continue
        h = height(x)
        worst = max(max(abs(p - q) for p, q in zip(x[k], y[k])) for k in x) / h
        ok = worst <= tol
        bad += not ok
        print(f'{name}: {len(x)} rows, max difference {worst:.3g} of height{"" if ok else "  <- changed"}')
    return 1 if bad else 0


def main(argv):
    if len(argv) >= 3 and argv[0] == 'snapshot':
        return snapshot(argv[1], argv[2], '--quick' in argv)
    if len(argv) >= 3 and argv[0] == 'compare':
        tol = float(argv[argv.index('--tol') + 1]) if '--tol' in argv else 1e-9
        return compare(argv[1], argv[2], tol)
    print(__doc__)
    return 2


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
