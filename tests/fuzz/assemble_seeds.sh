#!/usr/bin/env bash
# Assembles the fuzz targets' seeds from the repository's real files into OUT/<target>/:
# each take in assets/motions (and ../shared/motions when present) cut to its header and 5
# frames, byte for byte (CRLF, tabs kept); the mapping files of assets/mappings; the FBX and glTF
# files of ../shared/motions/formats as they are (libFuzzer cuts them to max_len); all of these
# again for the writers' target (write). The small
# hand-written seeds are in tests/fuzz/seeds/ (CSV and JOBS lines have no real files to use).
#   tests/fuzz/assemble_seeds.sh OUT
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
out="${1:?usage: assemble_seeds.sh OUT}"
mkdir -p "$out/bvh" "$out/mapping" "$out/gltf" "$out/fbx" "$out/write"
cut() {  # every line up to "Frame Time", then 5 more; awk splits on LF only, so CRs stay
  awk 'BEGIN { n = -1 } { print } /^[ \t]*Frame Time/ { n = 0; next } n >= 0 && ++n >= 5 { exit }' "$1" > "$2"
}
for f in "$root"/assets/motions/*.bvh; do cut "$f" "$out/bvh/assets_$(basename "$f")"; done
for f in "$root"/../shared/motions/*.bvh; do
  [ -f "$f" ] && cut "$f" "$out/bvh/shared_$(basename "$f")"
done
for f in "$root"/assets/mappings/*.txt; do cp "$f" "$out/mapping/"; done
for f in "$root"/../shared/motions/formats/*.glb "$root"/../shared/motions/formats/*.gltf; do
  [ -f "$f" ] && cp "$f" "$out/gltf/"
done
for f in "$root"/../shared/motions/formats/*.fbx; do
  [ -f "$f" ] && cp "$f" "$out/fbx/"
done
# The writers' target starts from every take the readers' targets start from.
cp "$out"/bvh/* "$out"/gltf/* "$out"/fbx/* "$out/write/" 2>/dev/null || true
true
