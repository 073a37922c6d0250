#!/usr/bin/env bash
# The test suite once more under sanitizers (docs/reliability.md, "Sanitizers"); .ci/run calls it
# after scripts/test.sh.
#
#   scripts/test_sanitizers.sh [asan|tsan|all]     (default: all)
#
# asan: every test, built with AddressSanitizer (with LeakSanitizer) and
#       UndefinedBehaviorSanitizer, every report fatal, in build-asan/.
# tsan: the tests of the parallel parts (every test that compares thread counts or reads from
#       many threads, selected by name below), built with ThreadSanitizer in build-tsan/.
# Both builds use -O1 (the usual level for sanitizer runs: fast to compile, stacks still
# readable) and skip the benchmarks. MOTIF_JOBS sets the parallel jobs (default 2).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
jobs="${MOTIF_JOBS:-2}"
which="${1:-all}"
case "$which" in asan|tsan|all) ;; *) sed -n '2,13p' "${BASH_SOURCE[0]}" >&2; exit 2 ;; esac
"$root/scripts/install_deps.sh"

# The tests ThreadSanitizer runs: the parallel parts, by test name, and the test executables
# that hold them (tests/*/CMakeLists.txt).
tsan_tests='ThreadCount|Threads|ManyThreads|Concurrent|Sharded|OneAndTwoThreads|OneOrTwoThreads'
tsan_targets=(lsh_test distance_test ingest_test trellis_test signature_test cluster_test
              frame_file_test trellis_file_test)

configure() {  # configure DIR FLAG...
  local dir="$1"
  shift
  cmake -S "$root" -B "$dir" -DCMAKE_BUILD_TYPE=None -DCMAKE_CXX_FLAGS="-O1 -g" \
    -DMOTIF_BUILD_BENCHMARKS=OFF "$@" >/dev/null
}

if [ "$which" != tsan ]; then
  echo "== AddressSanitizer + UndefinedBehaviorSanitizer: the whole test suite"
  configure "$root/build-asan" -DMOTIF_ENABLE_SANITIZERS=ON
  cmake --build "$root/build-asan" -j "$jobs"
  (cd "$root/build-asan" &&
     ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1 \
     UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
     ctest --output-on-failure -j "$jobs")
fi

if [ "$which" != asan ]; then
  echo "== ThreadSanitizer: the parallel parts"
  configure "$root/build-tsan" -DMOTIF_ENABLE_TSAN=ON
  cmake --build "$root/build-tsan" -j "$jobs" --target "${tsan_targets[@]}"
  (cd "$root/build-tsan" &&
     TSAN_OPTIONS=halt_on_error=1:second_deadlock_stack=1 \
     ctest --output-on-failure -j "$jobs" -R "$tsan_tests")
fi
