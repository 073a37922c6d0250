#!/usr/bin/env bash
# The test command: installs what is missing, builds, and runs the fast tier of the test suite
# with ctest (every test but those labelled `slow`: tests/tiers/slow_tests.cmake).
#
#   scripts/test.sh [--slow | --all] [CTEST ARGUMENTS...]
#
# --slow runs the slow tier only, --all both; CI runs the fast tier, then the slow one
# (.ci/run). Tests that need the real CMU takes (../shared/data/mocap) skip with a message when
# they are absent. MOTIF_BUILD_DIR sets the build directory, MOTIF_JOBS the parallel jobs (2).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
tier=(-LE slow)
case "${1:-}" in
  --slow) tier=(-L slow); shift ;;
  --all) tier=(); shift ;;
esac
"$root/scripts/build.sh"
build_dir="${MOTIF_BUILD_DIR:-$root/build}"
cd "$build_dir"
ctest --output-on-failure -j "${MOTIF_JOBS:-2}" "${tier[@]}" "$@"
