"""bpy.ops.mostyle.style_action: a mix or transfer of armatures' actions, written as a new action."""
import traceback

import bpy

from . import action_curves, styling, takes as take_io


class MOSTYLE_OT_style_action(bpy.types.Operator):
    """Mix the takes' styles (or transfer them onto the first) into a new action on the first
    take's armature"""
    bl_idname = "mostyle.style_action"
    bl_label = "Style Action"
    bl_options = {'REGISTER', 'UNDO'}

    takes: bpy.props.StringProperty(
        name="Takes", description="Obj[:Action],Obj[:Action],...: the first is the reference (a transfer's content)")
    weights: bpy.props.StringProperty(
        name="Weights", description="w1,w2,...: one per take (a mix's sum to 1; a transfer's scale each style's strength); empty: equal")
    part_weights: bpy.props.StringProperty(
        name="Part Weights", description="legs:w1,w2,...;arms:...;spine:...: a body part's own weights, one per take")
    mode: bpy.props.EnumProperty(
        name="Mode", items=[('MIX', "Mix", "Mix the takes' styles with the weights"),
                            ('TRANSFER', "Transfer", "Put the style takes' change from the neutral onto the first take")],
        default='MIX')
    neutral: bpy.props.StringProperty(
        name="Neutral", description="Obj[:Action]: the action without the style (transfer); empty: the first take is its own")
    strength: bpy.props.FloatProperty(
        name="Strength", description="How much of the style change a transfer adds (0: the content as it is)",
        default=1.0, min=-1.0, max=2.0)
    exact_positions: bpy.props.BoolProperty(
        name="Exact Positions", default=True,
        description="Key the small bone translations that put each major joint where mostyle put it (off: rotations only, which the rigid skeleton cannot always fit to the mix)")

    def execute(self, context):
        try:
            action = self.style(context)
        except Exception as e:  # the person sees one line; the traceback is for the console
            traceback.print_exc()
            self.report({'ERROR'}, styling.one_line(e))
            return {'CANCELLED'}
        self.report({'INFO'}, "mostyle: wrote action '%s'" % action.name)
        return {'FINISHED'}

    def style(self, context):
        mostyle = styling.module()
        refs = styling.parse_takes(self.takes)
        weights = styling.parse_numbers(self.weights, len(refs), "weights")
        parts = styling.parse_part_weights(self.part_weights, len(refs))
        neutral = None
        if self.mode == 'TRANSFER' and self.neutral.strip():
            neutral = take_io.armature_take(mostyle, *styling.parse_take(self.neutral, "neutral"))
        fps = take_io.scene_fps(context.scene)
        takes = [take_io.armature_take(mostyle, obj, action) for obj, action in refs]
        result = styling.style(mostyle, self.mode, takes, weights, parts, neutral, self.strength, fps)
        obj, source = refs[0]
        return write_result(result, obj, source, fps, self.exact_positions)


def write_result(result, obj, source, fps, exact=True):
    """The result as action '<source>_styled' on obj (made anew, or its keys replaced), which
    obj then plays; `source` keeps its keys and stays saved."""
    name = styling.styled_action_name(source)
    action = bpy.data.actions.get(name)
    if action is None:
        action = bpy.data.actions.new(name)
    else:
        action_curves.clear(action)
    take_io.write_take_action(result, obj, action, source.frame_range[0], fps, exact)
    styling.protect(source)
    obj.animation_data_create().action = action
    return action


classes = (MOSTYLE_OT_style_action,)
