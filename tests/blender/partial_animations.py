"""Writes a glTF robot with 14 animations, 12 of which move only some of its joints, for comparing
how mostyle and Blender read a joint that an animation does not move (glTF 2.0: a node no channel
targets keeps its own translation, rotation and scale).

usage: blender -b --factory-startup --python tests/blender/partial_animations.py -- OUT.glb

The rig: an armature node turned a quarter about X and scaled 100 (a Z-up file in centimetres, as
FBX2glTF writes them), hips, spine, head, arms and legs, each joint with a rest rotation of its
own; the skin's inverse bind matrices are of a bind pose turned off the rest pose (25 degrees about
a slanted axis), so Blender's bones (made in the bind pose) differ from the nodes' rest. Keys at 30
per second, LINEAR. The first two animations key every joint's rotation; the others a random few
(fixed seed), the hips' translation too where they key the hips. Deterministic: the same bytes on
every run.
"""
import json
import math
import random
import struct
import sys

from mathutils import Matrix, Quaternion, Vector

FPS = 30
NAMES = ["Dance", "Death", "Idle", "Jump", "No", "Punch", "Running", "Sitting", "Standing", "ThumbsUp",
         "Walking", "WalkJump", "Wave", "Yes"]


def quat(axis, degrees):
    """(x, y, z, w) of a turn about axis."""
    q = Quaternion(Vector(axis).normalized(), math.radians(degrees))
    return [q.x, q.y, q.z, q.w]


class Rig:
    def __init__(self):
        self.nodes = []

    def node(self, name, translation, rotation=None, scale=None, parent=None):
        n = {"name": name, "translation": translation}
        if rotation:
            n["rotation"] = rotation
        if scale:
            n["scale"] = scale
        self.nodes.append(n)
        index = len(self.nodes) - 1
        if parent is not None:
            self.nodes[parent].setdefault("children", []).append(index)
        return index

    def world(self):
        """Each node's rest world matrix."""
        parent = {c: i for i, n in enumerate(self.nodes) for c in n.get("children", [])}
        out = {}
        for i, n in enumerate(self.nodes):  # parents come first
            x, y, z, w = n.get("rotation", [0, 0, 0, 1])
            local = (Matrix.Translation(n["translation"]) @ Quaternion((w, x, y, z)).to_matrix().to_4x4() @
                     Matrix.Diagonal(list(n.get("scale", [1, 1, 1])) + [1]))
            out[i] = out[parent[i]] @ local if i in parent else local
        return out


def robot():
    r = Rig()
    root = r.node("RobotArmature", [0, 0, 0], quat([1, 0, 0], -90), [100, 100, 100])
    hips = r.node("Hips", [0, 0, 0.009], quat([1, 0, 0], 90), None, root)
    abdomen = r.node("Abdomen", [0, 0.002, 0], quat([0, 0, 1], 5), None, hips)
    torso = r.node("Torso", [0, 0.003, 0], quat([1, 0, 0], -8), None, abdomen)
    neck = r.node("Neck", [0, 0.004, 0], None, None, torso)
    r.node("Head", [0, 0.001, 0], quat([0, 1, 0], 10), None, neck)
    for side, sx in (("L", 1), ("R", -1)):
        shoulder = r.node("Shoulder." + side, [sx * 0.001, 0.003, 0], quat([0, 0, 1], -sx * 90), None, torso)
        upper = r.node("UpperArm." + side, [0, 0.002, 0], quat([0, 0, 1], -sx * 30), None, shoulder)
        lower = r.node("LowerArm." + side, [0, 0.0025, 0], quat([1, 0, 0], 20), None, upper)
        r.node("Palm." + side, [0, 0.002, 0], None, None, lower)
    for side, sx in (("L", 1), ("R", -1)):
        upper = r.node("UpperLeg." + side, [sx * 0.0012, -0.0005, 0], quat([0, 0, 1], 180), None, hips)
        lower = r.node("LowerLeg." + side, [0, 0.0042, 0], quat([1, 0, 0], -5), None, upper)
        r.node("Foot." + side, [0, 0.0040, 0], quat([1, 0, 0], 60), None, lower)
    return r, root, hips


class Buffer:
    def __init__(self):
        self.bytes = bytearray()
        self.views = []
        self.accessors = []

    def add(self, values, type_, count, minmax=False):
        self.bytes.extend(b"\0" * (-len(self.bytes) % 4))
        offset = len(self.bytes)
        self.bytes.extend(struct.pack("<%df" % len(values), *values))
        self.views.append({"buffer": 0, "byteOffset": offset, "byteLength": 4 * len(values)})
        accessor = {"bufferView": len(self.views) - 1, "componentType": 5126, "count": count, "type": type_}
        if minmax:
            accessor["min"] = [min(values)]
            accessor["max"] = [max(values)]
        self.accessors.append(accessor)
        return len(self.accessors) - 1


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if len(argv) != 1:
        print(__doc__.split("\n\n")[1])
        sys.exit(2)
    rng = random.Random(3)
    rig, root, hips = robot()
    joints = list(range(1, len(rig.nodes)))
    buffer = Buffer()
    world = rig.world()
    bind_turn = Quaternion(Vector((0.3, 1, 0.2)).normalized(), math.radians(25)).to_matrix().to_4x4()
    inverse_binds = []
    for j in joints:
        inverse = (world[j] @ bind_turn).inverted()
        inverse_binds += [inverse[r][c] for c in range(4) for r in range(4)]  # column-major
    binds = buffer.add(inverse_binds, "MAT4", len(joints))
    animations = []
    for index, name in enumerate(NAMES):
        channels, samplers = [], []
        keyed = joints[:] if index < 2 else sorted(rng.sample(joints, rng.randint(2, len(joints) // 2)))
        keys = int(round(rng.uniform(0.5, 2.0) * FPS)) + 1
        times = buffer.add([k / FPS for k in range(keys)], "SCALAR", keys, True)
        for j in keyed:
            rest = rig.nodes[j].get("rotation", [0, 0, 0, 1])
            rest = Quaternion((rest[3], rest[0], rest[1], rest[2]))
            axis = Vector((rng.random() - 0.5, rng.random() - 0.5, rng.random() - 0.5)).normalized()
            amplitude, phase = rng.uniform(10, 40), rng.uniform(0, 2 * math.pi)
            rotations = []
            for k in range(keys):
                q = Quaternion(axis, math.radians(amplitude * math.sin(phase + 2 * math.pi * k / keys))) @ rest
                rotations += [q.x, q.y, q.z, q.w]
            samplers.append({"input": times, "output": buffer.add(rotations, "VEC4", keys), "interpolation": "LINEAR"})
            channels.append({"sampler": len(samplers) - 1, "target": {"node": j, "path": "rotation"}})
            if j == hips:
                base = rig.nodes[j]["translation"]
                translations = []
                for k in range(keys):
                    translations += [base[0], base[1] + 0.0005 * math.sin(2 * math.pi * k / keys), base[2]]
                samplers.append({"input": times, "output": buffer.add(translations, "VEC3", keys),
                                 "interpolation": "LINEAR"})
                channels.append({"sampler": len(samplers) - 1, "target": {"node": j, "path": "translation"}})
        animations.append({"name": name, "channels": channels, "samplers": samplers})
    buffer.bytes.extend(b"\0" * (-len(buffer.bytes) % 4))
    doc = {"asset": {"version": "2.0", "generator": "mostyle tests/blender/partial_animations.py"}, "scene": 0,
           "scenes": [{"nodes": [root]}], "nodes": rig.nodes,
           "skins": [{"joints": joints, "inverseBindMatrices": binds, "skeleton": root}],
           "animations": animations, "accessors": buffer.accessors, "bufferViews": buffer.views,
           "buffers": [{"byteLength": len(buffer.bytes)}]}
    text = json.dumps(doc).encode()
    text += b" " * (-len(text) % 4)
    data = bytes(buffer.bytes)
    with open(argv[0], "wb") as out:
        out.write(b"glTF" + struct.pack("<II", 2, 28 + len(text) + len(data)) + struct.pack("<I", len(text)) +
                  b"JSON" + text + struct.pack("<I", len(data)) + b"BIN\0" + data)


main()
