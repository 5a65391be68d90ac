"""An armature's action as a mostyle Take, and a Take as an action of an armature.

A Take is a BVH-like skeleton: each joint's frame is the world's at rest (all rotations identity
is the rest pose), offsets are rest positions relative to the parent, rotations are local (w, x,
y, z) quaternions relative to the parent, Y up. Blender's bones carry rest orientations of their
own (a bone's Y axis runs head to tail) in a Z-up world, so both conversions go through world
space: a joint's rotation change from rest, D = world pose rotation * world rest rotation^-1, is
the same in either convention once the axes are turned Y up.
"""
import math
from types import SimpleNamespace

import numpy as np
from mathutils import Quaternion

from . import action_curves
from . import quaternions as qt

# Blender's Z-up world into a Take's Y-up one: (x, y, z) -> (x, z, -y), a quarter turn about X.
_Z_TO_Y = np.array([[1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, -1.0, 0.0]])
_Q_Z_TO_Y = np.array([math.cos(-math.pi / 4), math.sin(-math.pi / 4), 0.0, 0.0])


# A bone's translation from its parent further from its rest offset than this share of the
# rig's largest offset moves it (Blender's float32 matrices put a few 1e-7 on every bone).
_MOVED_BONE = 1e-5


def scene_fps(scene):
    return scene.render.fps / scene.render.fps_base


def skeleton_bones(obj):
    """The armature's bones a Take holds, parents first: the tree under the root bone with the
    most bones below it (a Take has one root; stray roots such as a mesh's helper bones are left
    out)."""
    bones = obj.data.bones
    roots = [b for b in bones if b.parent is None]
    if not roots:
        raise ValueError("armature '%s' has no bones" % obj.name)
    root = max(roots, key=lambda b: len(b.children_recursive))
    order = []
    stack = [root]
    while stack:
        b = stack.pop()
        order.append(b)
        stack.extend(reversed(b.children))
    return order


def action_times(action, fps):
    """The scene frames (possibly fractional) to sample an action at, and the rate they make.
    Keys spaced evenly closer than a frame (a 120 fps take in a 30 fps scene) are sampled where
    they lie, at their own rate, so that mostyle resamples the take as it does the file;
    anything else on every whole frame its keys span, at the scene's rate."""
    keys = set()
    for curve in action_curves.curves(action):
        points = curve.keyframe_points
        co = np.empty(2 * len(points), dtype=np.float32)
        points.foreach_get("co", co)
        keys.update(np.round(co[0::2].astype(float), 4))
    keys = np.array(sorted(keys))
    if len(keys) >= 3:
        steps = np.diff(keys)
        step = float(np.median(steps))
        if step < 1.0 - 1e-4 and np.all(np.abs(steps - step) < 1e-3):
            step = (keys[-1] - keys[0]) / (len(keys) - 1)
            return [keys[0] + i * step for i in range(len(keys))], fps / step
    start, end = action.frame_range
    first = int(math.ceil(start - 1e-4))
    last = int(math.floor(end + 1e-4))
    return [float(f) for f in range(first, max(first, last) + 1)], fps


class _ActionSwap:
    """Plays `action` alone on `obj` (its NLA off) while the block runs, then puts every value
    back: evaluating another action of an armature must leave the armature as it was."""

    def __init__(self, obj, action):
        self.obj, self.action = obj, action

    def __enter__(self):
        had = self.obj.animation_data is not None
        data = self.obj.animation_data_create()
        self.saved = (had, data.action, data.use_nla, data.action_influence, data.action_blend_type,
                      bpy_frame(self.obj))
        data.action = self.action
        play_first_slot(data)
        data.use_nla = False
        data.action_influence = 1.0
        data.action_blend_type = 'REPLACE'
        return self

    def __exit__(self, *exc):
        had, action, use_nla, influence, blend, frame = self.saved
        data = self.obj.animation_data
        data.action = action
        data.use_nla = use_nla
        data.action_influence = influence
        data.action_blend_type = blend
        if not had:
            self.obj.animation_data_clear()
        scene = _scene_of(self.obj)
        scene.frame_set(int(frame[0]), subframe=frame[1])
        return False


def play_first_slot(data):
    """Blender 4.4+ plays an action through one of its slots, and picks none when the action's
    slot has animated another ID (another armature's take): the first slot then, the one the
    curves read here are in. Older Blenders have no slots."""
    action = data.action
    if getattr(data, "action_slot", True) is None and action is not None and len(action.slots) > 0:
        data.action_slot = action.slots[0]


def bpy_frame(obj):
    scene = _scene_of(obj)
    return scene.frame_current, scene.frame_subframe


def _scene_of(obj):
    import bpy
    for scene in bpy.data.scenes:
        if obj.name in scene.objects:
            return scene
    raise ValueError("armature '%s' is in no scene, so Blender cannot play it" % obj.name)


def _world_matrices(obj, bones):
    """(bones, 4, 4) world matrices of the pose bones named by `bones` as Blender now poses them."""
    pose = obj.pose.bones
    flat = np.empty(len(pose) * 16, dtype=np.float32)
    pose.foreach_get("matrix", flat)
    # foreach_get hands matrices column by column.
    local = flat.reshape(len(pose), 4, 4).transpose(0, 2, 1).astype(float)
    index = {b.name: i for i, b in enumerate(pose)}
    world = np.array(obj.matrix_world, dtype=float)
    return world @ local[[index[b.name] for b in bones]]


def armature_take(mostyle, obj, action, played=False):
    """`action` played on armature `obj` as a mostyle.Take: every whole frame its keys span, at the
    scene's rate, as Blender evaluates it (constraints and drivers included), positions in
    Blender's units, Y up. Raises ValueError naming the armature when it cannot be read.

    Where the pose is the action's curves alone (no constraints or drivers, no object animation
    or parent, bones that inherit as Blender does by default), the curves are evaluated here, for
    all frames at once; else, or with `played`, Blender plays the action frame by frame."""
    if obj.type != 'ARMATURE':
        raise ValueError("'%s' is not an armature" % obj.name)
    bones = skeleton_bones(obj)
    scene = _scene_of(obj)
    frames, fps = action_times(action, scene_fps(scene))
    if len(frames) < 2:
        raise ValueError("action '%s' keys fewer than two frames" % action.name)
    world_rest = np.array(obj.matrix_world, dtype=float) @ np.array([np.array(b.matrix_local) for b in bones])
    rest_heads = world_rest[:, :3, 3] @ _Z_TO_Y.T
    rest_rot = qt.from_matrix(world_rest[:, :3, :3])
    if not played and _curves_alone(obj, action):
        poses = _curve_poses(obj, action, bones, np.asarray(frames, dtype=float))
    else:
        poses = np.empty((len(frames), len(bones), 4, 4))
        with _ActionSwap(obj, action):
            for i, f in enumerate(frames):
                whole = math.floor(f + 1e-6)
                scene.frame_set(int(whole), subframe=max(0.0, f - whole))
                poses[i] = _world_matrices(obj, bones)
    return _take_from_world(mostyle, bones, rest_heads, rest_rot, poses, fps)


def _curves_alone(obj, action):
    """Whether Blender's pose of `obj` playing `action` is the action's bone curves alone."""
    if obj.constraints or obj.parent is not None:
        return False
    data = obj.animation_data
    if data is not None and len(data.drivers) > 0:
        return False
    for pb in obj.pose.bones:
        b = pb.bone
        if pb.constraints or not b.use_inherit_rotation or b.inherit_scale != 'FULL' or not b.use_local_location \
                or b.use_relative_parent:
            return False
    return all(c.data_path.startswith('pose.bones["') for c in action_curves.curves(action))


def _curve_values(curve, frames):
    """The curve at `frames`: its keys interpolated where that is what Blender does (linear keys,
    or every frame on a key), else Blender's own evaluation frame by frame."""
    points = curve.keyframe_points
    co = np.empty(2 * len(points), dtype=np.float32)
    points.foreach_get("co", co)
    x, y = co[0::2].astype(float), co[1::2].astype(float)
    if len(x) == 0:
        return None
    if not curve.modifiers and curve.extrapolation == 'CONSTANT':
        modes = np.empty(len(points), dtype=np.int32)
        points.foreach_get("interpolation", modes)
        if np.all(modes[:-1] == _LINEAR) or _on_keys(frames, x):
            return np.interp(frames, x, y)
    return np.array([curve.evaluate(float(f)) for f in frames])


def _on_keys(frames, keys):
    """Whether every frame lies on a key (keys ascending)."""
    at = np.clip(np.searchsorted(keys, frames), 1, max(1, len(keys) - 1))
    near = np.minimum(np.abs(frames - keys[at - 1]), np.abs(frames - keys[np.minimum(at, len(keys) - 1)]))
    return bool(np.all(near < 1e-4))


def _euler_quaternions(angles, order):
    """(frames, 4) quaternions of Euler angles (frames, 3: x, y, z radians) in Blender's `order`
    ('XYZ': X turned first)."""
    axes = {"X": 0, "Y": 1, "Z": 2}
    q = np.tile([1.0, 0.0, 0.0, 0.0], (len(angles), 1))
    for axis in order:
        a = axes[axis]
        turn = np.zeros((len(angles), 4))
        turn[:, 0] = np.cos(angles[:, a] / 2)
        turn[:, 1 + a] = np.sin(angles[:, a] / 2)
        q = qt.multiply(turn, q)
    return q


def _curve_poses(obj, action, bones, frames):
    """(frames, bones, 4, 4) world matrices of `bones` as Blender poses them playing `action`,
    from its curves: parent pose @ (parent rest^-1 @ rest) @ basis, basis = location @ rotation
    @ scale, each channel without a curve at the pose bone's own value."""
    count = len(frames)
    curves = {}
    for c in action_curves.curves(action):
        curves[(c.data_path, c.array_index)] = c

    def channel(pb, prop, size):
        path = 'pose.bones["%s"].%s' % (_escape(pb.name), prop)
        own = np.array(getattr(pb, prop), dtype=float)
        out = np.tile(own, (count, 1))
        for i in range(size):
            c = curves.get((path, i))
            values = _curve_values(c, frames) if c is not None and not c.mute else None
            if values is not None:
                out[:, i] = values
        return out

    pose = {}
    order = []
    stack = [b for b in obj.data.bones if b.parent is None]
    while stack:
        b = stack.pop()
        order.append(b)
        stack.extend(b.children)
    for b in order:
        pb = obj.pose.bones[b.name]
        if pb.rotation_mode == 'QUATERNION':
            q = qt.normalized(channel(pb, "rotation_quaternion", 4))
        elif pb.rotation_mode == 'AXIS_ANGLE':
            v = channel(pb, "rotation_axis_angle", 4)
            axis = v[:, 1:] / np.maximum(np.linalg.norm(v[:, 1:], axis=1, keepdims=True), 1e-12)
            q = np.c_[np.cos(v[:, 0] / 2), axis * np.sin(v[:, 0] / 2)[:, None]]
        else:
            q = _euler_quaternions(channel(pb, "rotation_euler", 3), pb.rotation_mode)
        basis = np.tile(np.eye(4), (count, 1, 1))
        basis[:, :3, :3] = qt.to_matrix(q) * channel(pb, "scale", 3)[:, None, :]
        basis[:, :3, 3] = channel(pb, "location", 3)
        rest = np.array(b.matrix_local, dtype=float)
        if b.parent is None:
            pose[b.name] = rest @ basis
        else:
            relative = np.linalg.inv(np.array(b.parent.matrix_local, dtype=float)) @ rest
            pose[b.name] = pose[b.parent.name] @ relative @ basis
    world = np.array(obj.matrix_world, dtype=float)
    return np.stack([world @ pose[b.name] for b in bones], 1)


def _take_from_world(mostyle, bones, rest_heads, rest_rot, poses, fps):
    index = {b.name: i for i, b in enumerate(bones)}
    parents = [index[b.parent.name] if b.parent is not None and b.parent.name in index else -1 for b in bones]
    change = qt.multiply(qt.from_matrix(poses[:, :, :3, :3]), qt.conjugate(rest_rot)[None])
    change = qt.multiply(qt.multiply(_Q_Z_TO_Y, change), qt.conjugate(_Q_Z_TO_Y))
    local = change.copy()
    offsets = rest_heads.copy()
    for j, p in enumerate(parents):
        if p >= 0:
            local[:, j] = qt.multiply(qt.conjugate(change[:, p]), change[:, j])
            offsets[j] = rest_heads[j] - rest_heads[p]
    heads = poses[:, :, :3, 3] @ _Z_TO_Y.T
    root_positions = heads[:, 0]
    # A bone below the root moved by its location keys (Bandai's hips under a still root, a
    # rig's IK or prop bones): its translation from its parent, in the parent's posed frame, on
    # every frame; a rig whose bones all keep their rest offsets passes none.
    translations = np.broadcast_to(offsets, heads.shape).copy()
    for j, p in enumerate(parents):
        if p >= 0:
            translations[:, j] = qt.rotate(qt.conjugate(change[:, p]), heads[:, j] - heads[:, p])
    moved = np.abs(translations - offsets[None]).max() > _MOVED_BONE * max(1e-9, np.abs(offsets).max())
    return mostyle.Take(joint_names=[b.name for b in bones], parents=parents, offsets=offsets,
                        rotations=qt.normalized(qt.continuous(local)), root_positions=root_positions, fps=fps,
                        translations=translations if moved else None)


def position_targets(take):
    """{joint index: (frames, 3)} of the joints whose final positions a Take carries beside its
    rotations (a result: its major joints, as --positions-out; a take read from a file: every
    joint, position channels below the root included); {} for a Take without them."""
    positions = getattr(take, "positions", None)
    if positions is None:
        return {}
    positions = np.asarray(positions, dtype=float)
    frames = len(np.asarray(take.rotations))
    if positions.ndim == 2 and positions.shape[1] % 3 == 0:
        positions = positions.reshape(len(positions), -1, 3)
    if positions.ndim != 3 or positions.shape[0] != frames or positions.shape[2] != 3:
        return {}
    names = getattr(take, "position_joints", None)
    if not names:
        names = list(take.joint_names)
        if positions.shape[1] != len(names):
            report = getattr(take, "report", None) or {}
            names = report.get("joints") if isinstance(report, dict) else None
    if not names or len(names) != positions.shape[1]:
        return {}
    index = {n: i for i, n in enumerate(take.joint_names)}
    return {index[n]: positions[:, k] for k, n in enumerate(names) if n in index}


def _world_pose(take, targets=None, connected=()):
    """Each joint's world rotation (frames, joints, 4) and position (frames, joints, 3) of a Take,
    in Blender's Z-up world.

    Joints in `targets` ({index: (frames, 3)}, Take axes) are held to those positions: a joint
    whose one held child is that target is turned the least that points it there, and the
    target is placed there unless it is `connected` (Blender keeps a connected bone's head on
    its parent's tail whatever its location). Every other joint keeps its world rotation.
    Joints of one depth are worked out together, as each needs only its parent's."""
    targets = targets or {}
    local = np.asarray(take.rotations, dtype=float)
    offsets = np.asarray(take.offsets, dtype=float)
    parents = np.asarray(take.parents, dtype=int)
    frames, joints = local.shape[:2]
    held_children = {}
    for j in targets:
        if parents[j] >= 0:
            held_children.setdefault(int(parents[j]), []).append(j)
    levels = _depth_levels(parents)
    world = np.empty_like(local)
    for depth, level in enumerate(levels):
        world[:, level] = local[:, level] if depth == 0 else qt.multiply(world[:, parents[level]], local[:, level])
    rot = world.copy()
    pos = np.empty((frames, joints, 3))
    for depth, level in enumerate(levels):
        if depth == 0:
            pos[:, level] = np.asarray(take.root_positions, dtype=float)[:, None]
        else:
            above = parents[level]
            offset = np.broadcast_to(offsets[level], (frames, len(level), 3))
            pos[:, level] = pos[:, above] + qt.rotate(rot[:, above], offset)
        placed = [j for j in level if j in targets and j not in connected]
        if placed:
            pos[:, placed] = np.stack([targets[j] for j in placed], 1)
        turned = [j for j in level if len(held_children.get(j, ())) == 1]
        if turned:
            children = [held_children[j][0] for j in turned]
            have = qt.rotate(rot[:, turned], np.broadcast_to(offsets[children], (frames, len(turned), 3)))
            aim = np.stack([targets[c] for c in children], 1) - pos[:, turned]
            rot[:, turned] = qt.multiply(qt.between(have, aim), rot[:, turned])
    rot = qt.multiply(qt.multiply(qt.conjugate(_Q_Z_TO_Y), rot), _Q_Z_TO_Y)
    return rot, pos @ _Z_TO_Y


def _depth_levels(parents):
    """Joint indices by depth (parents: -1 for a root): the roots', their children's, and so on."""
    depth = np.zeros(len(parents), dtype=int)
    for j in _parents_first_indices(list(parents)):
        if parents[j] >= 0:
            depth[j] = depth[parents[j]] + 1
    return [np.flatnonzero(depth == d) for d in range(depth.max() + 1)] if len(parents) else []


def _parents_first_indices(parents):
    def depth(j):
        d = 0
        while parents[j] >= 0:
            j, d = parents[j], d + 1
        return d
    return sorted(range(len(parents)), key=depth)


def _compose(a, b):
    """Rigid transforms as (quaternion (..., 4), translation (..., 3)): a after b."""
    return qt.multiply(a[0], b[0]), a[1] + qt.rotate(a[0], np.broadcast_to(b[1], np.broadcast_shapes(
        np.shape(a[1]), np.shape(b[1]))))


def _inverse(a):
    q = qt.conjugate(a[0])
    return q, -qt.rotate(q, np.broadcast_to(a[1], np.broadcast_shapes(np.shape(q)[:-1] + (3,), np.shape(a[1]))))


def armature_rig(obj, joint_names):
    """What take_pose_bases needs of armature `obj` to pose it as Takes of joints `joint_names`,
    read once: its world transform, its pose bones' rests relative to their parents, and which
    bones the Take names. Valid while the armature's bones and placement stay as they are."""
    joint = {n: i for i, n in enumerate(joint_names)}
    world = np.array(obj.matrix_world, dtype=float)
    pose_bones = list(obj.pose.bones)
    index = {pb.name: i for i, pb in enumerate(pose_bones)}
    rest = np.array([np.array(pb.bone.matrix_local) for pb in pose_bones])
    rest_q, rest_t = qt.from_matrix(rest[:, :3, :3]), rest[:, :3, 3]
    parents = [index[pb.parent.name] if pb.parent is not None else -1 for pb in pose_bones]
    relative_q, relative_t = rest_q.copy(), rest_t.copy()
    for b, parent in enumerate(parents):
        if parent >= 0:
            relative_q[b], relative_t[b] = _compose(_inverse((rest_q[parent], rest_t[parent])), (rest_q[b], rest_t[b]))
    keyed = [pb.name in joint for pb in pose_bones]
    named = [b for b in range(len(pose_bones)) if keyed[b]]
    return SimpleNamespace(
        connected={joint[b.name] for b in obj.data.bones if b.use_connect and b.name in joint},
        world_q=qt.from_matrix(world[:3, :3]), world_inverse=np.linalg.inv(world), rest_q=rest_q,
        parents=parents, relative=(relative_q, relative_t), keyed=keyed, named=named,
        columns=[joint[pose_bones[b].name] for b in named],
        unnamed=[b for b in _parents_first(pose_bones) if not keyed[b]])


def take_pose_bases(take, obj, exact=True, rig=None):
    """The pose bones' matrix_basis that pose armature `obj` as the Take, as a rotation
    (frames, bones, 4: w, x, y, z) and a location (frames, bones, 3), for `obj`'s bones in
    obj.pose.bones order, and which of them the Take names. A bone the Take does not name keeps
    its rest relative to its parent. `rig`: armature_rig(obj, take.joint_names), read again
    when not given.

    A pose bone's armature-space transform is parent pose @ (parent rest^-1 @ rest) @ basis, and
    the wanted one is the Take's rotation change from rest applied to the bone's rest
    orientation, at the Take's joint position; the basis follows. Every transform is rigid (the
    armature's own scale is taken out of its world rotation), so each is a quaternion and a
    translation over all frames at once, never a matrix per key.

    With `exact`, a joint whose final position the result carries is placed there by the
    bone's location: a result's rotations are solved onto the rigid reference skeleton, which
    cannot always hold siblings where the mix put them (the hips' spine and legs), and the
    positions are the result."""
    rig = rig or armature_rig(obj, take.joint_names)
    rot, pos = _world_pose(take, position_targets(take) if exact else None, rig.connected)
    frames, bones = len(rot), len(rig.parents)
    named, columns = rig.named, rig.columns
    # Each bone's wanted armature-space transform; one more, the identity, is a root's parent.
    wanted_q = np.tile([1.0, 0.0, 0.0, 0.0], (frames, bones + 1, 1))
    wanted_t = np.zeros((frames, bones + 1, 3))
    # In armature space: world^-1 @ D @ world @ rest, the change applied where the bone is; all
    # the named bones at once.
    wanted_q[:, named] = qt.multiply(qt.multiply(qt.conjugate(rig.world_q), qt.multiply(rot[:, columns], rig.world_q)),
                                     rig.rest_q[named])
    wanted_t[:, named] = pos[:, columns] @ rig.world_inverse[:3, :3].T + rig.world_inverse[:3, 3]
    parent = np.array([p if p >= 0 else bones for p in rig.parents], dtype=int)
    relative_q, relative_t = rig.relative
    for b in rig.unnamed:
        wanted_q[:, b], wanted_t[:, b] = _compose((wanted_q[:, parent[b]], wanted_t[:, parent[b]]),
                                                  (relative_q[b], relative_t[b]))
    # basis = relative^-1 @ parent pose^-1 @ wanted, every named bone at once.
    above = parent[named]
    parent_pose = (wanted_q[:, above], wanted_t[:, above])
    basis = _compose(_inverse((relative_q[named], relative_t[named])),
                     _compose(_inverse(parent_pose), (wanted_q[:, named], wanted_t[:, named])))
    rotations = np.tile([1.0, 0.0, 0.0, 0.0], (frames, bones, 1))
    locations = np.zeros((frames, bones, 3))
    rotations[:, named] = basis[0]
    locations[:, named] = basis[1]
    return rotations, locations, rig.keyed


def _parents_first(pose_bones):
    depth = [len(pb.parent_recursive) for pb in pose_bones]
    return sorted(range(len(pose_bones)), key=lambda i: depth[i])


def write_take_action(take, obj, action, frame_start, fps, exact=True):
    """Keys `action` so that it plays the Take on armature `obj` from scene frame `frame_start`
    at scene rate `fps`: location and rotation of every bone the Take names, on every frame of
    the Take, linear between them. Any keys the action had on those channels are replaced.
    `exact`: see take_pose_bases."""
    rotations, locations, keyed = take_pose_bases(take, obj, exact)
    frames = frame_start + np.arange(len(rotations)) * (fps / float(take.fps))
    rotations = qt.continuous(qt.normalized(rotations))
    for b, pb in enumerate(obj.pose.bones):
        if not keyed[b]:
            continue
        base = 'pose.bones["%s"].' % _escape(pb.name)
        location = locations[:, b]
        for i in range(3):
            _key(action, base + "location", i, pb.name, frames, location[:, i])
        prop, values = _rotation_channels(rotations[:, b], pb.rotation_mode)
        for i in range(values.shape[1]):
            _key(action, base + prop, i, pb.name, frames, values[:, i])


def _rotation_channels(q, mode):
    """Unit quaternions q (frames, 4) as a pose bone of rotation `mode` holds them: its rotation
    property's name and values (frames, 4 or 3), Euler angles each nearest the frame before."""
    if mode == 'QUATERNION':
        return "rotation_quaternion", q
    if mode == 'AXIS_ANGLE':
        angle = 2 * np.arccos(np.clip(q[:, 0], -1, 1))
        axis = q[:, 1:] / np.maximum(np.linalg.norm(q[:, 1:], axis=1, keepdims=True), 1e-12)
        return "rotation_axis_angle", np.c_[angle, axis]
    eulers = np.empty((len(q), 3))
    previous = None
    for f in range(len(q)):
        e = Quaternion(q[f]).to_euler(mode, previous) if previous else Quaternion(q[f]).to_euler(mode)
        eulers[f] = e
        previous = e
    return "rotation_euler", eulers


def held_take(take):
    """A Take's arrays read out once, as a Take-like value whose frames take_frame picks without
    copying them again (each read of a mostyle.Take's array is a copy of the whole array)."""
    return SimpleNamespace(joint_names=list(take.joint_names), parents=list(take.parents),
                           offsets=np.asarray(take.offsets, dtype=float),
                           rotations=np.asarray(take.rotations, dtype=float),
                           root_positions=np.asarray(take.root_positions, dtype=float),
                           positions=np.asarray(take.positions, dtype=float),
                           position_joints=list(take.position_joints), fps=float(take.fps), report=None)


def take_frame(held, frame):
    """Frame `frame` of a held_take as a one-frame Take-like value."""
    one = slice(frame, frame + 1)
    return SimpleNamespace(**dict(vars(held), rotations=held.rotations[one], root_positions=held.root_positions[one],
                                  positions=held.positions[one]))


def take_index_at(take, scene_frame, frame_start, fps):
    """The Take's frame that write_take_action keys at `scene_frame` (or the nearest one; the
    first and last hold before and after it, as the action's curves do)."""
    index = int(round((scene_frame - frame_start) * float(take.fps) / fps))
    return min(max(index, 0), len(take.rotations) - 1)


def pose_take_frame(held, obj, frame, rig=None, exact=True):
    """Poses armature `obj`'s bones as frame `frame` of a held_take, as write_take_action's keys
    pose them there: the bones the Take names get its location and rotation, the others keep
    theirs. `rig`: as take_pose_bases's. Writes no keys; Blender shows the pose once it next
    evaluates the armature."""
    rotations, locations, keyed = take_pose_bases(take_frame(held, frame), obj, exact, rig)
    rotations = qt.normalized(rotations)
    for b, pb in enumerate(obj.pose.bones):
        if not keyed[b]:
            continue
        pb.location = locations[0, b].tolist()
        prop, values = _rotation_channels(rotations[:, b], pb.rotation_mode)
        setattr(pb, prop, values[0].tolist())


def _escape(name):
    return name.replace("\\", "\\\\").replace('"', '\\"')


_LINEAR = 1  # FCurve keyframe interpolation 'LINEAR' as foreach_set takes it


def _key(action, path, index, group, frames, values):
    curve = action_curves.ensure_curve(action, path, index, group)
    points = curve.keyframe_points
    fresh = len(points) != len(frames)
    if fresh:
        points.clear()
        points.add(len(frames))
        points.foreach_set("interpolation", [_LINEAR] * len(frames))
    co = np.empty(2 * len(frames), dtype=np.float32)
    co[0::2] = frames
    co[1::2] = values
    points.foreach_set("co", co)
    # Linear keys need no handles: only new keys need the curve's caches rebuilt; new values on
    # the same frames (the preview's every change) only need Blender told.
    if fresh:
        curve.update()
