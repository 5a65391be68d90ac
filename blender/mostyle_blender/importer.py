"""File > Import > Import with mostyle: a take read by mostyle's own readers (BVH, FBX, glTF,
FILE#ANIM for one animation of several) as an armature playing it."""
import os
import traceback

import bpy
import numpy as np
from bpy_extras.io_utils import ImportHelper

from . import styling, takes as take_io

# A bone with no child to point at, or a zero offset, gets this fraction of the body's height.
_LEAF_LENGTH = 0.05


def rest_heads(take):
    """Each joint's rest position (joints, 3), Take units and axes."""
    offsets = np.asarray(take.offsets, dtype=float)
    parents = list(take.parents)
    heads = np.zeros_like(offsets)
    for j in take_io._parents_first_indices(parents):
        heads[j] = offsets[j] + (heads[parents[j]] if parents[j] >= 0 else 0.0)
    if parents.count(-1) == 1:
        # The root's own offset is where its position channels would put it; the first frame
        # places the armature, so the rest skeleton starts at the origin.
        heads -= heads[parents.index(-1)]
    return heads


def build_armature(context, take, name):
    """A new armature object in the active collection with the Take's skeleton as its rest pose
    (each joint's head at its rest position, Blender's Z up)."""
    heads = rest_heads(take) @ take_io._Z_TO_Y  # Y up to Z up
    parents = list(take.parents)
    height = max(float(np.ptp(heads[:, 2])), float(np.ptp(heads, axis=0).max()), 1e-6)
    data = bpy.data.armatures.new(name)
    obj = bpy.data.objects.new(name, data)
    context.collection.objects.link(obj)
    for o in context.view_layer.objects:
        o.select_set(False)
    context.view_layer.objects.active = obj
    obj.select_set(True)
    bpy.ops.object.mode_set(mode='EDIT')
    children = {j: [c for c, p in enumerate(parents) if p == j] for j in range(len(parents))}
    edit = []
    for j, joint in enumerate(take.joint_names):
        bone = data.edit_bones.new(joint)
        bone.head = heads[j]
        tail = None
        for c in children[j]:
            if np.linalg.norm(heads[c] - heads[j]) > 1e-6 * height:
                tail = heads[c]
                break
        if tail is None:
            direction = heads[j] - heads[parents[j]] if parents[j] >= 0 else np.array([0.0, 0.0, 1.0])
            if np.linalg.norm(direction) < 1e-6 * height:
                direction = np.array([0.0, 0.0, 1.0])
            tail = heads[j] + direction / np.linalg.norm(direction) * _LEAF_LENGTH * height
        bone.tail = tail
        edit.append(bone)
    for j, p in enumerate(parents):
        if p >= 0:
            edit[j].parent = edit[p]
    bpy.ops.object.mode_set(mode='OBJECT')
    for pb in obj.pose.bones:
        pb.rotation_mode = 'QUATERNION'
    return obj


def import_take(context, path, take_name=None, use_scene_fps=False):
    """Reads `path` (FILE#ANIM picks an animation) with mostyle and adds an armature playing it
    from the scene's start frame; the scene's rate becomes the take's when use_scene_fps."""
    mostyle = styling.module()
    if take_name is None and "#" in os.path.basename(path):
        path, take_name = path.rsplit("#", 1)
    take = mostyle.read(path, take=take_name) if take_name else mostyle.read(path)
    scene = context.scene
    if use_scene_fps:
        fps = float(take.fps)
        scene.render.fps = max(1, round(fps))
        scene.render.fps_base = scene.render.fps / fps
    name = take_name or os.path.splitext(os.path.basename(path))[0]
    obj = build_armature(context, take, name)
    action = bpy.data.actions.new(name)
    take_io.write_take_action(take, obj, action, scene.frame_start, take_io.scene_fps(scene))
    # Assigned once keyed: Blender 4.4+ gives an object the slot of an action assigned to it only
    # if the action has one (the keys make it).
    obj.animation_data_create().action = action
    end = int(np.ceil(action.frame_range[1]))
    if end > scene.frame_end:
        scene.frame_end = end
    return obj


class MOSTYLE_OT_import_take(bpy.types.Operator, ImportHelper):
    """Read a BVH, FBX or glTF take with mostyle's readers, as an armature with its action"""
    bl_idname = "mostyle.import_take"
    bl_label = "Import with mostyle"
    bl_options = {'REGISTER', 'UNDO'}

    filter_glob: bpy.props.StringProperty(default="*.bvh;*.fbx;*.glb;*.gltf", options={'HIDDEN'})
    take: bpy.props.StringProperty(
        name="Animation", description="The file's animation to read (FBX, glTF); empty: the first, or FILE#ANIM's")
    use_scene_fps: bpy.props.BoolProperty(
        name="Scene Frame Rate", description="Set the scene's frame rate to the take's", default=False)

    def execute(self, context):
        try:
            obj = import_take(context, self.filepath, self.take or None, self.use_scene_fps)
        except Exception as e:
            traceback.print_exc()
            self.report({'ERROR'}, styling.one_line(e))
            return {'CANCELLED'}
        self.report({'INFO'}, "mostyle: imported '%s'" % obj.name)
        return {'FINISHED'}


def menu_import(self, context):
    self.layout.operator(MOSTYLE_OT_import_take.bl_idname, text="Import with mostyle (.bvh, .fbx, .glb)")


classes = (MOSTYLE_OT_import_take,)
