#!/usr/bin/env bash
# Builds the libFuzzer targets (tests/fuzz/CMakeLists.txt: clang, ASan, UBSan) in build-fuzz/
# and runs each for SECONDS (default 30), seeded from tests/fuzz/seeds/, the repository's real
# files (assemble_seeds.sh) and tests/fuzz/regressions/. Exits 1 when any target crashed, leaked,
# timed out (10 s on one input) or went over 2 GB; the input is left in build-fuzz/findings/.
#   tests/fuzz/run.sh [SECONDS [TARGET...]]     targets: bvh mapping csv job_line session gltf fbx write axis
#   tests/fuzz/run.sh --fixed [TARGET...]
# SECONDS explores: a new random seed each run, and the corpus grows from run to run. --fixed is
# what CI runs: seed 1, a set number of inputs per target (about 20 s each on a 2-core machine)
# and a fresh corpus, so the same code tries the same inputs on any machine, and a CI failure
# is one command away from being seen here.
# A finding: fix the reader, copy the input to tests/fuzz/regressions/TARGET/ (the normal test
# build replays it: tests/fuzz/regressions_test.cpp).
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
fixed=0
seconds=30
if [ "${1:-}" = "--fixed" ]; then fixed=1; shift
elif [ $# -gt 0 ]; then seconds="$1"; shift; fi
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(bvh mapping csv job_line session gltf fbx write axis)
# Longest input per target: a BVH header of 38 joints and a few frames; a mapping file; a short
# CSV; a JOBS line; a session with per-component alphas and a palette; a GLB or FBX of a short
# take (the seeds: a few frames of a CMU skeleton, about 20 to 40 KB).
# write: any of these takes, written as FBX and GLB and read back. axis: a few stream lines.
declare -A max_len=([bvh]=16384 [mapping]=4096 [csv]=4096 [job_line]=4096 [session]=8192 [gltf]=65536
                    [fbx]=786432 [write]=786432 [axis]=4096)
# --fixed: inputs per target, about 20 s each (inputs measured in 20 s on a 2-core machine).
declare -A fixed_runs=([bvh]=250000 [mapping]=800000 [csv]=600000 [job_line]=450000 [session]=300000
                       [gltf]=50000 [fbx]=1200 [write]=3000 [axis]=170000)

"$root/app/install-deps.sh"
export CCACHE_BASEDIR="$root" CCACHE_NOHASHDIR=1  # ccache keys relative to the clone
build="$root/build-fuzz"
CC=clang CXX=clang++ cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DMOSTYLE_FUZZ=ON \
  -DMOSTYLE_BUILD_GUI=OFF -DMOSTYLE_BUILD_TESTS=OFF -DMOSTYLE_BUILD_BENCH=OFF >/dev/null
cmake --build "$build" -j"${MOSTYLE_BUILD_JOBS:-$(nproc)}" --target "${targets[@]/#/mostyle_fuzz_}"
rm -rf "$build/seeds"
"$root/tests/fuzz/assemble_seeds.sh" "$build/seeds"

export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
# Leaks inside system libraries, as the tests suppress them (assimp's FBX parser on bad input).
export LSAN_OPTIONS="suppressions=$root/tests/lsan.supp:print_suppressions=0"
failed=()
for t in "${targets[@]}"; do
  corpus="$build/corpus/$t"      # grows from run to run; new inputs are written here
  budget=(-max_total_time="$seconds")
  if [ $fixed = 1 ]; then
    corpus="$build/corpus-fixed/$t"
    rm -rf "$corpus"
    budget=(-seed=1 -runs="${fixed_runs[$t]}")
  fi
  findings="$build/findings/$t"
  log="$build/fuzz-$t.log"
  rm -rf "$findings"  # what this run finds, only
  mkdir -p "$corpus" "$findings"
  inputs=("$corpus")
  for d in "$build/seeds/$t" "$root/tests/fuzz/seeds/$t" "$root/tests/fuzz/regressions/$t"; do
    [ -d "$d" ] && inputs+=("$d")
  done
  dict=()
  [ -f "$root/tests/fuzz/$t.dict" ] && dict=(-dict="$root/tests/fuzz/$t.dict")
  if "$build/tests/fuzz/mostyle_fuzz_$t" "${budget[@]}" -max_len="${max_len[$t]}" \
       -rss_limit_mb=2048 -timeout=10 -print_final_stats=1 -artifact_prefix="$findings/" \
       "${dict[@]}" "${inputs[@]}" >"$log" 2>&1; then
    echo "fuzz $t: ok, $(sed -n 's/^stat::number_of_executed_units: *//p' "$log") inputs$([ $fixed = 1 ] && echo ", seed 1" || echo " in ${seconds} s")"
  else
    echo "fuzz $t: FAILED (log: $log, input: $findings/)"
    grep -E "^(==[0-9]+==ERROR|SUMMARY|.*runtime error|terminate called|  what\(\))" "$log" | head -6 || true
    # The input itself, when small enough to paste back from a CI log (base64).
    for f in "$findings"/*; do
      [ -f "$f" ] || continue
      if [ "$(stat -c %s "$f")" -le 4096 ]; then echo "input $(basename "$f") (base64):"; base64 -w 0 "$f"; echo
      else echo "input $(basename "$f"): $(stat -c %s "$f") bytes"; fi
    done
    failed+=("$t")
  fi
done
if [ ${#failed[@]} -gt 0 ]; then
  echo "fuzz: ${failed[*]} failed"
  exit 1
fi
