"""Quaternion and matrix arithmetic on numpy arrays of any leading shape, (..., 4) as w, x, y, z:
a whole take's frames and bones at once, where mathutils would loop in Python."""
import numpy as np


def multiply(a, b):
    """a * b: apply b, then a. a, b: (..., 4)."""
    aw, ax, ay, az = np.moveaxis(a, -1, 0)
    bw, bx, by, bz = np.moveaxis(b, -1, 0)
    return np.stack([aw * bw - ax * bx - ay * by - az * bz,
                     aw * bx + ax * bw + ay * bz - az * by,
                     aw * by - ax * bz + ay * bw + az * bx,
                     aw * bz + ax * by - ay * bx + az * bw], -1)


def conjugate(q):
    return q * np.array([1.0, -1.0, -1.0, -1.0])


def normalized(q):
    return q / np.linalg.norm(q, axis=-1, keepdims=True)


def cross(a, b):
    """a x b over (..., 3), broadcast; np.cross's axis handling costs more than the products."""
    ax, ay, az = a[..., 0], a[..., 1], a[..., 2]
    bx, by, bz = b[..., 0], b[..., 1], b[..., 2]
    return np.stack([ay * bz - az * by, az * bx - ax * bz, ax * by - ay * bx], -1)


def rotate(q, v):
    """v (..., 3) turned by unit q (..., 4)."""
    w = q[..., :1]
    u = q[..., 1:]
    t = 2.0 * cross(u, v)
    return v + w * t + cross(u, t)


def to_matrix(q):
    """(..., 3, 3) rotation matrices of unit q (..., 4)."""
    w, x, y, z = np.moveaxis(q, -1, 0)
    return np.stack([np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)], -1),
                     np.stack([2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)], -1),
                     np.stack([2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)], -1)], -2)


def from_matrix(m):
    """Unit quaternions (..., 4) of rotation matrices m (..., 3, 3), any scale removed per column.
    Picks the largest of w, x, y, z to divide by, so that no case loses precision."""
    m = m / np.linalg.norm(m, axis=-2, keepdims=True)
    trace = m[..., 0, 0] + m[..., 1, 1] + m[..., 2, 2]
    candidates = np.stack([trace, m[..., 0, 0], m[..., 1, 1], m[..., 2, 2]], -1)
    pick = np.argmax(candidates, -1)
    q = np.empty(m.shape[:-2] + (4,))
    for case in range(4):
        s = pick == case
        if not np.any(s):
            continue
        r = m[s]
        if case == 0:
            t = np.sqrt(1.0 + r[:, 0, 0] + r[:, 1, 1] + r[:, 2, 2]) * 2
            q[s] = np.stack([t / 4, (r[:, 2, 1] - r[:, 1, 2]) / t, (r[:, 0, 2] - r[:, 2, 0]) / t,
                             (r[:, 1, 0] - r[:, 0, 1]) / t], -1)
        elif case == 1:
            t = np.sqrt(1.0 + r[:, 0, 0] - r[:, 1, 1] - r[:, 2, 2]) * 2
            q[s] = np.stack([(r[:, 2, 1] - r[:, 1, 2]) / t, t / 4, (r[:, 0, 1] + r[:, 1, 0]) / t,
                             (r[:, 0, 2] + r[:, 2, 0]) / t], -1)
        elif case == 2:
            t = np.sqrt(1.0 - r[:, 0, 0] + r[:, 1, 1] - r[:, 2, 2]) * 2
            q[s] = np.stack([(r[:, 0, 2] - r[:, 2, 0]) / t, (r[:, 0, 1] + r[:, 1, 0]) / t, t / 4,
                             (r[:, 1, 2] + r[:, 2, 1]) / t], -1)
        else:
            t = np.sqrt(1.0 - r[:, 0, 0] - r[:, 1, 1] + r[:, 2, 2]) * 2
            q[s] = np.stack([(r[:, 1, 0] - r[:, 0, 1]) / t, (r[:, 0, 2] + r[:, 2, 0]) / t,
                             (r[:, 1, 2] + r[:, 2, 1]) / t, t / 4], -1)
    return q


def continuous(q):
    """q (frames, ..., 4) with each frame's sign flipped to lie nearest the frame before, so that
    keys interpolated between frames take the short way round."""
    q = np.asarray(q, dtype=float)
    if len(q) < 2:
        return q.copy()
    turns = np.sign(np.sum(q[1:] * q[:-1], -1))
    turns[turns == 0] = 1.0
    signs = np.concatenate([np.ones((1,) + turns.shape[1:]), np.cumprod(turns, axis=0)])
    return q * signs[..., None]


def between(u, v):
    """The shortest turns (..., 4) taking directions u to v (..., 3); identity where either is
    zero, a half turn about a perpendicular where they are opposite."""
    un = u / np.maximum(np.linalg.norm(u, axis=-1, keepdims=True), 1e-300)
    vn = v / np.maximum(np.linalg.norm(v, axis=-1, keepdims=True), 1e-300)
    q = np.concatenate([1.0 + np.sum(un * vn, -1, keepdims=True), np.cross(un, vn)], -1)
    opposite = q[..., 0] < 1e-9
    if np.any(opposite):
        side = np.cross(un[opposite], [1.0, 0.0, 0.0])
        weak = np.linalg.norm(side, axis=-1) < 1e-6
        side[weak] = np.cross(un[opposite][weak], [0.0, 1.0, 0.0])
        q[opposite] = np.concatenate([np.zeros((len(side), 1)), side], -1)
    zero = (np.linalg.norm(u, axis=-1) < 1e-300) | (np.linalg.norm(v, axis=-1) < 1e-300)
    q[zero] = [1.0, 0.0, 0.0, 0.0]
    return normalized(q)
