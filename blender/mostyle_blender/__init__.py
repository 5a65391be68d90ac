"""mostyle in Blender: mix the styles of armatures' actions, or transfer a style onto one, with
the mostyle engine (its Python module), from a sidebar tab, an operator and an importer."""

bl_info = {
    "name": "mostyle",
    "author": "mostyle",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "3D View > Sidebar > mostyle; File > Import > Import with mostyle",
    "description": "Mix and transfer motion styles between armatures' actions",
    "category": "Animation",
}

if "bpy" in locals():
    import importlib
    for _name in ("quaternions", "takes", "engine_link", "styling", "operators", "importer", "preview", "panel"):
        if _name in locals():
            importlib.reload(locals()[_name])

import bpy

from . import engine_link, importer, operators, panel, preview, quaternions, styling, takes

_classes = operators.classes + importer.classes + panel.classes


def register():
    for cls in _classes:
        bpy.utils.register_class(cls)
    panel.register_properties()
    bpy.types.TOPBAR_MT_file_import.append(importer.menu_import)


def unregister():
    preview.stop()
    bpy.types.TOPBAR_MT_file_import.remove(importer.menu_import)
    panel.unregister_properties()
    for cls in reversed(_classes):
        bpy.utils.unregister_class(cls)
