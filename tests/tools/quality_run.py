#!/usr/bin/env python3
"""A quality run over folders of takes, as compression libraries run their error metrics over a
whole motion-capture database: every kind of output mostyle makes, on every kind of take found,
measured the same way, in one table.

usage: quality_run.py CLI DIR [DIR ...] [--quick] [--json OUT] [--markdown OUT.md] [--per-class N]
                      [--timeout S] [--only TEXT ...]
       quality_run.py --self-test

--markdown docs/quality.md writes the table as the project's quality page (written to a temporary
file, then renamed): the command that made it, the takes, the table and what its columns mean.

Takes: every BVH file of each folder, and of each FBX or glTF file its walk and run animations
(FILE#ANIMATION; a file with one animation is taken whole). `info --json` tells each take's rate,
height, skeleton and cycles; a take whose cycles are one cycle covering it whole is a loop.
A dataset is the takes of one folder that share one skeleton (the same joint names).

Outputs (plain Python, the CLI run as a person runs it; a command exiting non-zero is a row
saying so, never a crash):
  blends at alpha 0.5 of each pairing class: two takes of one dataset, of two datasets, a loop
    with a loop (with --loop), a loop with a long take (either one the reference);
  transfers of every take with one style pair (bandai_walk_normal -> bandai_walk_old when both
    are given, else the first two takes of the take's folder), and, when the CLI takes a transfer
    without --neutral, each take with the style alone (the content its own neutral);
  mixes of 3 and 4 takes with equal weights;
  styled families (takes named FAMILY_STYLE of one folder with a FAMILY_normal or FAMILY_neutral
    among them, as actions/ and the Bandai walks are): each style's blend with the family's
    neutral at alpha 0 (A shown whole?) and at alpha 1 (is it B?), the family's palette (a mix of
    all of its takes, equal weights), and the family's change (neutral -> style) transferred onto
    another family's neutral (cross-action), with the neutral and with the style clip alone.
Columns (see MEASURES below for each function):
  cover   fraction of the reference's frames the output shows (its report's source_frames)
  cycles  cycles `info` finds in each input (count and kind: g gait, p periodic, n none,
          u unknown; L a loop), reference first
  seam    loop references and --loop outputs: the last->first step over the largest step inside
          (the fastest move of the loop; at most 1.5 is seamless to the eye)
  fast    the output's fastest move over the fastest input's (99.9th percentile of the per-frame
          fastest joint speed, in body heights per second)
  feet    planted-foot sliding of the output over the inputs' mixed by weight (a blend (1-a)A +
          aB, a transfer its content, a mix its weights); a foot joint (ankle, toe) is planted
          within 3% of body height of its own floor (the 5th percentile of its heights), the
          definition mostyle's report and editor use, measured here again from the positions;
          speeds compared in leg lengths per second (takes on other skeletons are scaled by
          their legs when mixed)
  body height: every measure in heights is of the body height mostyle reports for that take
          as a reference (its major joints stood upright from their bone lengths)
  s0      transfers: the output at strength 0 against the content, largest per-frame joint
          distance, % of height
  dir     transfers: cosine and size ratio of (output - content) against (style - neutral) on
          per-joint posture, per-joint amplitude and the stride period (the period only where
          the output's timing is not the content's: --timing mix)
  way     one style clip (no neutral): how far the output's features went towards the style's,
          the projection of (output - content) onto (style - content) over its length
  hips    one style clip: the output's hips' largest horizontal distance from the content's, in
          body heights
  toB     blends at alpha 1: the output's mean pose distance to B over the distance from A to B,
          poses in the body's frame about the hips (as for `features`), in body heights, each pair
          of takes matched by a DTW (at most 0.2: alpha 1 is B's performance)
  lenB    blends at alpha 1: the output's length over B's
"""
import argparse, csv, json, math, os, re, subprocess, sys, tempfile, time

# ----------------------------------------------------------------------------------------------
# MEASURES: pure functions of plain lists, tested by --self-test. frames: frames x joints x 3.

PLANTED_FRACTION = 0.03  # a foot joint within this fraction of body height of its own floor is planted
FLOOR_PERCENTILE = 0.05  # a joint's floor: this low percentile of its heights (a glitch frame is no floor)
FAST_PERCENTILE = 0.999  # the fastest move: this percentile of the per-frame fastest joint speed
PERIOD_WEIGHT = 0.5      # the stride period's weight among the direction features (log seconds)
LOOP_COVER = 0.9         # one cycle covering this fraction of a take makes it a loop


def percentile(values, q):
    """The q-quantile (0..1) of values by the nearest rank below; None for no values."""
    v = sorted(values)
    return v[min(len(v) - 1, int(q * len(v)))] if v else None


def shown_fraction(source_frames, n, period=0.0):
    """Fraction of a take's n frames an output shows: frame i counts when the output shows a frame
    within one of it (source_frames: the take's frame at each output frame; None entries skipped).
    For a loop (period: its loop's length in these frames, 0 for none), a frame shown is shown a
    period later too: the loop's end is its start again (a closed output shows the start, and the
    take's last frame, a copy of its first or a step short of it, is that same moment)."""
    shown = [f for f in source_frames if f is not None]
    got = set(int(round(f)) for f in shown)
    if period > 0: got |= set(int(round(f + period)) for f in shown)
    return sum(1 for i in range(n) if i in got or i - 1 in got or i + 1 in got) / max(1, n)


def fastest_move(frames, fps, height, step=1):
    """99.9th percentile over frames of the fastest joint's speed, body heights per second; frames
    at fps, every step-th used (so inputs at a higher rate are read at the output's)."""
    frames = frames[::step]
    v = [max(math.dist(p, q) for p, q in zip(a, b)) * fps / step / height for a, b in zip(frames, frames[1:])]
    return percentile(v, FAST_PERCENTILE) or 0.0


def root_relative(frames, root=0):
    """Each frame with the root's horizontal position (x, z) taken away (y kept: a hop is a pose)."""
    return [[(p[0] - f[root][0], p[1], p[2] - f[root][2]) for p in f] for f in frames]


def pose_step(a, b):
    """RMS over joints of the distance between two poses."""
    return math.sqrt(sum(math.dist(p, q) ** 2 for p, q in zip(a, b)) / max(1, len(a)))


def seam_ratio(frames):
    """A loop's seam: the root-relative step from the last frame to the first over the largest
    step between neighbouring frames inside (the loop's fastest move). At most about 1 (or 0, a
    last frame repeating the first) is seamless."""
    rel = root_relative(frames)
    if len(rel) < 3: return None
    largest = max(pose_step(a, b) for a, b in zip(rel, rel[1:]))
    return pose_step(rel[-1], rel[0]) / largest if largest > 0 else None


def planted_sliding(frames, fps, height, feet):
    """Mean horizontal speed (body heights per second) of the foot joints `feet` (indexes) while
    planted: within PLANTED_FRACTION of height of the joint's own floor at both ends of a step.
    None when no foot joint is ever planted."""
    total, count = 0.0, 0
    for j in feet:
        ys = [f[j][1] for f in frames]
        floor = percentile(ys, FLOOR_PERCENTILE)
        planted = [y - floor < PLANTED_FRACTION * height for y in ys]
        for k in range(len(frames) - 1):
            if planted[k] and planted[k + 1]:
                a, b = frames[k][j], frames[k + 1][j]
                total += math.hypot(b[0] - a[0], b[2] - a[2]) * fps / height
                count += 1
    return total / count if count else None


def by_weight(values, weights):
    """sum w_i v_i over the takes with a value; None when none has one."""
    pairs = [(w, v) for w, v in zip(weights, values) if v is not None and w != 0]
    return sum(w * v for w, v in pairs) if pairs else None


def ratio(a, b):
    return a / b if a is not None and b not in (None, 0) else None


def interpolate(frames, at):
    """The pose at fractional frame `at` (clamped), linear between frames."""
    at = min(max(at, 0.0), len(frames) - 1.0)
    i = min(int(at), len(frames) - 2) if len(frames) > 1 else 0
    t = at - i if len(frames) > 1 else 0.0
    a, b = frames[i], frames[min(i + 1, len(frames) - 1)]
    return [tuple((1 - t) * x + t * y for x, y in zip(p, q)) for p, q in zip(a, b)]


def select(frames, names, wanted):
    """The joints named `wanted`, in that order (a palette's majors are those its takes share)."""
    index = [names.index(n) for n in wanted]
    return [[f[i] for i in index] for f in frames]


def largest_error(out, reference, source_frames, height):
    """Largest per-frame joint distance between `out` and the reference at the frames it shows
    (source_frames: the reference's frame at each output frame), as a fraction of height."""
    worst = 0.0
    for f, s in zip(out, source_frames):
        if s is None: continue
        worst = max(worst, max(math.dist(p, q) for p, q in zip(f, interpolate(reference, s))))
    return worst / height


# The major skeleton's roles. A positions CSV of mostyle lists the major joints in one order
# (hips, spine, chest, head, left arm, right arm, left leg, right leg; a part missing in a
# skeleton left out), each under its nearest major ancestor: roles follow from that tree alone.
def major_parents(names, parent_of):
    """Each major joint's nearest major ancestor (index into names; -1 for the root). parent_of:
    the full skeleton's joint -> parent name (None for its root)."""
    index = {n: i for i, n in enumerate(names)}
    out = []
    for n in names:
        p = parent_of.get(n)
        while p is not None and p not in index: p = parent_of.get(p)
        out.append(index[p] if p is not None else -1)
    return out


def major_roles(parents):
    """Role names by the tree: 'hips'; 'chest' (the spine joint that branches), 'spine1', 'spine2'
    ... below it down to the hips, 'head0', 'head1' ... above it; 'L_arm0..', 'R_arm0..', 'L_leg0..',
    'R_leg0..' (depth along the chain: a leg's 0 hip, 1 knee, 2 ankle, 3 toe). The hips' children
    in order are the spine, the left leg, the right leg; the chest carries the head, the left arm
    and the right arm in that order. Skeletons with or without a spine joint or hands agree on
    the roles they share."""
    n = len(parents)
    children = [[c for c in range(n) if parents[c] == i] for i in range(n)]
    roles = [None] * n
    root = parents.index(-1) if -1 in parents else 0
    roles[root] = 'hips'

    def chain(start, name):
        j, d = start, 0
        while j is not None:
            roles[j] = f'{name}{d}'
            d += 1
            j = children[j][0] if len(children[j]) == 1 else None

    kids = children[root]
    spine = kids[0] if len(kids) in (1, 3) else None
    if len(kids) >= 2:
        chain(kids[-2], 'L_leg')
        chain(kids[-1], 'R_leg')
    # The spine: down single children to the joint that branches (the chest), or to its end.
    below, j = [], spine
    while j is not None and len(children[j]) == 1:
        below.append(j)
        j = children[j][0]
    if j is not None and not children[j]:
        roles[j] = 'head0'  # a spine without arms ends at the head
    elif j is not None:
        roles[j] = 'chest'
        branch = children[j]
        if len(branch) >= 3:
            chain(branch[0], 'head')
            chain(branch[1], 'L_arm')
            chain(branch[2], 'R_arm')
        elif len(branch) == 2:
            chain(branch[0], 'L_arm')
            chain(branch[1], 'R_arm')
    for d, k in enumerate(reversed(below)):
        roles[k] = f'spine{d + 1}'
    return roles


def foot_joints(roles):
    """The ankles and toes: leg joints two or more below the hip."""
    return [i for i, r in enumerate(roles) if r and r[:5] in ('L_leg', 'R_leg') and int(r[5:]) >= 2]


def leg_length(frames, roles):
    """Thigh plus shin on the first frame, averaged over the legs (None without a leg): the
    length mostyle scales a take's travel by when it retargets it onto another skeleton."""
    index = {r: i for i, r in enumerate(roles) if r}
    legs = [math.dist(frames[0][index[f'{s}_leg0']], frames[0][index[f'{s}_leg1']]) +
            math.dist(frames[0][index[f'{s}_leg1']], frames[0][index[f'{s}_leg2']])
            for s in 'LR' if all(f'{s}_leg{d}' in index for d in range(3))]
    return sum(legs) / len(legs) if legs and frames else None


def features(frames, roles, height, period_s):
    """style_check.py's features, by role: per joint (but the hips) its mean height above the hips
    and reach forward of them, its RMS amplitude about its mean in the body's frame (all in
    heights), and the stride period (PERIOD_WEIGHT log seconds; left out where `info` finds none). The body's frame:
    lateral from the right leg's hip to the left's, forward across it on the ground (body_frame)."""
    local = body_frame(frames, roles)
    out = {}
    for j, role in enumerate(roles):
        if role in (None, 'hips'): continue
        mean = [sum(fr[j][c] for fr in local) / len(local) for c in range(3)]
        amp = math.sqrt(sum(sum((fr[j][c] - mean[c]) ** 2 for c in range(3)) for fr in local) / len(local))
        out['up ' + role] = mean[1] / height
        out['forward ' + role] = mean[0] / height
        out['amplitude ' + role] = amp / height
    if period_s and period_s > 0: out['period'] = PERIOD_WEIGHT * math.log(period_s)  # unknown: not compared
    return out


def change(a, b):
    """a - b on the features both have."""
    return {k: a[k] - b[k] for k in a if k in b}


def direction(made, wanted):
    """Cosine and size ratio of the change made against the change wanted, on the features both
    have; None where either is empty or zero."""
    keys = [k for k in made if k in wanted]
    x, y = [made[k] for k in keys], [wanted[k] for k in keys]
    nx, ny = math.sqrt(sum(v * v for v in x)), math.sqrt(sum(v * v for v in y))
    if nx == 0 or ny == 0: return None, None
    return sum(p * q for p, q in zip(x, y)) / (nx * ny), nx / ny


def way_to(made, wanted):
    """How far along the change wanted the change made goes: its projection onto wanted over
    wanted's length (1: all the way, 0: none, negative: away); None where wanted is empty or 0."""
    keys = [k for k in made if k in wanted]
    ny2 = sum(wanted[k] ** 2 for k in keys)
    return sum(made[k] * wanted[k] for k in keys) / ny2 if ny2 > 0 else None


def body_frame(frames, roles):
    """Each frame's joints about its hips, in the body's frame (forward, up, lateral): lateral from
    the right leg's hip to the left's, forward across it on the ground."""
    li, ri = roles.index('L_leg0'), roles.index('R_leg0')
    out = []
    for f in frames:
        hips, l, r = f[0], f[li], f[ri]
        lat = (l[0] - r[0], l[2] - r[2])
        n = math.hypot(*lat) or 1.0
        lat = (lat[0] / n, lat[1] / n)
        fwd = (lat[1], -lat[0])
        out.append([((p[0] - hips[0]) * fwd[0] + (p[2] - hips[2]) * fwd[1], p[1] - hips[1],
                     (p[0] - hips[0]) * lat[0] + (p[2] - hips[2]) * lat[1]) for p in f])
    return out


def resampled(frames, n):
    """frames (at least one) read at n evenly spread fractional frames, linearly."""
    if n <= 1 or len(frames) == 1: return [frames[0]] * max(1, n)
    return [interpolate(frames, k * (len(frames) - 1) / (n - 1)) for k in range(n)]


def pose_gap(x, y):
    """Mean pose distance of two motions (frames x joints x 3, one skeleton's joints) along their
    DTW path (steps (1,0), (0,1), (1,1)): the mean over the path's cells of the mean joint
    distance."""
    n, m = len(x), len(y)
    if n == 0 or m == 0: return None
    cost = [[sum(math.dist(p, q) for p, q in zip(a, b)) / len(a) for b in y] for a in x]
    inf = float('inf')
    total = [[inf] * (m + 1) for _ in range(n + 1)]
    steps = [[0] * (m + 1) for _ in range(n + 1)]
    total[0][0] = 0.0
    for i in range(1, n + 1):
        for j in range(1, m + 1):
            best = min((total[i - 1][j - 1], steps[i - 1][j - 1]), (total[i - 1][j], steps[i - 1][j]),
                       (total[i][j - 1], steps[i][j - 1]))
            total[i][j] = best[0] + cost[i - 1][j - 1]
            steps[i][j] = best[1] + 1
    return total[n][m] / steps[n][m]


def hips_stray(out, reference, source_frames, height):
    """Largest horizontal distance of the output's hips (joint 0) from the reference's at the
    frame each output frame shows, as a fraction of height; None when no frame shows one."""
    worst = None
    for f, s in zip(out, source_frames):
        if s is None: continue
        r = interpolate(reference, s)[0]
        d = math.hypot(f[0][0] - r[0], f[0][2] - r[2]) / height
        worst = d if worst is None else max(worst, d)
    return worst


def cycles_of(info):
    """(count, kind letter, loop) of an `info --json` report: a loop is one cycle covering
    LOOP_COVER of the take (or a take `info` says loops)."""
    c = info.get('cycles') or {}
    kind = c.get('kind') or 'unknown'
    cycles = c.get('cycles') or []
    frames = max((info.get('frames') or 2) - 1, 1)
    loop = bool(c.get('loop_frames')) or (
        len(cycles) == 1 and (cycles[0]['end'] - cycles[0]['start']) >= LOOP_COVER * frames)
    return len(cycles), {'gait': 'g', 'periodic': 'p', 'none': 'n'}.get(kind, 'u'), loop


def read_positions(path):
    """(joint names, frames x joints x 3) of a positions CSV frame,joint,x,y,z, joints in the
    order they first appear."""
    joints, names = {}, []
    with open(path, newline='') as fh:
        for r in csv.DictReader(fh):
            if r['joint'] not in joints:
                joints[r['joint']] = []
                names.append(r['joint'])
            joints[r['joint']].append((int(r['frame']), float(r['x']), float(r['y']), float(r['z'])))
    series = [[p[1:] for p in sorted(joints[n])] for n in names]
    return names, [[s[f] for s in series] for f in range(min(len(s) for s in series))] if series else []


# ----------------------------------------------------------------------------------------------
# THE RUN

class Failed(Exception):
    pass


class Cli:
    def __init__(self, path, work, timeout):
        self.path, self.work, self.timeout, self.seconds, self.commands = path, work, timeout, 0.0, 0
        self._info, self._fk, self._majors, self._body = {}, {}, {}, {}
        self.count = 0

    def run(self, *args):
        """stdout of one command; Failed with its exit code and first line of stderr otherwise."""
        t0 = time.time()
        self.commands += 1
        try:
            p = subprocess.run([self.path, *args], capture_output=True, text=True, timeout=self.timeout)
        except subprocess.TimeoutExpired:
            raise Failed(f'timeout after {self.timeout:g} s')
        finally:
            self.seconds += time.time() - t0
        if p.returncode != 0:
            lines = [l for l in p.stderr.splitlines() if l.strip() and 'warning' not in l] or p.stderr.splitlines() or ['']
            # Paths named by their file names, so the sentence fits its row.
            message = re.sub(r'(?:/[^/\s:]+)+/', '', lines[-1].strip()).replace('mostyle: ', '', 1)
            raise Failed(f'exit {p.returncode}: {message[:150]}')
        return p.stdout

    def file(self, tag, ext):
        self.count += 1
        return os.path.join(self.work, f'{self.count:04d}_{re.sub(r"[^A-Za-z0-9_.-]", "_", tag)[:60]}{ext}')

    def info(self, take):
        if take not in self._info: self._info[take] = json.loads(self.run('info', take, '--json'))
        return self._info[take]

    def fk(self, take):
        """All joints of the take at its own rate (for speeds)."""
        if take not in self._fk:
            out = self.file('fk', '.csv')
            self.run('fk', take, '--out', out)
            self._fk[take] = read_positions(out)[1]
        return self._fk[take]

    def majors(self, take):
        """(names, frames, roles) of the take's major joints, as mostyle reads them: the take on
        itself at strength 0, at its own rate, without the foot lock."""
        if take not in self._majors:
            out, rep = self.file('majors', '.csv'), self.file('majors', '.json')
            self.run('transfer', take, '--neutral', take, '--style', take, '--strength', '0', '--no-foot-lock',
                     '--positions-out', out, '--report', rep)
            names, frames = read_positions(out)
            self._majors[take] = (names, frames, self.roles(take, names))
            self._body[take] = json.load(open(rep))['foot_sliding']['body_height']
        return self._majors[take]

    def body_height(self, take):
        """The body height mostyle takes for this take as a reference (its major joints stood
        upright), the one every planted band and speed of the table is relative to."""
        self.majors(take)
        return self._body[take]

    def roles(self, take, names):
        parent_of = {j['name']: j['parent'] for j in self.info(take)['joints']}
        return major_roles(major_parents(names, parent_of))


def pick_takes(cli, folder):
    """The folder's takes: BVH files, and the walk and run animations of FBX and glTF files."""
    takes = []
    for name in sorted(os.listdir(folder)):
        path = os.path.join(folder, name)
        ext = os.path.splitext(name)[1].lower()
        if not os.path.isfile(path): continue
        if ext == '.bvh':
            takes.append(path)
        elif ext in ('.fbx', '.glb', '.gltf'):
            try:
                animations = [t['name'] for t in cli.info(path).get('takes', [])]
            except (Failed, ValueError) as e:
                print(f'  {name}: not read ({e})', file=sys.stderr)
                continue
            if len(animations) <= 1:
                takes.append(path)
            else:
                takes += [f'{path}#{a}' for a in animations if re.search(r'walk|run', a, re.I)]
    return takes


def short(take):
    base = os.path.basename(take)
    return re.sub(r'\.(bvh|fbx|glb|gltf)(?=#|$)', '', base, flags=re.I)


class Take:
    def __init__(self, cli, path, folder):
        self.path, self.folder, self.name = path, folder, short(path)
        info = cli.info(path)
        self.fps, self.height, self.frames = info['fps'], info.get('height') or 1.0, info['frames']
        self.duration = info['duration_s']
        self.count, self.kind, self.loop = cycles_of(info)
        self.period = (info.get('cycles') or {}).get('period_s') or 0.0
        # A loop's length in seconds (its loop frames at its rate), 0 for a take that is no loop.
        self.loop_s = ((info.get('cycles') or {}).get('loop_frames') or 0) / self.fps if self.loop else 0.0
        self.skeleton = tuple(sorted(j['name'] for j in info.get('joints', [])))

    def cycles_label(self):
        return f'{self.count}{getattr(self, "kind", "g")}{"L" if self.loop else ""}'


def datasets_of(takes):
    """Takes grouped by folder and skeleton, in the order first met."""
    groups = {}
    for t in takes: groups.setdefault((t.folder, t.skeleton), []).append(t)
    return list(groups.values())


def spread(candidates, limit):
    """At most `limit` of the candidates, evenly spread over the list."""
    if len(candidates) <= limit: return candidates
    return [candidates[int(i * len(candidates) / limit)] for i in range(limit)]


def plan(takes, quick, per_class, style_pairs, own_neutral):
    """The outputs to make: (kind, label, takes, options, weights)."""
    limit = per_class or (2 if quick else 6)
    sets = datasets_of(takes)
    jobs = []
    # Neighbouring takes of each dataset, round-robin over the datasets (each tried before any
    # twice); for two datasets, a take of each, a different one each time the dataset comes up.
    same = [(g[i], g[i + 1]) for i in range(max(map(len, sets))) for g in sets if i + 1 < len(g)]
    used = {id(g): 0 for g in sets}

    def next_of(g):
        used[id(g)] += 1
        return g[(used[id(g)] - 1) % len(g)]

    across = [(next_of(a), next_of(b)) for i, a in enumerate(sets) for b in sets[i + 1:]]
    loops = [t for t in takes if t.loop]
    longs = [t for t in takes if not t.loop and t.count >= 2]
    loop_loop = [(a, b) for i, a in enumerate(loops) for b in loops[i + 1:]]
    loop_long = [p for a in loops for b in longs for p in ((a, b), (b, a))]
    for cls, pairs, options in (('same', same, []), ('across', across, []), ('loop+loop', loop_loop, ['--loop']),
                                ('loop+long', loop_long, [])):
        for a, b in spread(pairs, limit):
            jobs.append(('blend', ' '.join([f'blend {cls}', *options]), [a, b], ['--alpha', '0.5', *options], [0.5, 0.5]))
    contents = takes if not quick else [g[0] for g in sets]
    for c in contents:
        n, s = style_pairs(c)
        if n is None: continue
        jobs.append(('transfer', f'transfer', [c, n, s], [], None))
        if own_neutral and c is not s:
            jobs.append(('transfer', f'transfer own', [c, s], [], None))
    # Style from one clip of the content's own dataset (as the neural style-transfer demos pair a
    # content with a style clip and no neutral): the dataset's longest gait take styles the others.
    if own_neutral:
        for g in sets:
            gaits = [t for t in g if t.kind == 'g' and t.count >= 1]
            if len(g) < 2 or not gaits: continue
            style = max(gaits, key=lambda t: t.frames)
            for c in (g if not quick else g[:2]):
                if c is not style: jobs.append(('transfer', 'transfer clip', [c, style], [], None))
    mixes = []
    big = max(sets, key=len)
    if len(big) >= 3: mixes.append(('mix same', big[:3]))
    # Across datasets, each of the first datasets' takes the reference (the first take) in turn.
    across = [g[0] for g in sets[:4]]
    if len(across) >= 3:
        for k in range(len(across)):
            mixes.append(('mix across', across[k:] + across[:k]))
    if len(loops) >= 3: mixes.append(('mix loops', loops[:3]))
    for label, ts in (mixes[:1] if quick else mixes):
        jobs.append(('mix', label, ts, [], [1.0 / len(ts)] * len(ts)))
    return jobs + family_jobs(takes, quick, own_neutral)


NEUTRAL_STYLES = ('normal', 'neutral')


def families_of(takes):
    """Styled families: takes of one folder named FAMILY_STYLE, one of them FAMILY_normal (or
    _neutral), as [(neutral, [style takes])] in the order first met; a family of its neutral
    alone has no style takes (it is still a content for another family's change)."""
    groups = {}
    for t in takes:
        if '_' not in t.name or '#' in t.name: continue
        family, style = t.name.rsplit('_', 1)
        groups.setdefault((t.folder, family), []).append((style.lower(), t))
    out = []
    for members in groups.values():
        neutral = next((t for style, t in members if style in NEUTRAL_STYLES), None)
        if neutral is not None: out.append((neutral, [t for _, t in members if t is not neutral]))
    return out


def family_jobs(takes, quick, own_neutral):
    """The styled families' outputs: each style against its neutral at alpha 0 and 1, each
    family's palette, and each family's change onto another family's neutral (the next one in
    turn, so every content is used), with the neutral and, where the CLI takes it, alone."""
    families = families_of(takes)
    jobs = []
    for n, styles in families:
        for s in (styles[:1] if quick else styles):
            for alpha in ('0', '1'):
                jobs.append(('blend', f'family blend a={alpha}', [n, s], ['--alpha', alpha], [1 - float(alpha), float(alpha)]))
        if len(styles) >= 2:
            members = [n] + styles
            jobs.append(('mix', 'family palette', members, [], [1.0 / len(members)] * len(members)))
    contents = [n for n, _ in families]
    turn = 0
    for n, styles in families:
        others = [c for c in contents if c is not n]
        if not others: continue
        for s in (styles[:1] if quick else styles):
            c = others[turn % len(others)]
            turn += 1
            jobs.append(('transfer', 'transfer across', [c, n, s], [], None))
            if own_neutral: jobs.append(('transfer', 'transfer across clip', [c, s], [], None))
    return jobs


def job_text(job):
    """A job as its row reads: 'what: take + take'."""
    return f'{job[1]}: ' + ' + '.join(t.name for t in job[2])


def only(jobs, texts):
    """The jobs whose row text holds one of `texts` (all of them when none is given)."""
    return [j for j in jobs if not texts or any(t in job_text(j) for t in texts)]


def measure(cli, kind, label, takes, options, weights):
    """One output made and measured: a dict of the row's values (status 'ok' or why not)."""
    row = {'kind': kind, 'what': label, 'takes': [t.name for t in takes],
           'cycles': '/'.join(t.cycles_label() for t in takes), 'status': 'ok'}
    ref = takes[0]
    csv_out, rep = cli.file(kind, '.csv'), cli.file(kind, '.json')
    bvh = cli.file(kind, '.bvh')
    if kind == 'blend':
        args = ['blend', takes[0].path, takes[1].path, *options]
    elif kind == 'mix':
        args = ['mix', *[t.path for t in takes], '--weights', ','.join(f'{w:.6g}' for w in weights), *options]
    elif len(takes) == 3:
        args = ['transfer', takes[0].path, '--neutral', takes[1].path, '--style', takes[2].path, *options]
    else:
        args = ['transfer', takes[0].path, '--style', takes[1].path, *options]
    try:
        cli.run(*args, '--positions-out', csv_out, '--report', rep, *(['--out', bvh] if kind == 'transfer' else []))
    except Failed as e:
        row['status'] = str(e)
        return row
    try:
        r = json.load(open(rep))
        fps, height = r['fps'], r['foot_sliding']['body_height']
        names, frames = read_positions(csv_out)
        row['frames'], row['seconds'] = len(frames), len(frames) / fps
        n_ref = int(round(ref.duration * fps)) + 1
        row['cover'] = shown_fraction(r['takes'][0]['source_frames'], n_ref, ref.loop_s * fps)
        if ref.loop or '--loop' in options: row['seam'] = seam_ratio(frames)
        inputs = max(fastest_move(cli.fk(t.path), t.fps, cli.body_height(t.path), max(1, round(t.fps / fps)))
                     for t in takes)
        row['fast'] = ratio(fastest_move(frames, fps, height), inputs)
        roles = cli.roles(ref.path, names)
        # Speeds of takes on different skeletons are compared in leg lengths per second, as
        # mostyle scales a take's travel onto the reference's legs (a walk's speed goes with its
        # legs); a take's own heights per second would weigh a long-legged body's feet wrong.
        def slide_in_legs(f, fr, h, rl):
            v, legs = planted_sliding(f, fr, h, foot_joints(rl)), leg_length(f, rl)
            return None if v is None or not legs else v * h / legs
        out_slide = slide_in_legs(frames, fps, height, roles)
        slides = []
        for t in takes:
            _, tf, troles = cli.majors(t.path)
            slides.append(slide_in_legs(tf, t.fps, cli.body_height(t.path), troles))
        mixed = by_weight(slides, [1.0] + [0.0] * (len(takes) - 1) if kind == 'transfer'
                          else [t['weight'] for t in r['takes']])
        row['feet'] = ratio(out_slide, mixed)
        row['feet_out'] = out_slide
        if kind == 'transfer': transfer_measures(cli, row, takes, args, frames, names, roles, height, bvh, r)
        if kind == 'blend' and options[:2] == ['--alpha', '1']: to_b_measures(cli, row, takes, frames, names, roles, fps, height)
    except Failed as e:
        row['status'] = 'measure: ' + str(e)
    except Exception as e:  # a measure that cannot be taken is said in its row
        row['status'] = f'measure: {type(e).__name__}: {str(e)[:100]}'
    return row


GAP_FRAMES = 150  # poses compared a take at most (longer takes read at every k-th frame): the DTW is plain Python


def to_b_measures(cli, row, takes, frames, names, roles, fps, height):
    """A blend at alpha 1 against B: its pose distance to B over A's, and its length over B's."""
    def posed(path):
        t_names, t_frames, t_roles = cli.majors(path)
        t = next(x for x in takes if x.path == path)
        return t_roles, resampled(body_frame(t_frames, t_roles), max(2, int(round(len(t_frames) * fps / t.fps))))
    a_roles, a = posed(takes[0].path)
    b_roles, b = posed(takes[1].path)
    o = body_frame(frames, roles)
    shared = [r for r in roles if r and r != 'hips' and r in a_roles and r in b_roles]
    def pick(x, x_roles):
        index = [x_roles.index(r) for r in shared]
        step = max(1, -(-len(x) // GAP_FRAMES))
        return [[f[i] for i in index] for f in x[::step]]
    o_b = pose_gap(pick(o, roles), pick(b, b_roles))
    a_b = pose_gap(pick(a, a_roles), pick(b, b_roles))
    row['to_b'] = ratio(o_b, a_b)
    row['len_b'] = len(frames) / len(b)


def transfer_measures(cli, row, takes, args, frames, names, roles, height, bvh, report):
    content = takes[0]
    c_names, c_frames, c_roles = cli.majors(content.path)
    # Strength 0 against the content, at the frames it shows.
    z_csv, z_rep = cli.file('s0', '.csv'), cli.file('s0', '.json')
    cli.run(*args, '--strength', '0', '--positions-out', z_csv, '--report', z_rep)
    z_names, z = read_positions(z_csv)
    zr = json.load(open(z_rep))
    row['s0'] = largest_error(z, select(c_frames, c_names, z_names), zr['takes'][0]['source_frames'], height)
    # The change made against the change asked for: (output - content) against (S - N), N the
    # content itself when it is its own neutral.
    period = lambda path: (cli.info(path).get('cycles') or {}).get('period_s') or 0.0
    # On the content's timeline (--timing content, the default) the output's period is the
    # content's by construction: compared, it would count against every output whose cycles
    # `info` finds and for none whose it does not.
    content_timing = '--timing' not in args or args[args.index('--timing') + 1] == 'content'
    out_f = features(frames, roles, height, 0.0 if content_timing else period(bvh))
    c_f = features(c_frames, c_roles, cli.body_height(content.path), content.period)
    n = takes[1] if len(takes) == 3 else content
    s = takes[-1]
    n_names, n_frames, n_roles = cli.majors(n.path)
    s_names, s_frames, s_roles = cli.majors(s.path)
    wanted = change(features(s_frames, s_roles, cli.body_height(s.path), s.period),
                    features(n_frames, n_roles, cli.body_height(n.path), n.period))
    row['dir_cos'], row['dir_size'] = direction(change(out_f, c_f), wanted)
    if len(takes) == 2:  # one style clip, the content its own neutral: how far towards S, C's path kept
        row['way'] = way_to(change(out_f, c_f), wanted)
        row['hips'] = hips_stray(frames, select(c_frames, c_names, names), report['takes'][0]['source_frames'], height)


def fmt(v, spec, none='-'):
    return none if v is None else format(v, spec)


COLUMNS = [('#', lambda i, r: str(i)), ('what', lambda i, r: r['what']),
           ('takes', lambda i, r: ' + '.join(r['takes'])),
           ('cycles', lambda i, r: r['cycles']),
           ('s', lambda i, r: fmt(r.get('seconds'), '.1f')),
           ('cover', lambda i, r: fmt(r.get('cover'), '.0%')),
           ('seam', lambda i, r: fmt(r.get('seam'), '.2f', '')),
           ('fast', lambda i, r: fmt(r.get('fast'), '.2f')),
           ('feet', lambda i, r: fmt(r.get('feet'), '.2f')),
           ('s0 %h', lambda i, r: fmt(None if r.get('s0') is None else 100 * r['s0'], '.2f', '')),
           ('dir cos/size', lambda i, r: '' if r.get('dir_cos') is None else f'{r["dir_cos"]:+.2f}/{r["dir_size"]:.2f}'),
           ('way', lambda i, r: fmt(r.get('way'), '.0%', '')),
           ('hips', lambda i, r: fmt(r.get('hips'), '.2f', '')),
           ('toB', lambda i, r: fmt(r.get('to_b'), '.2f', '')),
           ('lenB', lambda i, r: fmt(r.get('len_b'), '.2f', '')),
           ('status', lambda i, r: r['status'])]


def table(rows):
    cells = [[c[0] for c in COLUMNS]] + [[f(i + 1, r) for _, f in COLUMNS] for i, r in enumerate(rows)]
    widths = [max(len(row[k]) for row in cells) for k in range(len(COLUMNS) - 1)]
    lines = []
    for n, row in enumerate(cells):
        lines.append('  '.join(c.ljust(w) if k < 3 else c.rjust(w) for k, (c, w) in enumerate(zip(row, widths))) +
                     '  ' + row[-1])
        if n == 0: lines.append('-' * len(lines[0]))
    return '\n'.join(lines)


def markdown_cell(text):
    """A table cell's text in Markdown: '|' escaped, line breaks as spaces."""
    return str(text).replace('\\', '\\\\').replace('|', '\\|').replace('\n', ' ')


def markdown_table(rows):
    """The rows as a Markdown table, the columns of `table`."""
    head = '| ' + ' | '.join(markdown_cell(c[0]) for c in COLUMNS) + ' |'
    rule = '|' + '|'.join('---' for _ in COLUMNS) + '|'
    body = ['| ' + ' | '.join(markdown_cell(f(i + 1, r)) for _, f in COLUMNS) + ' |' for i, r in enumerate(rows)]
    return '\n'.join([head, rule] + body)


def columns_legend():
    """The columns' meanings, as this file's docstring gives them."""
    doc = __doc__.split('Columns (see MEASURES below for each function):\n', 1)[1]
    return '\n'.join(line[2:] if line.startswith('  ') else line for line in doc.rstrip().split('\n'))


def markdown_page(command, summary, rows, totals):
    """docs/quality.md: what made it (command), the takes (summary), the table, the totals and
    the columns' meanings."""
    return '\n'.join([
        '# Quality run',
        '',
        'Generated by `tests/tools/quality_run.py` with `--markdown`; do not edit by hand. To make it',
        'again, from the repository root:',
        '',
        '```sh',
        command,
        '```',
        '',
        summary,
        '',
        markdown_table(rows),
        '',
        totals,
        '',
        '## Columns',
        '',
        '```text',
        columns_legend(),
        '```',
        ''])


def write_atomically(path, text):
    """Writes text to path through a temporary file in the same folder, renamed over it, so that
    a run stopped part way leaves the old page whole."""
    folder = os.path.dirname(os.path.abspath(path))
    fd, tmp = tempfile.mkstemp(prefix='.' + os.path.basename(path) + '.', dir=folder)
    try:
        with os.fdopen(fd, 'w') as fh:
            fh.write(text)
        os.chmod(tmp, 0o644)  # mkstemp's 0600 would stay on the page
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp): os.remove(tmp)
        raise


def command_line(argv):
    """The command as it was run, each argument quoted for a shell where it needs it."""
    import shlex
    return ' '.join(shlex.quote(a) for a in ['python3', 'tests/tools/quality_run.py'] + list(argv))


def takes_neutral_optional(cli):
    """Whether this CLI's transfer runs without --neutral (the content its own neutral)."""
    try:
        help_text = cli.run('transfer', '--help')
    except Failed:
        return False
    line = next((l for l in help_text.splitlines() if l.strip().startswith('--neutral')), '')
    return bool(line) and 'REQUIRED' not in line


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    ap.add_argument('cli', nargs='?')
    ap.add_argument('dirs', nargs='*')
    ap.add_argument('--quick', action='store_true', help='two pairings per class, one transfer per dataset, one mix')
    ap.add_argument('--per-class', type=int, default=0, help='pairings per blend class (default 6, --quick 2)')
    ap.add_argument('--json', help='write the rows as JSON here')
    ap.add_argument('--markdown', metavar='OUT.md',
                    help='write the table as a Markdown page here (docs/quality.md), through a temporary file')
    ap.add_argument('--only', action='append', default=[], metavar='TEXT',
                    help='make only the outputs whose row ("what: take + take") holds TEXT; repeatable')
    ap.add_argument('--timeout', type=float, default=600.0, help='seconds one command may take')
    ap.add_argument('--self-test', action='store_true', help='check the measures on synthetic motion and exit')
    a = ap.parse_args(argv)
    if a.self_test: return self_test()
    if not a.cli or not a.dirs: ap.error('give CLI and one or more DIR')
    t0 = time.time()
    cli = Cli(a.cli, tempfile.mkdtemp(prefix='quality-run-'), a.timeout)
    takes = []
    for d in a.dirs:
        for path in pick_takes(cli, d):
            try:
                takes.append(Take(cli, path, d))
            except (Failed, KeyError, ValueError) as e:
                print(f'  {short(path)}: not read ({e})', file=sys.stderr)
    by_name = {os.path.basename(t.path): t for t in takes}
    default = (by_name.get('bandai_walk_normal.bvh'), by_name.get('bandai_walk_old.bvh'))

    def style_pair(content):
        if default[0] and default[1]: return default
        own = [t for t in takes if t.folder == content.folder]
        return (own[0], own[1]) if len(own) >= 2 else (None, None)

    jobs = only(plan(takes, a.quick, a.per_class, style_pair, takes_neutral_optional(cli)), a.only)
    sets = datasets_of(takes)
    summary = (f'{len(takes)} takes in {len(sets)} datasets ('
               + ', '.join(f'{len(g)} {os.path.basename(g[0].folder.rstrip("/")) or g[0].folder}/{g[0].name}...'
                           for g in sets)
               + f'); {sum(t.loop for t in takes)} loops{"" if any(t.loop for t in takes) else " (no loop pairings)"}; '
               f'{len(jobs)} outputs')
    print(summary, flush=True)
    rows = []
    for kind, label, ts, options, weights in jobs:
        rows.append(measure(cli, kind, label, ts, options, weights))
        r = rows[-1]
        print(f'  {len(rows)}/{len(jobs)} {label}: {" + ".join(r["takes"])}: {r["status"]}', file=sys.stderr, flush=True)
    print(table(rows))
    failed = sum(r['status'] != 'ok' for r in rows)
    totals = (f'{len(rows)} outputs, {failed} not made or not measured; {cli.commands} commands, '
              f'{time.time() - t0:.0f} s')
    print(totals)
    if a.json:
        with open(a.json, 'w') as fh:
            json.dump({'cli': a.cli, 'dirs': a.dirs, 'quick': a.quick, 'rows': rows}, fh, indent=1)
    if a.markdown:
        write_atomically(a.markdown, markdown_page(command_line(argv), summary, rows, totals))
    return 0


# ----------------------------------------------------------------------------------------------
# SELF-TEST: the measures on synthetic motion worked out by hand.

def walker(frames=120, fps=30.0, speed=1.0, slide=0.0, period=1.0, glitch=None):
    """A stick body 1 high (hips, spine, head; per leg hip, knee, ankle, toe) walking along x at
    `speed` heights/s: each foot planted half the cycle (sliding `slide` heights/s), swinging the
    other half. Names and parents as a skeleton file gives them."""
    names = ['hips', 'spine', 'head', 'lhip', 'lknee', 'lankle', 'ltoe', 'rhip', 'rknee', 'rankle', 'rtoe']
    parent_of = {'hips': None, 'spine': 'hips', 'head': 'spine', 'lhip': 'hips', 'lknee': 'lhip',
                 'lankle': 'lknee', 'ltoe': 'lankle', 'rhip': 'hips', 'rknee': 'rhip', 'rankle': 'rknee',
                 'rtoe': 'rankle'}
    out = []
    for k in range(frames):
        t = k / fps
        x = speed * t
        f = [(x, 0.5, 0.0), (x, 0.7, 0.0), (x, 1.0, 0.0)]
        for side, z in ((0, 0.1), (1, -0.1)):
            phase = (t / period + 0.5 * side) % 1.0
            if phase < 0.5:  # planted: where it landed, sliding slowly
                landed = speed * (t - phase * period)
                fx, fy = landed + speed * 0.25 * period + slide * phase * period, 0.0
            else:  # swinging forward, lifted clear of the floor from its first frame to its last
                s = (phase - 0.5) * 2
                start = speed * (t - phase * period) + speed * 0.25 * period + slide * 0.5 * period
                fx = start + (speed * period - slide * 0.5 * period) * s
                fy = 0.1 * min(1.0, 4.0 * math.sin(math.pi * s))
            f += [(x, 0.5, z), (fx, 0.25 + fy, z), (fx, 0.05 + fy, z), (fx + 0.1, 0.0 + fy, z)]
        out.append(f)
    if glitch is not None: out[glitch] = [(p[0] + 0.5, p[1], p[2]) for p in out[glitch]]
    return names, parent_of, out


def self_test():
    checks = []

    def check(what, ok):
        checks.append((what, bool(ok)))

    # Coverage: every frame, every third frame (each within one of a shown one), half.
    check('cover all', shown_fraction(list(range(10)), 10) == 1.0)
    check('cover every third', shown_fraction([0, 3, 6, 9], 10) == 1.0)
    check('cover half', abs(shown_fraction([0, 1, 2, 3], 10) - 0.5) < 1e-12)
    check('cover posture-only frames skipped', shown_fraction([None, None], 10) == 0.0)
    check('cover a loop end shown as its start', shown_fraction([0, 2, 4, 6, 8], 10, 9.0) == 1.0)
    check('cover no loop, end unseen', shown_fraction([0, 2, 4, 6], 10) == 0.8)
    # Fastest move: one joint at 2 heights/s, a pop of 0.5 heights in one frame.
    line = [[(2.0 * k / 30.0, 0.0, 0.0), (0.0, 1.0, 0.0)] for k in range(300)]
    check('fast steady', abs(fastest_move(line, 30.0, 1.0) - 2.0) < 1e-9)
    check('fast read every 4th at a quarter rate', abs(fastest_move(line, 30.0, 1.0, 4) - 2.0) < 1e-9)
    popped = [list(f) for f in line]
    popped[150][0] = (popped[150][0][0] + 0.5, 0.0, 0.0)
    check('fast pop', fastest_move(popped, 30.0, 1.0) > 10.0)
    # Seam: a circle sampled so that the last step closes it; the same with the last frame pulled away.
    circle = [[(0.0, 0.0, 0.0), (math.cos(2 * math.pi * k / 40), 1.0, math.sin(2 * math.pi * k / 40))]
              for k in range(40)]
    check('seam closed', abs(seam_ratio(circle) - 1.0) < 1e-9)
    check('seam walking root', abs(seam_ratio([[(p[0] + 0.3 * k, p[1], p[2]) for p in f]
                                               for k, f in enumerate(circle)]) - 1.0) < 1e-9)
    check('seam open', seam_ratio(circle[:30]) > 5.0)
    # Feet and roles from the tree of a walker.
    names, parent_of, walk = walker()
    parents = major_parents(names, parent_of)
    check('major parents', parents == [-1, 0, 1, 0, 3, 4, 5, 0, 7, 8, 9])
    roles = major_roles(parents)
    check('roles', roles == ['hips', 'spine1', 'head0', 'L_leg0', 'L_leg1', 'L_leg2', 'L_leg3', 'R_leg0',
                             'R_leg1', 'R_leg2', 'R_leg3'])
    check('feet', foot_joints(roles) == [5, 6, 9, 10])
    check('way: part of the change', abs(way_to({'a': 0.3, 'b': 0.4}, {'a': 0.5, 'b': 0.5}) - 0.7) < 1e-12)
    check('way: none asked', way_to({'a': 1.0}, {'a': 0.0}) is None)
    moved = [[(p[0] + 0.3, p[1] + 1.0, p[2] - 0.4) for p in f] for f in walk]
    check('hips stray: horizontal only', abs(hips_stray(moved, walk, list(range(len(walk))), 2.0) - 0.25) < 1e-12)
    # Both legs on the first frame: a thigh from (0, 0.5) to (+-0.25, 0.25), a shin 0.2 long.
    check('leg length', abs(leg_length(walk, roles) - (math.sqrt(0.125) + 0.2)) < 1e-12)
    # A full skeleton: spine, chest carrying head and arms, a hand missing (left out of the majors).
    full = ['hips', 'spine', 'chest', 'head', 'ls', 'le', 'lw', 'rs', 're', 'rw', 'rh', 'lhip', 'lk', 'la', 'rhip', 'rk', 'ra']
    fp = {'hips': None, 'spine': 'hips', 'chest': 'spine', 'neck': 'chest', 'head': 'neck', 'lclav': 'chest',
          'ls': 'lclav', 'le': 'ls', 'lw': 'le', 'rs': 'chest', 're': 'rs', 'rw': 're', 'rh': 'rw', 'lhip': 'hips',
          'lk': 'lhip', 'la': 'lk', 'rhip': 'hips', 'rk': 'rhip', 'ra': 'rk'}
    fr = major_roles(major_parents(full, fp))
    check('roles of a full skeleton', fr == ['hips', 'spine1', 'chest', 'head0', 'L_arm0', 'L_arm1', 'L_arm2',
                                             'R_arm0', 'R_arm1', 'R_arm2', 'R_arm3', 'L_leg0', 'L_leg1', 'L_leg2',
                                             'R_leg0', 'R_leg1', 'R_leg2'])
    # Planted sliding: none for a clean walk, the slide's speed for one that slides.
    feet = foot_joints(roles)
    clean = planted_sliding(walk, 30.0, 1.0, feet)
    check('planted clean', clean is not None and clean < 1e-9)
    _, _, sliding = walker(slide=0.2)
    s = planted_sliding(sliding, 30.0, 1.0, feet)
    check('planted sliding', s is not None and abs(s - 0.2) < 0.05)
    check('by weight', abs(by_weight([0.1, 0.3], [0.5, 0.5]) - 0.2) < 1e-12 and by_weight([None], [1]) is None)
    # Largest error: the take against itself at its own frames, and shifted by 0.1 heights.
    check('error none', largest_error(walk, walk, list(range(len(walk))), 1.0) < 1e-12)
    shifted = [[(p[0], p[1] + 0.1, p[2]) for p in f] for f in walk]
    check('error shifted', abs(largest_error(shifted, walk, list(range(len(walk))), 1.0) - 0.1) < 1e-9)
    check('error between frames', largest_error([interpolate(walk, 10.5)], walk, [10.5], 1.0) < 1e-12)
    # Direction: a lower head (a stoop) made half as much as asked; the period change alone.
    stoop = [[(p[0], p[1] - (0.1 if j == 2 else 0.0), p[2]) for j, p in enumerate(f)] for f in walk]
    half = [[(p[0], p[1] - (0.05 if j == 2 else 0.0), p[2]) for j, p in enumerate(f)] for f in walk]
    base = features(walk, roles, 1.0, 1.0)
    cos, size = direction(change(features(half, roles, 1.0, 1.0), base), change(features(stoop, roles, 1.0, 1.0), base))
    check('direction same way, half size', abs(cos - 1.0) < 1e-9 and abs(size - 0.5) < 1e-9)
    cos, _ = direction(change(base, features(half, roles, 1.0, 1.0)), change(features(stoop, roles, 1.0, 1.0), base))
    check('direction opposite', abs(cos + 1.0) < 1e-9)
    check('direction none', direction(change(base, base), change(base, base)) == (None, None))
    slow = change(features(walk, roles, 1.0, 2.0), base)
    check('period feature', abs(slow['period'] - PERIOD_WEIGHT * math.log(2.0)) < 1e-12)
    # Cycles: one cycle over the whole take is a loop; a cycle over half is not.
    check('loop', cycles_of({'frames': 31, 'cycles': {'kind': 'gait', 'cycles': [{'start': 0, 'end': 30}]}}) ==
          (1, 'g', True))
    check('not a loop', cycles_of({'frames': 61, 'cycles': {'kind': 'gait', 'cycles': [{'start': 0, 'end': 30}]}})[2]
          is False)
    check('no cycles', cycles_of({'frames': 61, 'cycles': {'kind': 'none', 'cycles': []}}) == (0, 'n', False))
    # The CSV reader: joints in their first order, frames sorted.
    path = os.path.join(tempfile.mkdtemp(prefix='quality-run-test-'), 'p.csv')
    with open(path, 'w') as fh:
        fh.write('frame,joint,x,y,z\n1,b,4,5,6\n0,b,1,2,3\n0,a,0,0,0\n1,a,1,1,1\n')
    n, f = read_positions(path)
    check('csv', n == ['b', 'a'] and f == [[(1, 2, 3), (0, 0, 0)], [(4, 5, 6), (1, 1, 1)]])
    # The table: a failed row says why and keeps its place.
    text = table([{'what': 'blend same', 'takes': ['a', 'b'], 'cycles': '1g/2g', 'status': 'exit 1: no'},
                  {'what': 'mix', 'takes': ['a', 'b', 'c'], 'cycles': '1g/2g/0n', 'status': 'ok', 'cover': 1.0,
                   'fast': 1.1, 'feet': 0.9, 'seconds': 2.0}])
    check('table', 'exit 1: no' in text and '100%' in text and len(text.splitlines()) == 4)
    # The Markdown page: a header row, a rule and a row per output, a '|' in a status escaped;
    # written whole through a temporary file, which does not stay.
    md_rows = [{'what': 'blend same', 'takes': ['a', 'b'], 'cycles': '1g/2g', 'status': 'exit 1: a | b'},
               {'what': 'mix', 'takes': ['a', 'b', 'c'], 'cycles': '1g/2g/0n', 'status': 'ok', 'cover': 1.0,
                'fast': 1.1, 'feet': 0.9, 'seconds': 2.0}]
    md = markdown_table(md_rows).splitlines()
    check('markdown table', len(md) == 4 and md[1].count('|') == len(COLUMNS) + 1 and
          all(l.startswith('| ') and l.endswith(' |') for l in md[:1] + md[2:]))
    check('markdown cells', 'exit 1: a \\| b' in md[2] and '| 100% |' in md[3] and
          all(l.replace('\\|', '').count('|') == len(COLUMNS) + 1 for l in md))
    folder = tempfile.mkdtemp(prefix='quality-run-test-')
    page_path = os.path.join(folder, 'quality.md')
    with open(page_path, 'w') as fh:
        fh.write('old page\n')
    page = markdown_page(command_line(['build/app/mostyle-cli', 'a b', '--markdown', 'docs/quality.md']),
                         '2 takes in 1 datasets', md_rows, '2 outputs, 1 not made or not measured')
    write_atomically(page_path, page)
    with open(page_path) as fh:
        written = fh.read()
    check('markdown page written whole', written == page and os.listdir(folder) == ['quality.md'])
    check('markdown page header', written.startswith('# Quality run\n\nGenerated by `tests/tools/quality_run.py`')
          and "python3 tests/tools/quality_run.py build/app/mostyle-cli 'a b' --markdown docs/quality.md" in written)
    check('markdown page legend', '## Columns' in written and 'cover   fraction of the reference' in written)
    # The plan: every pairing class the takes have, transfers with their style pair, mixes.
    class Fake:
        def __init__(self, name, folder, skeleton, loop, count):
            self.name, self.path, self.folder, self.skeleton, self.loop, self.count = \
                name, name, folder, skeleton, loop, count
            self.kind, self.frames = 'g', 10 * count

        def cycles_label(self):
            return Take.cycles_label(self)

    fakes = [Fake('a1', 'd', 'A', False, 5), Fake('a2', 'd', 'A', False, 4), Fake('a3', 'd', 'A', False, 6),
             Fake('l1', 'w', 'L', True, 1), Fake('l2', 'w', 'L', True, 1), Fake('m1', 'w', 'M', True, 1)]
    jobs = plan(fakes, False, 0, lambda c: (fakes[0], fakes[1]), True)
    labels = [j[1] for j in jobs]
    check('plan classes', all(any(l.startswith(c) for l in labels)
                              for c in ('blend same', 'blend across', 'blend loop+loop --loop', 'blend loop+long',
                                        'transfer', 'transfer own', 'transfer clip', 'mix same', 'mix across',
                                        'mix loops')))
    check('plan: the longest gait take of a dataset styles the others',
          sorted(j[2][0].name for j in jobs if j[1] == 'transfer clip') == ['a1', 'a2', 'l2'])
    check('plan loop+loop has --loop', all('--loop' in j[3] for j in jobs if j[1].startswith('blend loop+loop')))
    check('plan loop+long both ways', {j[2][0].loop for j in jobs if j[1] == 'blend loop+long'} == {True, False})
    check('only: a row by its text', [job_text(j) for j in only(jobs, ['transfer clip: a2'])] ==
          ['transfer clip: a2 + a3'])
    check('only: none given keeps all', only(jobs, []) == jobs)
    check('plan quick is smaller', len(plan(fakes, True, 0, lambda c: (fakes[0], fakes[1]), True)) < len(jobs))
    # A command that fails is a row saying so.
    failing = Cli('false', tempfile.mkdtemp(prefix='quality-run-test-'), 10)
    row = measure(failing, 'blend', 'blend same', fakes[:2], ['--alpha', '0.5'], [0.5, 0.5])
    check('failed command is a row', row['status'].startswith('exit 1'))
    for what, ok in checks:
        if not ok: print(f'FAILED: {what}')
    failed = sum(not ok for _, ok in checks)
    print(f'quality_run self-test: {len(checks) - failed} passed, {failed} failed')
    return 1 if failed else 0


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
