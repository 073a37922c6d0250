#!/usr/bin/env bash
# The library as a downstream project meets it: installs BUILD (default build/) into a temporary
# prefix, configures and builds examples/mine_archive against it with find_package(motifmine),
# runs it on a built-in synthetic archive, and checks that it finds the motifs the installed tool
# finds on the same archive. Run by ctest as install_and_example (docs/library.md).
#
#   scripts/test_install.sh [BUILD]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="$(cd "${1:-$root/build}" && pwd)"
prefix="$(mktemp -d)"
trap 'rm -rf "$prefix"' EXIT

cmake --install "$build" --prefix "$prefix/usr" >/dev/null
test -f "$prefix/usr/include/motifmine/motifmine.h"
test -f "$prefix/usr/lib/cmake/motifmine/motifmineConfig.cmake" ||
  test -f "$prefix/usr/lib/x86_64-linux-gnu/cmake/motifmine/motifmineConfig.cmake"
cmake -S "$root/examples/mine_archive" -B "$prefix/example" -DCMAKE_PREFIX_PATH="$prefix/usr" \
  -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$prefix/example" -j 2 >/dev/null

"$prefix/example/mine_archive" --out "$prefix/library" --synth-frames 20000 --synth-motifs 3 \
  > "$prefix/library.txt"
"$prefix/usr/bin/motifmine" mine --out "$prefix/tool" --synth-frames 20000 --synth-motifs 3 \
  --quiet --no-report > /dev/null
grep -q "^motif 0:" "$prefix/library.txt"
# The same motifs, instance for instance: motifs.json apart from the archive path and timings.
strip() { grep -v '"archive"\|seconds' "$1"; }
if ! diff <(strip "$prefix/library/motifs.json") <(strip "$prefix/tool/motifs.json") >/dev/null; then
  echo "the example's motifs differ from the tool's" >&2
  exit 1
fi
# The installed Python module imports from the prefix, with no LD_LIBRARY_PATH: its RUNPATH is
# relative to its own folder (python/CMakeLists.txt). Skipped when the module was not built.
module="$(find "$prefix/usr" -name 'motifmine*.so' -path '*dist-packages*' | head -1)"
if [ -n "$module" ]; then
  frames="$(env -u LD_LIBRARY_PATH PYTHONPATH="$(dirname "$module")" /usr/bin/python3 -c \
    "import motifmine, sys; print(motifmine.Archive(sys.argv[1]).frames)" \
    "$prefix/library/archive.mfs")"
  if [ "$frames" != 20000 ]; then
    echo "the installed Python module read $frames frames, not 20000" >&2
    exit 1
  fi
  echo "the installed Python module ($module) imports from the prefix and reads the archive"
else
  echo "no Python module installed: its import from the prefix is not checked"
fi
echo "installed into a prefix, built examples/mine_archive against it, and mined:"
head -3 "$prefix/library.txt"
