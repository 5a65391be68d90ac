"""The sidebar's mostyle tab: the active armature's takes with a weight each, the body parts'
own weights, mix or transfer, and the live preview."""
import traceback

import bpy

from . import action_curves, preview, styling


def _is_armature(self, obj):
    return obj.type == 'ARMATURE'


def _changed(self, context):
    """A weight, strength or part weight moved: the preview re-styles (a new set of takes, a
    new mode: a new preview session)."""
    obj = context.object
    if obj is None or obj.type != 'ARMATURE' or not obj.mostyle.use_preview:
        return
    settings = obj.mostyle
    try:
        refs, neutral = preview.settings_refs(settings, obj)
        key = (tuple((o.name, a.name) for o, a in refs), neutral and (neutral[0].name, neutral[1].name),
               settings.mode, preview.take_io.scene_fps(context.scene))
        session = preview.session()
        if session is None or session.key != key:
            preview.start(settings, obj)
        else:
            preview.request(settings)
    except Exception as e:
        traceback.print_exc()
        preview.status()["error"] = styling.one_line(e)


def _preview_toggled(self, context):
    if self.use_preview:
        _changed(self, context)
    else:
        preview.stop()


class MostyleTake(bpy.types.PropertyGroup):
    object: bpy.props.PointerProperty(name="Armature", type=bpy.types.Object, poll=_is_armature, update=_changed,
                                      description="The armature that plays the take")
    action: bpy.props.PointerProperty(name="Action", type=bpy.types.Action, update=_changed,
                                      description="The take's action; empty: the armature's current one")
    weight: bpy.props.FloatProperty(name="Weight", default=0.5, soft_min=-0.5, soft_max=1.5, update=_changed,
                                    description="How much of this take's style (a mix's weights sum to 1; a transfer's scale a style's strength)")
    legs: bpy.props.FloatProperty(name="Legs", default=0.5, soft_min=-0.5, soft_max=1.5, update=_changed,
                                  description="This take's weight for the legs")
    arms: bpy.props.FloatProperty(name="Arms", default=0.5, soft_min=-0.5, soft_max=1.5, update=_changed,
                                  description="This take's weight for the arms")
    spine: bpy.props.FloatProperty(name="Spine", default=0.5, soft_min=-0.5, soft_max=1.5, update=_changed,
                                   description="This take's weight for the spine and head")


class MostyleSettings(bpy.types.PropertyGroup):
    takes: bpy.props.CollectionProperty(type=MostyleTake)
    active: bpy.props.IntProperty(name="Active Take")
    mode: bpy.props.EnumProperty(
        name="Mode", update=_changed,
        items=[('MIX', "Mix", "Mix the takes' styles with the weights; the first take is the reference"),
               ('TRANSFER', "Transfer", "Put the other takes' style change onto the first take")])
    neutral_object: bpy.props.PointerProperty(name="Neutral", type=bpy.types.Object, poll=_is_armature, update=_changed,
                                              description="Transfer: the armature playing the action without the style; empty: the first take is its own neutral")
    neutral_action: bpy.props.PointerProperty(name="Neutral Action", type=bpy.types.Action, update=_changed,
                                              description="The neutral's action; empty: its armature's current one")
    strength: bpy.props.FloatProperty(name="Strength", default=1.0, soft_min=-1.0, soft_max=2.0, update=_changed,
                                      description="Transfer: how much of the style change is added (0: the first take as it is)")
    use_parts: bpy.props.BoolProperty(name="Body Parts", default=False, update=_changed,
                                      description="Give the legs, arms and spine weights of their own")
    use_preview: bpy.props.BoolProperty(name="Live Preview", default=False, update=_preview_toggled,
                                        description="Play the styled result on the first take's armature while weights change")


def take_label(take):
    if take.object is None:
        return "(no armature)"
    action = take.action or preview.own_action(take.object)
    return "%s : %s" % (take.object.name, action.name if action else "(no action)")


def candidate_takes(context):
    """Every armature in the scene with each action that keys its bones: (object, action)."""
    out = []
    for obj in context.scene.objects:
        if obj.type != 'ARMATURE':
            continue
        names = {b.name for b in obj.data.bones}
        own = preview.own_action(obj)
        if own is not None:
            out.append((obj, own))
        for action in bpy.data.actions:
            if action is own:
                continue
            bones = {c.data_path.split('"')[1] for c in action_curves.curves(action) if c.data_path.startswith('pose.bones["')}
            if bones and len(bones & names) >= 0.5 * len(bones):
                out.append((obj, action))
    return out


def _candidate_items(self, context):
    items = []
    for obj, action in candidate_takes(context):
        key = obj.name + ":" + action.name
        items.append((key, "%s : %s" % (obj.name, action.name), "Armature %s playing %s" % (obj.name, action.name)))
    _candidate_items.keep = items  # Blender needs the strings kept alive while the menu shows
    return items or [("", "(no armatures with actions)", "")]


class MOSTYLE_OT_add_take(bpy.types.Operator):
    """Add an armature's action as a take of the active armature's mix"""
    bl_idname = "mostyle.add_take"
    bl_label = "Add Take"
    bl_options = {'REGISTER', 'UNDO'}
    bl_property = "take"

    take: bpy.props.EnumProperty(name="Take", items=_candidate_items)

    @classmethod
    def poll(cls, context):
        return context.object is not None and context.object.type == 'ARMATURE'

    def invoke(self, context, event):
        context.window_manager.invoke_search_popup(self)
        return {'RUNNING_MODAL'}

    def execute(self, context):
        settings = context.object.mostyle
        try:
            obj, action = styling.parse_take(self.take)
        except ValueError as e:
            self.report({'ERROR'}, str(e))
            return {'CANCELLED'}
        if not settings.takes:
            own = preview.own_action(context.object)
            if own is not None and (obj, action) != (context.object, own):
                first = settings.takes.add()
                first.object, first.action = context.object, own
        t = settings.takes.add()
        t.object, t.action = obj, action
        equal = 1.0 / len(settings.takes)
        for t in settings.takes:
            t.weight = t.legs = t.arms = t.spine = equal
        settings.active = len(settings.takes) - 1
        return {'FINISHED'}


def armature_with_takes(context):
    """Whether the active object is an armature with takes in its mostyle list."""
    return context.object is not None and context.object.type == 'ARMATURE' and len(context.object.mostyle.takes) > 0


class MOSTYLE_OT_remove_take(bpy.types.Operator):
    """Remove the selected take"""
    bl_idname = "mostyle.remove_take"
    bl_label = "Remove Take"
    bl_options = {'REGISTER', 'UNDO'}

    @classmethod
    def poll(cls, context):
        return armature_with_takes(context)

    def execute(self, context):
        settings = context.object.mostyle
        settings.takes.remove(settings.active)
        settings.active = max(0, min(settings.active, len(settings.takes) - 1))
        return {'FINISHED'}


def take_spec(obj, action):
    """A take as style_action names it: "Obj:Action", "Obj" for its own action, "" for none."""
    if obj is None:
        return ""
    return obj.name + (":" + action.name if action else "")


def operator_arguments(settings):
    """The panel's settings as bpy.ops.mostyle.style_action's arguments."""
    takes = [take_spec(t.object, t.action) for t in settings.takes]
    args = {"takes": ",".join(takes), "weights": ",".join("%.9g" % t.weight for t in settings.takes),
            "mode": settings.mode, "strength": settings.strength, "neutral": ""}
    if settings.use_parts:
        args["part_weights"] = ";".join(p + ":" + ",".join("%.9g" % getattr(t, p) for t in settings.takes)
                                        for p in styling.PARTS)
    if settings.mode == 'TRANSFER' and settings.neutral_object is not None:
        args["neutral"] = take_spec(settings.neutral_object, settings.neutral_action)
    return args


class MOSTYLE_OT_apply(bpy.types.Operator):
    """Write the styled result as a new action '<reference action>_styled' on the first take's armature"""
    bl_idname = "mostyle.apply"
    bl_label = "Style Action"
    bl_options = {'REGISTER', 'UNDO'}

    @classmethod
    def poll(cls, context):
        return armature_with_takes(context)

    def execute(self, context):
        settings = context.object.mostyle
        if settings.use_preview:
            settings.use_preview = False
        try:
            return bpy.ops.mostyle.style_action(**operator_arguments(settings))
        except RuntimeError:  # style_action reported its error already
            return {'CANCELLED'}


class MOSTYLE_UL_takes(bpy.types.UIList):
    def draw_item(self, context, layout, data, item, icon, active_data, active_property, index=0):
        row = layout.row(align=True)
        row.label(text=("Ref: " if index == 0 else "") + take_label(item), icon='ARMATURE_DATA')
        row.prop(item, "weight", text="")


class MOSTYLE_PT_panel(bpy.types.Panel):
    bl_label = "mostyle"
    bl_idname = "MOSTYLE_PT_panel"
    bl_space_type = 'VIEW_3D'
    bl_region_type = 'UI'
    bl_category = "mostyle"

    @classmethod
    def poll(cls, context):
        return context.object is not None and context.object.type == 'ARMATURE'

    def draw(self, context):
        layout = self.layout
        settings = context.object.mostyle
        layout.prop(settings, "mode", expand=True)
        row = layout.row()
        row.template_list("MOSTYLE_UL_takes", "", settings, "takes", settings, "active", rows=3)
        column = row.column(align=True)
        column.operator("mostyle.add_take", icon='ADD', text="")
        column.operator("mostyle.remove_take", icon='REMOVE', text="")
        if 0 <= settings.active < len(settings.takes):
            take = settings.takes[settings.active]
            box = layout.box()
            box.prop(take, "object")
            box.prop(take, "action")
        layout.prop(settings, "use_parts")
        if settings.use_parts and settings.takes:
            grid = layout.grid_flow(columns=4, align=True)
            for label in ("Take", "Legs", "Arms", "Spine"):
                grid.label(text=label)
            for t in settings.takes:
                grid.label(text=t.object.name if t.object else "-")
                for p in styling.PARTS:
                    grid.prop(t, p, text="")
        if settings.mode == 'TRANSFER':
            box = layout.box()
            box.prop(settings, "neutral_object")
            if settings.neutral_object is not None:
                box.prop(settings, "neutral_action")
            box.prop(settings, "strength")
        layout.prop(settings, "use_preview")
        error = preview.status()["error"]
        if error:
            layout.label(text=error, icon='ERROR')
        session = preview.session()
        if session is not None and hasattr(session, "last_ms"):
            layout.label(text="preview: %.0f ms" % session.last_ms)
        layout.operator("mostyle.apply", icon='ACTION')


classes = (MostyleTake, MostyleSettings, MOSTYLE_OT_add_take, MOSTYLE_OT_remove_take, MOSTYLE_OT_apply,
           MOSTYLE_UL_takes, MOSTYLE_PT_panel)


def register_properties():
    bpy.types.Object.mostyle = bpy.props.PointerProperty(type=MostyleSettings)


def unregister_properties():
    del bpy.types.Object.mostyle
