"""An action's F-curves on every Blender the add-on runs in.

Up to 4.3 an action is a flat list of F-curves (`action.fcurves`). Blender 4.4 made actions
slotted: curves live in a channelbag per slot, on a layer's keyframe strip; 4.4 and 4.5 keep
`action.fcurves` as a view of the first slot's curves, and 5.0 removes it. The add-on's actions
animate one armature each, through their first slot, so that first slot's curves are the ones
read and written here, whichever API the running Blender has.
"""


def _legacy(action):
    return getattr(action, "fcurves", None)


def _channelbag(action, create):
    """The first slot's channelbag on the first layer's first strip (made, with its slot, layer
    and strip, when `create`); None when the action has none."""
    slots, layers = action.slots, action.layers
    if len(slots) == 0:
        if not create:
            return None
        slots.new(id_type='OBJECT', name=action.name)
    if len(layers) == 0:
        if not create:
            return None
        layers.new("Layer")
    strips = layers[0].strips
    if len(strips) == 0:
        if not create:
            return None
        strips.new(type='KEYFRAME')
    slot = slots[0]
    bag = strips[0].channelbag(slot)
    if bag is None and create:
        bag = strips[0].channelbags.new(slot)
    return bag


def curves(action):
    """The F-curves the action plays (its first slot's); an empty list where it has none yet."""
    legacy = _legacy(action)
    if legacy is not None:
        return legacy
    bag = _channelbag(action, create=False)
    return bag.fcurves if bag is not None else []


def ensure_curve(action, path, index, group):
    """The F-curve of `path`[`index`] in the action's first slot, made in `group` if it has none."""
    legacy = _legacy(action)
    if legacy is not None:
        curve = legacy.find(path, index=index)
        return curve if curve is not None else legacy.new(path, index=index, action_group=group)
    bag = _channelbag(action, create=True)
    curve = bag.fcurves.find(path, index=index)
    return curve if curve is not None else bag.fcurves.new(path, index=index, group_name=group)


def clear(action):
    """Removes every F-curve of the action's first slot."""
    curves(action).clear()


