#!/usr/bin/env bash
# Builds mostyle and runs every test (installing what it needs first).
#   tests/run.sh                               normal build (build/), all tests
#   tests/run.sh --sanitize address,undefined  ASan+UBSan build (build-address-undefined/), all tests
#   tests/run.sh --sanitize thread             TSan build (build-thread/), the threaded tests
#                                              (worker, job runner, editor, ui)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
sanitize=""
if [ "${1:-}" = "--sanitize" ]; then sanitize="${2:?--sanitize needs a value}"; fi
"$root/app/install-deps.sh"
# ccache keys on paths relative to the clone, so another clone (CI's, a work tree) reuses its objects.
export CCACHE_BASEDIR="$root" CCACHE_NOHASHDIR=1

build="$root/build"
flags=(-DCMAKE_BUILD_TYPE=RelWithDebInfo)
filter=()
targets=()
if [ -n "$sanitize" ]; then
  build="$root/build-${sanitize//,/-}"
  flags+=(-DMOSTYLE_SANITIZE="$sanitize" -DMOSTYLE_BUILD_BENCH=OFF)
fi
if [ "$sanitize" = "thread" ]; then
  filter=(-R "worker|jobs:|editor|ui:")
  targets=(--target mostyle_worker_tests mostyle_job_runner_tests mostyle_editor_tests mostyle_ui_tests mostyle mostyle-cli)
  # Mesa's llvmpipe threads are not instrumented; render on the calling thread.
  export LP_NUM_THREADS=0
  export TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1"
fi
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1"
export LSAN_OPTIONS="suppressions=$root/tests/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"

cmake -S "$root" -B "$build" "${flags[@]}" >/dev/null
cmake --build "$build" -j"$(nproc)" "${targets[@]}"
# A test program that cannot start (a sanitizer's runtime refusing it) lists no tests, and ctest
# would then run none of them and pass: each must list its tests.
for program in "$build"/tests/mostyle_*_tests; do
  [ -x "$program" ] || continue
  listed="$("$program" --list-test-names-only 2>&1)" || true
  if [ -z "$listed" ]; then
    echo "$(basename "$program") does not start: it lists no tests"
    exit 1
  fi
done
ctest --test-dir "$build" --output-on-failure -j"$(nproc)" "${filter[@]}"
