#!/usr/bin/env bash
# The test command: installs what is missing, builds, and runs the whole test suite with ctest.
# Tests that need the real CMU takes (../shared/data/mocap) skip with a message when absent.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/build.sh"
build_dir="${MOTIF_BUILD_DIR:-$root/build}"
cd "$build_dir"
ctest --output-on-failure -j "${MOTIF_JOBS:-2}" "$@"
