"""What the operator and the live preview share: take lists as text, the module's calls, and
where a result is written."""
from . import engine_link

PARTS = ("legs", "arms", "spine")


def parse_take(text, what="take"):
    """'Obj' or 'Obj:Action' to (object, action); ValueError naming what is wrong. An object's
    own name may hold ':', so the longest object name the text starts with wins."""
    import bpy
    text = text.strip()
    if not text:
        raise ValueError("a %s is empty: write Obj or Obj:Action" % what)
    obj, action_name = bpy.data.objects.get(text), None
    if obj is None:
        for cut in range(len(text) - 1, 0, -1):
            if text[cut] == ":" and text[:cut] in bpy.data.objects:
                obj, action_name = bpy.data.objects[text[:cut]], text[cut + 1:]
                break
    if obj is None:
        raise ValueError("no object is named '%s'" % text.split(":")[0])
    if obj.type != 'ARMATURE':
        raise ValueError("'%s' is a %s, not an armature" % (obj.name, obj.type.lower()))
    if action_name is None:
        action = obj.animation_data.action if obj.animation_data else None
        if action is None:
            raise ValueError("armature '%s' has no action: name one as %s:Action" % (obj.name, obj.name))
    else:
        action = bpy.data.actions.get(action_name)
        if action is None:
            raise ValueError("no action is named '%s'" % action_name)
    return obj, action


def parse_takes(text):
    takes = [parse_take(t) for t in text.split(",")] if text.strip() else []
    if not takes:
        raise ValueError("no takes: write takes=\"Obj[:Action],Obj[:Action],...\"")
    return takes


def parse_numbers(text, count, what):
    """A comma-separated list of `count` numbers; None for empty text."""
    if not text.strip():
        return None
    try:
        values = [float(v) for v in text.split(",")]
    except ValueError:
        raise ValueError("%s '%s' are not numbers separated by commas" % (what, text)) from None
    if len(values) != count:
        raise ValueError("%d %s for %d takes: give one per take" % (len(values), what, count))
    return values


def parse_part_weights(text, count):
    """'legs:w1,w2;arms:w1,w2' to {part: [weights]}; None for empty text."""
    if not text.strip():
        return None
    out = {}
    for item in text.split(";"):
        part, _, values = item.partition(":")
        part = part.strip()
        if not values:
            raise ValueError("part weights '%s' need PART:w1,w2,..." % item)
        out[part] = parse_numbers(values, count, part + " weights")
    return out


def style(mostyle, mode, takes, weights, part_weights, neutral, strength, fps):
    """The module's result for takes (Takes or paths; the first is the reference, or a transfer's
    content). A transfer's styles are the other takes, each at strength times its weight."""
    if mode == 'MIX':
        if len(takes) < 2:
            raise ValueError("a mix needs two takes or more; this has %d" % len(takes))
        return mostyle.mix(takes, weights=weights, part_weights=part_weights, fps=fps)
    if len(takes) < 2:
        raise ValueError("a transfer needs the content and at least one style take")
    styles = takes[1:]
    strengths = [strength * w for w in weights[1:]] if weights else [strength] * len(styles)
    parts = None
    if part_weights:
        parts = {p: [strength * w for w in ws[1:]] for p, ws in part_weights.items()}
    options = {"fps": fps}
    if parts:
        options["part_strength"] = parts
    return mostyle.transfer(takes[0], styles if len(styles) > 1 else styles[0], neutral=neutral,
                            strength=strengths if len(strengths) > 1 else strengths[0], **options)


def styled_action_name(action):
    return action.name + "_styled"


def protect(action):
    """Keeps an original action saved with the file once the armature plays another."""
    if action.users <= 1 and not action.use_fake_user:
        action.use_fake_user = True


def one_line(error):
    """An exception as the one line the person sees (the traceback goes to the console)."""
    text = str(error).strip()
    return text.splitlines()[0] if text else type(error).__name__


def module():
    return engine_link.module()
