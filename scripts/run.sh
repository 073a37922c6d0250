#!/usr/bin/env bash
# The main job. Installs what is missing and builds, then mines motion motifs:
#   scripts/run.sh            a built-in synthetic archive with planted motifs: prints the summary
#                             and how well the planted motifs were recovered
#   scripts/run.sh PATH...    your BVH / ASF+AMC takes (files or folders) or an archive (.mfs)
# Results go to out/ (MOTIF_OUT overrides): out/motifs.json, out/report.html. Extra options for
# `motifmine mine` can be given in MOTIF_MINE_ARGS (e.g. "--min-length 1s --groups 20").
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/build.sh" >&2
tool="${MOTIF_BUILD_DIR:-$root/build}/motifmine"
out="${MOTIF_OUT:-$root/out}"
# shellcheck disable=SC2086  # MOTIF_MINE_ARGS is a list of options
"$tool" mine "$@" --out "$out" ${MOTIF_MINE_ARGS:-}
echo
echo "report: $out/report.html (a single file: open it in a browser)"
