#!/usr/bin/env bash
# The library as a downstream project meets it: installs BUILD (default build/) into a temporary
# prefix, configures and builds examples/mine_archive against it with find_package(motifmine),
# runs it on a built-in synthetic archive, and checks that it finds the motifs the installed tool
# finds on the same archive; the installed Python module, with PYTHONPATH unset, loads the mined
# folder and rebuilds a pose as export writes it. Run by ctest as install_and_example
# (docs/library.md).
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
# PYTHONPATH unset: the module is found by its folder alone, never the build tree's. It loads
# the folder the example mined (motifmine.load: the same motifs as motifs.json) and rebuilds a
# pose whose forward kinematics is the BVH the installed tool exports (python/tests/
# test_pose_and_load.py's check, its FK and BVH reader).
module="$(find "$prefix/usr" -name 'motifmine*.so' -path '*dist-packages*' | head -1)"
if [ -n "$module" ]; then
  env -u LD_LIBRARY_PATH -u PYTHONPATH MOTIFMINE_TOOL="$prefix/usr/bin/motifmine" \
    /usr/bin/python3 - "$(dirname "$module")" "$root/python/tests" "$prefix/library" \
    "$prefix/pose" <<'PYTHON'
import json, os, pathlib, sys
sys.path[:0] = sys.argv[1:3]
import motifmine
import test_pose_and_load as check
module_dir, _, mined, pose_dir = sys.argv[1:]
assert motifmine.__file__.startswith(module_dir), motifmine.__file__
archive = motifmine.Archive(os.path.join(mined, "archive.mfs"))
assert archive.frames == 20000, archive.frames
loaded = motifmine.load(mined)
with open(os.path.join(mined, "motifs.json")) as f:
    expected = json.load(f)["motifs"]
got = [[(i.clip, i.start, i.end) for i in m.instances] for m in loaded.motifs]
assert got == [[(i["clip"], i["start"], i["end"]) for i in m["instances"]] for m in expected]
instance = loaded.motifs[0].instances[0]
os.makedirs(pose_dir)
check.check_pose_is_exports(archive, instance.clip, instance.start, instance.end,
                            pathlib.Path(pose_dir))
print("the installed Python module (%s) imports from the prefix, loads %r and rebuilds the "
      "pose of %r as export writes it" % (motifmine.__file__, loaded, instance))
PYTHON
else
  echo "no Python module installed: its import from the prefix is not checked"
fi
echo "installed into a prefix, built examples/mine_archive against it, and mined:"
head -3 "$prefix/library.txt"
