#!/usr/bin/env bash
# Installs the Debian packages motifmine builds on, if any is missing. Safe to run repeatedly.
# Why each: ninja-build (the build scripts' generator when present: it builds the same tree
# faster than Make, docs/reliability.md), Boost (iostreams, interprocess mmap, program_options
# for the CLI), Eigen (pose math), oneTBB (parallel import and LSH shards), zstd (block
# compression), xxHash (XXH3 block checksums), nlohmann-json (motifs.json, truth files, --json
# output), Spectra (header-only sparse Lanczos eigensolver: normalized cut on large instance
# graphs, engine/cluster/), Google Benchmark and GoogleTest/GoogleMock (bench/ and tests/),
# chromium (headless: the test that opens report.html in a browser,
# tests/engine/cli/report_browser_test.cc, checks that its script runs without errors and draws
# every figure, and saves a screenshot; it skips without it), python3 (the crash-consistency
# harness and the hostile-input corpus, scripts/crash_harness.py and scripts/hostile_inputs.py,
# both run by ctest; standard library only), pybind11-dev, python3-dev, python3-numpy and
# python3-pytest (the Python module `motifmine` for Debian's /usr/bin/python3, its numpy arrays,
# and its tests: python/, docs/python.md), libopenmpi-dev and openmpi-bin (Open MPI, the
# distributed engine motifmine-mpi runs on, and mpirun for its tests: docs/design/distributed.md).
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libboost-dev libboost-iostreams-dev libboost-program-options-dev
  libeigen3-dev libtbb-dev libzstd-dev libxxhash-dev nlohmann-json3-dev
  libspectra-dev
  libbenchmark-dev libgtest-dev libgmock-dev
  chromium python3
  pybind11-dev python3-dev python3-numpy python3-pytest
  libopenmpi-dev openmpi-bin
)

missing=()
for package in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$package")
  fi
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "installing: ${missing[*]}" >&2
sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then
  if command -v sudo >/dev/null 2>&1; then sudo_cmd=(sudo); else
    echo "error: missing packages (${missing[*]}) and not root; install them and re-run" >&2
    exit 1
  fi
fi
"${sudo_cmd[@]}" apt-get update -qq
DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends \
  "${missing[@]}" >&2
