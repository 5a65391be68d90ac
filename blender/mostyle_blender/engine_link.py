"""Finds the mostyle module: the copy installed in this add-on's lib/ folder first (where
blender/install.sh puts it), else any on Python's path (a build tree a developer added)."""
import importlib
import os
import sys

_LIB = os.path.join(os.path.dirname(os.path.abspath(__file__)), "lib")


class MissingModule(RuntimeError):
    pass


def module():
    """The mostyle module; MissingModule with what to do when it is absent."""
    if os.path.isdir(_LIB) and _LIB not in sys.path:
        sys.path.insert(0, _LIB)
    try:
        return importlib.import_module("mostyle")
    except ImportError as e:
        raise MissingModule("the mostyle Python module is not installed (%s): run blender/install.sh" % e) from e


def error_types():
    """The exceptions that are the person's input, not our bug: mostyle.Error and ValueError."""
    try:
        return (module().Error, ValueError)
    except MissingModule:
        return (ValueError,)
