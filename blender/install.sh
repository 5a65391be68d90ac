#!/usr/bin/env bash
# Installs the Blender add-on mostyle_blender with the mostyle Python module it runs on.
#   blender/install.sh                     build the module (or use build/'s), install for every
#                                          Blender on the PATH (its user add-ons folder)
#   blender/install.sh --build DIR         use (and make) the module in the build folder DIR
#   blender/install.sh --blender PATH      install for that Blender program
#   blender/install.sh --addons DIR        install into DIR (an add-ons folder) instead
# BLENDER_USER_SCRIPTS, when set, is where Blender looks for scripts: the add-on goes to its
# addons/. Then turn it on in Preferences > Add-ons (search "mostyle"), or from Python with
# addon_utils.enable("mostyle_blender").
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="$root/build"
blender_program=""
addons=""
while [ $# -gt 0 ]; do
  case "$1" in
    --build) build="$(realpath -m "${2:?--build needs a folder}")"; shift 2 ;;
    --blender) blender_program="${2:?--blender needs a program}"; shift 2 ;;
    --addons) addons="${2:?--addons needs a folder}"; shift 2 ;;
    -h|--help) sed -n '2,10p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "install.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done

module() { ls "$build"/python/mostyle*.so 2>/dev/null | head -n 1; }

if [ -z "$(module)" ]; then
  echo "mostyle: building the Python module in $build"
  export CCACHE_BASEDIR="$root" CCACHE_NOHASHDIR=1
  cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DMOSTYLE_BUILD_PYTHON=ON >/dev/null
  cmake --build "$build" --target mostyle_python -j"${JOBS:-$(nproc)}"
fi
so="$(module)"
if [ -z "$so" ]; then
  echo "install.sh: no mostyle module was built in $build/python (is pybind11-dev installed?)" >&2
  exit 1
fi

# Each Blender names its own user add-ons folder (3.4: ~/.config/blender/3.4/scripts/addons; 4.x
# likewise; BLENDER_USER_SCRIPTS moves it), so ask it rather than guess.
folders=()
if [ -n "$addons" ]; then
  folders+=("$addons")
elif [ -n "${BLENDER_USER_SCRIPTS:-}" ]; then
  folders+=("$BLENDER_USER_SCRIPTS/addons")
else
  programs=()
  if [ -n "$blender_program" ]; then programs+=("$blender_program")
  else
    while IFS= read -r p; do programs+=("$p"); done < <(type -ap blender | awk '!seen[$0]++')
  fi
  if [ ${#programs[@]} -eq 0 ]; then
    echo "install.sh: no blender on the PATH; name one with --blender or a folder with --addons" >&2
    exit 1
  fi
  for program in "${programs[@]}"; do
    folder="$("$program" -b --factory-startup --python-expr \
      "import bpy; print('mostyle-addons=' + bpy.utils.user_resource('SCRIPTS', path='addons', create=True))" \
      2>/dev/null | sed -n 's/^mostyle-addons=//p' | tail -n 1)"
    if [ -z "$folder" ]; then
      echo "install.sh: $program did not say where its add-ons go" >&2
      exit 1
    fi
    folders+=("$folder")
  done
fi

for folder in "${folders[@]}"; do
  target="$folder/mostyle_blender"
  mkdir -p "$folder"
  # A copy made anew: an old module or a removed file must not linger.
  rm -rf "$target.new"
  cp -r "$root/blender/mostyle_blender" "$target.new"
  find "$target.new" -name __pycache__ -prune -exec rm -rf {} +
  mkdir -p "$target.new/lib"
  cp "$so" "$target.new/lib/"
  rm -rf "$target"
  mv "$target.new" "$target"
  echo "mostyle: installed the add-on in $target"
done
echo "mostyle: turn it on in Blender's Preferences > Add-ons (search \"mostyle\")"
