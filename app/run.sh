#!/usr/bin/env bash
# Builds mostyle (installing what it needs) and opens the editor: on the bundled example pair,
# or on the BVH files given. Other editor flags pass through (see `mostyle --help`).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
"$root/app/install-deps.sh"
export CCACHE_BASEDIR="$root" CCACHE_NOHASHDIR=1  # ccache keys relative to the clone
cmake -S "$root" -B "$root/build" >/dev/null
cmake --build "$root/build" -j"$(nproc)" --target mostyle mostyle-cli
exec "$root/build/app/mostyle" "$@"
