#!/usr/bin/env bash
# Installs the Debian 12 packages mostyle builds with, when any is missing (sudo when not root).
set -euo pipefail
# clang and libclang-rt-14-dev (libFuzzer, only a Recommends of clang): tests/fuzz/run.sh.
# libassimp-dev (FBX) and libtinygltf-dev (glTF): engine/io. nodejs and npm: the Khronos glTF
# validator (npm package gltf-validator) that tests/tools/validate_gltf.js runs.
packages=(build-essential cmake pkg-config libeigen3-dev libglfw3-dev libglm-dev libimgui-dev
          libstb-dev libosmesa6-dev libgl-dev catch2 libbenchmark-dev nlohmann-json3-dev
          libcli11-dev xvfb xauth clang libclang-rt-14-dev ccache libassimp-dev libtinygltf-dev
          nodejs npm)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0
echo "mostyle: installing ${missing[*]}"
as_root=()
[ "$(id -u)" -eq 0 ] || as_root=(sudo)
export DEBIAN_FRONTEND=noninteractive
"${as_root[@]}" apt-get update -qq
"${as_root[@]}" apt-get install -y -qq "${missing[@]}"
