#!/usr/bin/env bash
# Imports the real CMU takes of MOCAP_DIR into ARCHIVE (when it does not exist yet): bvh/ (the
# 31-joint MotionBuilder BVH) and the AMC takes that are not also in bvh/ (05_01 and the other
# takes in both formats are imported once, from bvh/). The archive of scripts/eval_signatures.sh
# and scripts/eval_segmentation.sh.
#
#   scripts/import_cmu_takes.sh ARCHIVE MOCAP_DIR
set -euo pipefail
cd "$(dirname "$0")/.."
archive=$1
mocap=$2
[ -f "$archive" ] && exit 0
amcs=()
for amc in "$mocap"/asfamc/*/*.amc; do
  stem=$(basename "$amc" .amc)
  [ -f "$mocap/bvh/${stem%%-*}.bvh" ] || amcs+=("$amc")
done
build/motifmine import "$archive" "$mocap/bvh" "${amcs[@]}" --quiet
