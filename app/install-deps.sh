#!/usr/bin/env bash
# Installs the Debian 12 packages mostyle builds with, when any is missing (sudo when not root).
#   app/install-deps.sh            what the build and tests/run.sh need
#   app/install-deps.sh --cluster  and a one-node Slurm for tests/cluster/slurm_test.sh
set -euo pipefail
# clang and libclang-rt-14-dev (libFuzzer, only a Recommends of clang): tests/fuzz/run.sh.
# libassimp-dev (reading FBX), zlib1g-dev (writing FBX) and libtinygltf-dev (glTF): engine/io.
# nodejs and npm: the Khronos glTF validator (npm package gltf-validator) that
# tests/tools/validate_gltf.js runs.
packages=(build-essential cmake pkg-config libeigen3-dev libglfw3-dev libglm-dev libimgui-dev
          libstb-dev libosmesa6-dev libgl-dev catch2 libbenchmark-dev nlohmann-json3-dev
          libcli11-dev xvfb xauth clang libclang-rt-14-dev ccache libassimp-dev zlib1g-dev
          libtinygltf-dev nodejs)
# slurm-wlm (slurmctld, slurmd, sbatch) and munge (its authentication): CI's real Slurm.
if [ "${1:-}" = "--cluster" ]; then packages+=(slurm-wlm munge); fi
# blender and python3-numpy (Debian's Blender imports glTF only with numpy): the [blender] tests
# open what mostyle writes with Blender's own importers, as an animator would.
packages+=(blender python3-numpy)
# pybind11-dev and python3-dev: the Python module (python/); python3-pytest runs its tests.
packages+=(pybind11-dev python3-dev python3-pytest)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
# npm: Debian's package, unless one is installed another way (nodejs.org's builds bring their own).
command -v npm >/dev/null 2>&1 || missing+=(npm)
as_root=()
[ "$(id -u)" -eq 0 ] || as_root=(sudo)
if [ ${#missing[@]} -gt 0 ]; then
  echo "mostyle: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  "${as_root[@]}" apt-get update -qq
  "${as_root[@]}" apt-get install -y -qq "${missing[@]}"
fi
# The Khronos glTF validator for the glTF tests (they skip, saying so, without it).
if ! [ -d "$(npm root -g 2>/dev/null)/gltf-validator" ]; then
  echo "mostyle: installing the npm package gltf-validator"
  "${as_root[@]}" npm install -g --silent gltf-validator || echo "mostyle: warning: could not install gltf-validator; the glTF tests skip the validator"
fi
