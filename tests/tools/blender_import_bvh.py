"""Imports BVH files with Blender's own BVH importer (default settings), each into an empty scene,
and prints one line per file: its frames as Blender keys them, or why the import failed. For the
recordings of `mostyle-cli live --record`, which must import whole however the recorder ended
(kill -9 included).

usage: blender -b --factory-startup --python tests/tools/blender_import_bvh.py -- FILE.bvh ...

Exits 0 when every file imports as one armature with one action, 1 otherwise. Debian 12's
Blender 3.4 importer opens files with mode 'rU', which its Python 3.11 refuses: the script drops
the 'U' (universal newlines are Python 3's default), leaving the importer's parsing as it is.
"""
import builtins
import sys

import bpy

_open = builtins.open


def _open_without_u(file, mode="r", *args, **kwargs):
    return _open(file, mode.replace("U", ""), *args, **kwargs)


def main():
    builtins.open = _open_without_u
    paths = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    failed = 0
    for path in paths:
        bpy.ops.wm.read_factory_settings(use_empty=True)
        try:
            bpy.ops.import_anim.bvh(filepath=path)
        except Exception as e:  # the importer's error, as Blender reports it
            lines = [line.strip() for line in str(e).splitlines() if "Error" in line]
            print(f"{path}: failed: {lines[-1] if lines else str(e).strip()}")
            failed += 1
            continue
        armatures = [o for o in bpy.data.objects if o.type == "ARMATURE"]
        action = armatures[0].animation_data.action if len(armatures) == 1 and armatures[0].animation_data else None
        if action is None:
            print(f"{path}: failed: {len(armatures)} armatures, no action")
            failed += 1
            continue
        first, last = action.frame_range
        print(f"{path}: {int(last - first) + 1} frames")
    sys.exit(1 if failed else 0)


main()
