"""The add-on's F-curve access on both of Blender's action models, without Blender: the flat
list of Blender up to 4.5 (`action.fcurves`) and the slotted actions of 5.0, which removed it
(curves in a channelbag per slot, on a layer's keyframe strip). Debian's Blender is 3.4, so the
5.0 model is played here by stand-ins with its API's names and signatures."""
import importlib.util
import pathlib

import pytest

_PATH = pathlib.Path(__file__).resolve().parents[2] / "blender" / "mostyle_blender" / "action_curves.py"
_SPEC = importlib.util.spec_from_file_location("action_curves", _PATH)
action_curves = importlib.util.module_from_spec(_SPEC)
_SPEC.loader.exec_module(action_curves)  # the package's __init__ needs bpy; this file does not


class Curve:
    def __init__(self, path, index, group):
        self.data_path, self.array_index, self.group = path, index, group


class Curves(list):
    """A collection of F-curves: find, new, remove and clear as Blender's have them."""

    def __init__(self, group_keyword):
        super().__init__()
        self.group_keyword = group_keyword  # 'action_group' (flat) or 'group_name' (channelbag)

    def find(self, path, *, index=0):
        return next((c for c in self if c.data_path == path and c.array_index == index), None)

    def new(self, path, *, index=0, **group):
        assert set(group) <= {self.group_keyword}, "a keyword this Blender does not take: %s" % group
        curve = Curve(path, index, group.get(self.group_keyword, ""))
        self.append(curve)
        return curve


class FlatAction:
    def __init__(self):
        self.fcurves = Curves("action_group")


class Channelbag:
    def __init__(self, slot):
        self.slot, self.fcurves = slot, Curves("group_name")


class Strip:
    def __init__(self):
        self.channelbags = type("Bags", (list,), {"new": lambda bags, slot: bags.append(Channelbag(slot)) or bags[-1]})()

    def channelbag(self, slot, ensure=False):
        return next((b for b in self.channelbags if b.slot is slot), None)


class Collection(list):
    def __init__(self, make):
        super().__init__()
        self.make = make

    def new(self, *args, **kwargs):
        self.append(self.make(*args, **kwargs))
        return self[-1]


class Layer:
    def __init__(self, name):
        self.name = name
        self.strips = Collection(lambda type: Strip())


class SlottedAction:
    """Blender 5.0's action: no `fcurves`."""

    def __init__(self, name="walk"):
        self.name = name
        self.slots = Collection(lambda id_type, name: type("Slot", (), {"id_type": id_type, "name": name})())
        self.layers = Collection(Layer)


@pytest.mark.parametrize("make", [FlatAction, SlottedAction])
def test_curves_are_made_once_found_again_and_cleared(make):
    action = make()
    assert list(action_curves.curves(action)) == []
    x = action_curves.ensure_curve(action, 'pose.bones["Hips"].location', 0, "Hips")
    y = action_curves.ensure_curve(action, 'pose.bones["Hips"].location', 1, "Hips")
    assert action_curves.ensure_curve(action, 'pose.bones["Hips"].location', 0, "Hips") is x
    assert list(action_curves.curves(action)) == [x, y]
    assert x.group == "Hips"
    action_curves.clear(action)
    assert list(action_curves.curves(action)) == []


def test_a_slotted_action_keys_its_first_slot_on_one_layer_and_strip():
    action = SlottedAction("bye_styled")
    action_curves.ensure_curve(action, 'pose.bones["Head"].rotation_quaternion', 3, "Head")
    action_curves.ensure_curve(action, 'pose.bones["Hips"].location', 0, "Hips")
    assert len(action.slots) == 1 and action.slots[0].id_type == 'OBJECT'
    assert len(action.layers) == 1 and len(action.layers[0].strips) == 1
    bags = action.layers[0].strips[0].channelbags
    assert len(bags) == 1 and bags[0].slot is action.slots[0]
    assert [c.array_index for c in bags[0].fcurves] == [3, 0]
