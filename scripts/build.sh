#!/usr/bin/env bash
# Installs what is missing, then configures and builds motifmine (Release) into build/.
# MOTIF_BUILD_DIR overrides the build directory; MOTIF_JOBS the parallel jobs (default 2).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/install_deps.sh"
source "$root/scripts/cmake_generator.sh"
build_dir="${MOTIF_BUILD_DIR:-$root/build}"
# shellcheck disable=SC2046  # the generator's words
cmake -S "$root" -B "$build_dir" $(generator_args "$build_dir") -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build_dir" -j "${MOTIF_JOBS:-2}"
"$root/scripts/install_npm_test_deps.sh" "$build_dir"
