#!/usr/bin/env python3
"""How a transfer treats its content, frame by frame and as a whole. For each content
take, runs `transfer CONTENT --neutral N --style S` and prints:
  - shown: the fraction of the content's frames the output shows (its report's source_frames), its
    frame rate against the content's;
  - pop: the 99.9th percentile of the fastest joint's per-frame speed (heights per second) over the
    fastest input's (content, neutral, style), as ../shared/hooks/pop_check.py measures it;
  - direction: the change the transfer makes to the content (output - content) against the change
    from N to S, on per-joint posture (height above the hips, reach forward of them), per-joint
    amplitude (RMS about the mean pose in the body's frame; all in heights) and the stride period
    (0.5 log seconds, from `info`): their cosine and the ratio of their sizes, with the cosine of
    each group apart;
  - strength 0: the output against the content (largest per-frame joint distance, % of height).
usage: style_check.py CLI NEUTRAL STYLE CONTENT [CONTENT ...]   (plain Python)"""
import csv, json, math, os, subprocess, sys, tempfile

cli, neutral, style, contents = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4:]
work = tempfile.mkdtemp(prefix='stylecheck-')
PERIOD_WEIGHT = 0.5


def run(*args):
    return subprocess.run([cli, *args], check=True, capture_output=True, text=True, timeout=600).stdout


def load(path, names=None):
    """frames x joints x 3; joints in the file's order, or those named, in that order"""
    joints = {}
    with open(path) as fh:
        for r in csv.DictReader(fh):
            joints.setdefault(r['joint'], []).append((int(r['frame']), float(r['x']), float(r['y']), float(r['z'])))
    names = names or list(joints)
    series = [[p[1:] for p in sorted(joints[n])] for n in names]
    return [[s[f] for s in series] for f in range(min(len(s) for s in series))]


def joint_names(path):
    with open(path) as fh:
        names = []
        for r in csv.DictReader(fh):
            if r['joint'] in names: break
            names.append(r['joint'])
        return names


def height(frames):
    ys = [p[1] for p in frames[0]]
    return (max(ys) - min(ys)) or 1.0


def fast(frames, fps, step=1, h=None):
    h = h or height(frames)
    frames = frames[::step]
    v = sorted(max(math.dist(p, q) for p, q in zip(a, b)) * fps / step / h for a, b in zip(frames, frames[1:]))
    return v[min(len(v) - 1, int(0.999 * len(v)))] if v else 0.0


def period(path):
    c = json.loads(run('info', path, '--json'))['cycles']
    return c.get('period_s', 0.0) if c.get('kind') not in (None, 'none', 'unknown') else 0.0


def features(frames, per):
    """posture (up, forward), amplitude per joint but the hips (major joints: 10, 14 the hips' legs), period"""
    h = height(frames)
    local = []
    for f in frames:
        hips, l, r = f[0], f[10], f[14]
        lat = (l[0] - r[0], l[2] - r[2])
        n = math.hypot(*lat) or 1.0
        lat = (lat[0] / n, lat[1] / n)
        fwd = (lat[1], -lat[0])  # left x up, on the ground
        local.append([((p[0] - hips[0]) * fwd[0] + (p[2] - hips[2]) * fwd[1],
                       p[1] - hips[1],
                       (p[0] - hips[0]) * lat[0] + (p[2] - hips[2]) * lat[1]) for p in f])
    joints = range(1, len(frames[0]))
    mean = [[sum(fr[j][c] for fr in local) / len(local) for c in range(3)] for j in range(len(frames[0]))]
    up = [mean[j][1] / h for j in joints]
    forward = [mean[j][0] / h for j in joints]
    amp = [math.sqrt(sum(sum((fr[j][c] - mean[j][c]) ** 2 for c in range(3)) for fr in local) / len(local)) / h
           for j in joints]
    return {'posture': up + forward, 'amplitude': amp, 'period': [PERIOD_WEIGHT * math.log(per)] if per > 0 else [0.0]}


def cosine(a, b):
    na, nb = math.sqrt(sum(x * x for x in a)), math.sqrt(sum(x * x for x in b))
    return sum(x * y for x, y in zip(a, b)) / (na * nb) if na > 0 and nb > 0 else 0.0


def diff(f, g):
    return {k: [x - y for x, y in zip(f[k], g[k])] for k in f}


def flat(d):
    return d['posture'] + d['amplitude'] + d['period']


def positions(path, tag):
    out = os.path.join(work, tag + '.csv')
    run('fk', path, '--out', out)
    return out


def majors(path, tag):
    """the take's 18 major joints, on itself (a transfer at strength 0 writes them in one order)"""
    out = os.path.join(work, tag + '.csv')
    run('transfer', path, '--neutral', path, '--style', path, '--strength', '0', '--positions-out', out)
    return load(out)


n_frames, s_frames = majors(neutral, 'n'), majors(style, 's')
ns = diff(features(s_frames, period(style)), features(n_frames, period(neutral)))
fps_of = lambda p: json.loads(run('info', p, '--json'))['fps']
for content in contents:
    name = os.path.basename(content)
    try:
        out_csv, out_bvh, rep = (os.path.join(work, 't' + e) for e in ('.csv', '.bvh', '.json'))
        run('transfer', content, '--neutral', neutral, '--style', style, '--positions-out', out_csv, '--out', out_bvh,
            '--report', rep)
        r = json.load(open(rep))
        t_frames = load(out_csv)
        c_frames = load(positions(content, 'c'), joint_names(out_csv))  # the joints the output has, in its order
        c_fps = fps_of(content)
        n_in = len(c_frames)
        got = set(int(round(f)) for f in r['takes'][0]['source_frames'])
        shown = sum(1 for i in range(n_in) if i in got or i - 1 in got or i + 1 in got) / max(1, n_in)
        inputs = max(fast(load(positions(p, 'in')), fps_of(p), max(1, round(fps_of(p) / r['fps'])))
                     for p in (content, neutral, style))
        pop = fast(t_frames, r['fps'], 1, height(c_frames)) / inputs
        change = diff(features(t_frames, period(out_bvh)), features(c_frames, period(content)))
        cos = cosine(flat(change), flat(ns))
        size = math.sqrt(sum(x * x for x in flat(change))) / (math.sqrt(sum(x * x for x in flat(ns))) or 1.0)
        groups = ', '.join(f'{k} {cosine(change[k], ns[k]):+.2f}' for k in ('posture', 'amplitude'))
        zero = os.path.join(work, 'z.csv')
        run('transfer', content, '--neutral', neutral, '--style', style, '--strength', '0', '--positions-out', zero)
        z = load(zero)
        h = height(c_frames)
        zero_err = max(max(math.dist(p, q) for p, q in zip(a, b)) for a, b in zip(z, c_frames)) / h if len(z) == len(c_frames) else float('nan')
        print(f'{name} ({n_in / c_fps:.1f} s at {c_fps:g} fps): shows {shown:.0%} at {r["fps"]:g} fps, '
              f'{r["duration_s"]:.1f} s out; pop {pop:.2f}x; N->S cosine {cos:+.2f} ({groups}; period '
              f'{change["period"][0] / PERIOD_WEIGHT:+.2f} vs {ns["period"][0] / PERIOD_WEIGHT:+.2f} log s), size {size:.2f}x; '
              f'strength 0: {len(z)} of {n_in} frames, max {100 * zero_err:.2f}% of height')
    except Exception as e:
        print(f'{name}: could not check ({str(e)[:200]})')
