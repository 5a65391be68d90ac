"""An armature's action as a mostyle Take, and a Take as an action of an armature.

A Take is a BVH-like skeleton: each joint's frame is the world's at rest (all rotations identity
is the rest pose), offsets are rest positions relative to the parent, rotations are local (w, x,
y, z) quaternions relative to the parent, Y up. Blender's bones carry rest orientations of their
own (a bone's Y axis runs head to tail) in a Z-up world, so both conversions go through world
space: a joint's rotation change from rest, D = world pose rotation * world rest rotation^-1, is
the same in either convention once the axes are turned Y up.
"""
import math

import numpy as np
from mathutils import Quaternion

from . import quaternions as qt

# Blender's Z-up world into a Take's Y-up one: (x, y, z) -> (x, z, -y), a quarter turn about X.
_Z_TO_Y = np.array([[1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, -1.0, 0.0]])
_Q_Z_TO_Y = np.array([math.cos(-math.pi / 4), math.sin(-math.pi / 4), 0.0, 0.0])


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
    for curve in action.fcurves:
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


def armature_take(mostyle, obj, action):
    """`action` played on armature `obj` as a mostyle.Take: every whole frame its keys span, at the
    scene's rate, as Blender evaluates it (constraints and drivers included), positions in
    Blender's units, Y up. Raises ValueError naming the armature when it cannot be read."""
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
    poses = np.empty((len(frames), len(bones), 4, 4))
    with _ActionSwap(obj, action):
        for i, f in enumerate(frames):
            whole = math.floor(f + 1e-6)
            scene.frame_set(int(whole), subframe=max(0.0, f - whole))
            poses[i] = _world_matrices(obj, bones)
    return _take_from_world(mostyle, bones, rest_heads, rest_rot, poses, fps)


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
    root_positions = poses[:, 0, :3, 3] @ _Z_TO_Y.T
    return mostyle.Take(joint_names=[b.name for b in bones], parents=parents, offsets=offsets,
                        rotations=qt.normalized(qt.continuous(local)), root_positions=root_positions, fps=fps)


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
    its parent's tail whatever its location). Every other joint keeps its world rotation."""
    targets = targets or {}
    local = np.asarray(take.rotations, dtype=float)
    offsets = np.asarray(take.offsets, dtype=float)
    parents = list(take.parents)
    frames, joints = local.shape[:2]
    held_children = {}
    for j in targets:
        if parents[j] >= 0:
            held_children.setdefault(parents[j], []).append(j)
    order = _parents_first_indices(parents)
    world = np.empty_like(local)
    for j in order:
        p = parents[j]
        world[:, j] = local[:, j] if p < 0 else qt.multiply(world[:, p], local[:, j])
    rot = world.copy()
    pos = np.empty((frames, joints, 3))
    for j in order:
        p = parents[j]
        if p < 0:
            pos[:, j] = np.asarray(take.root_positions, dtype=float)
        else:
            pos[:, j] = pos[:, p] + qt.rotate(rot[:, p], np.broadcast_to(offsets[j], (frames, 3)))
        if j in targets and j not in connected:
            pos[:, j] = targets[j]
        children = held_children.get(j, [])
        if len(children) == 1:
            c = children[0]
            have = qt.rotate(rot[:, j], np.broadcast_to(offsets[c], (frames, 3)))
            rot[:, j] = qt.multiply(qt.between(have, targets[c] - pos[:, j]), rot[:, j])
    rot = qt.multiply(qt.multiply(qt.conjugate(_Q_Z_TO_Y), rot), _Q_Z_TO_Y)
    return rot, pos @ _Z_TO_Y


def _parents_first_indices(parents):
    def depth(j):
        d = 0
        while parents[j] >= 0:
            j, d = parents[j], d + 1
        return d
    return sorted(range(len(parents)), key=depth)


def _inverse_rigid(m):
    """Inverse of (..., 4, 4) rotation-and-translation matrices."""
    out = np.zeros_like(m)
    r = np.swapaxes(m[..., :3, :3], -1, -2)
    out[..., :3, :3] = r
    out[..., :3, 3] = -(r @ m[..., :3, 3:])[..., 0]
    out[..., 3, 3] = 1.0
    return out


def take_pose_bases(take, obj, exact=True):
    """The pose bones' matrix_basis (frames, bones, 4, 4) that pose armature `obj` as the Take,
    for `obj`'s bones in obj.pose.bones order, and which of them the Take names. A bone the
    Take does not name keeps its rest relative to its parent.

    A pose bone's armature-space matrix is parent pose @ (parent rest^-1 @ rest) @ basis, and
    the wanted one is the Take's rotation change from rest applied to the bone's rest
    orientation, at the Take's joint position; the basis follows.

    With `exact`, a joint whose final position the result carries is placed there by the
    bone's location: a result's rotations are solved onto the rigid reference skeleton, which
    cannot always hold siblings where the mix put them (the hips' spine and legs), and the
    positions are the result."""
    joint = {n: i for i, n in enumerate(take.joint_names)}
    connected = {joint[b.name] for b in obj.data.bones if b.use_connect and b.name in joint}
    rot, pos = _world_pose(take, position_targets(take) if exact else None, connected)
    frames = len(rot)
    world = np.array(obj.matrix_world, dtype=float)
    world3 = world[:3, :3]
    world3_inverse = np.linalg.inv(world3)
    world_inverse = np.linalg.inv(world)
    pose_bones = list(obj.pose.bones)
    index = {pb.name: i for i, pb in enumerate(pose_bones)}
    rest = np.array([np.array(pb.bone.matrix_local) for pb in pose_bones])
    wanted = [None] * len(pose_bones)
    bases = np.tile(np.eye(4), (frames, len(pose_bones), 1, 1))
    keyed = [False] * len(pose_bones)
    for b in _parents_first(pose_bones):
        pb = pose_bones[b]
        parent = index[pb.parent.name] if pb.parent is not None else -1
        if parent >= 0:
            relative = _inverse_rigid(rest[parent]) @ rest[b]
            parent_pose = wanted[parent]
        else:
            relative = rest[b]
            parent_pose = np.tile(np.eye(4), (frames, 1, 1))
        j = joint.get(pb.name)
        if j is None:
            wanted[b] = parent_pose @ relative
            continue
        m = np.tile(np.eye(4), (frames, 1, 1))
        # In armature space: world^-1 @ D @ world @ rest, the change applied where the bone is.
        turn = qt.to_matrix(rot[:, j])
        m[:, :3, :3] = world3_inverse @ turn @ (world3 @ rest[b, :3, :3])
        m[:, :3, 3] = (np.c_[pos[:, j], np.ones(frames)] @ world_inverse.T)[:, :3]
        wanted[b] = m
        bases[:, b] = _inverse_rigid(relative) @ _inverse_rigid(parent_pose) @ m
        keyed[b] = True
    return bases, keyed


def _parents_first(pose_bones):
    depth = [len(pb.parent_recursive) for pb in pose_bones]
    return sorted(range(len(pose_bones)), key=lambda i: depth[i])


def write_take_action(take, obj, action, frame_start, fps, exact=True):
    """Keys `action` so that it plays the Take on armature `obj` from scene frame `frame_start`
    at scene rate `fps`: location and rotation of every bone the Take names, on every frame of
    the Take, linear between them. Any keys the action had on those channels are replaced.
    `exact`: see take_pose_bases."""
    bases, keyed = take_pose_bases(take, obj, exact)
    frames = frame_start + np.arange(len(bases)) * (fps / float(take.fps))
    for b, pb in enumerate(obj.pose.bones):
        if not keyed[b]:
            continue
        base = 'pose.bones["%s"].' % _escape(pb.name)
        location = bases[:, b, :3, 3]
        for i in range(3):
            _key(action, base + "location", i, pb.name, frames, location[:, i])
        q = qt.continuous(qt.from_matrix(bases[:, b, :3, :3]))
        if pb.rotation_mode == 'QUATERNION':
            for i in range(4):
                _key(action, base + "rotation_quaternion", i, pb.name, frames, q[:, i])
        elif pb.rotation_mode == 'AXIS_ANGLE':
            angle = 2 * np.arccos(np.clip(q[:, 0], -1, 1))
            axis = q[:, 1:] / np.maximum(np.linalg.norm(q[:, 1:], axis=1, keepdims=True), 1e-12)
            values = np.c_[angle, axis]
            for i in range(4):
                _key(action, base + "rotation_axis_angle", i, pb.name, frames, values[:, i])
        else:
            eulers = np.empty((len(q), 3))
            previous = None
            for f in range(len(q)):
                e = Quaternion(q[f]).to_euler(pb.rotation_mode, previous) if previous else \
                    Quaternion(q[f]).to_euler(pb.rotation_mode)
                eulers[f] = e
                previous = e
            for i in range(3):
                _key(action, base + "rotation_euler", i, pb.name, frames, eulers[:, i])


def _escape(name):
    return name.replace("\\", "\\\\").replace('"', '\\"')


_LINEAR = 1  # FCurve keyframe interpolation 'LINEAR' as foreach_set takes it


def _key(action, path, index, group, frames, values):
    curve = action.fcurves.find(path, index=index)
    if curve is None:
        curve = action.fcurves.new(path, index=index, action_group=group)
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
