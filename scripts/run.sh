#!/usr/bin/env bash
# The main job. Installs what is missing and builds, then:
#   scripts/run.sh            makes a synthetic archive with planted motifs and describes it
#   scripts/run.sh PATH...    imports your BVH / ASF+AMC takes (files or folders) and describes them
# Outputs go to out/ (MOTIF_OUT overrides). Mining itself arrives with `motifmine mine`.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/build.sh" >&2
tool="${MOTIF_BUILD_DIR:-$root/build}/motifmine"
out="${MOTIF_OUT:-$root/out}"
mkdir -p "$out"
if [ $# -eq 0 ]; then
  archive="$out/synthetic.mfs"
  "$tool" synth "$archive" --frames 360000 --motifs 8 --seed 1 --force
  "$tool" verify "$archive"
  "$tool" info "$archive" --clips 5
  echo
  echo "planted motifs: $out/synthetic.truth.json"
else
  archive="$out/archive.mfs"
  rm -f "$archive"
  "$tool" import "$archive" "$@"
  "$tool" info "$archive"
fi
