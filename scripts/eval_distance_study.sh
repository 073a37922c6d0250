#!/usr/bin/env bash
# The distance study over the labelled set (docs/design/motion_distance.md): imports each take of
# tests/data/repetitions alone, trains the part-B word embedding the way `motifmine words` does
# (on the real CMU takes of scripts/import_cmu_takes.sh, and on the Daz BVH folder for the Daz
# take), runs build/bench/studies/distance_study on every take, and prints, per candidate
# distance: the mean 1-NN fraction over takes and pooled over queries, the mean ROC AUC (pooled
# per take, and per query), the median cost over takes, and how its column distances are
# distributed; then the 1-NN fraction and the AUC take by take, and per movement on the hard takes.
#
#   scripts/eval_distance_study.sh [MOCAP_DIR] [key=value ...]
#     MOCAP_DIR   default ../shared/data/mocap beside the clone
#     key=value   passed to every distance_study run (e.g. frame_grid=4 candidates=quat_dtw)
# Environment: MOTIF_STUDY_OUT the work folder (archives and embeddings, reused when there, and
# runs/RUN/ with each take's output, rows.tsv and movements.tsv; default a temporary folder,
# removed at the end); MOTIF_STUDY_RUN the run's name (default "default");
# MOTIF_EVAL_TAKES a space-separated subset of clips; MOTIF_BUILD_DIR the build folder (default
# build; the two programs are built there when missing); MOTIF_STUDY_EMBEDDING=0 leaves the
# embedding out (no training).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
mocap="$root/../shared/data/mocap"
if [ $# -gt 0 ] && [[ "$1" != *=* ]]; then
  mocap="$1"
  shift
fi
labels="$root/tests/data/repetitions"
if [ ! -d "$mocap" ]; then
  echo "eval_distance_study: skipped: no motion-capture folder at $mocap" >&2
  exit 0
fi
build="${MOTIF_BUILD_DIR:-$root/build}"
tool="$build/motifmine"
study="$build/bench/studies/distance_study"
if [ ! -x "$tool" ] || [ ! -x "$study" ]; then
  cmake --build "$build" -j1 --target motifmine distance_study >&2
fi
if [ -n "${MOTIF_STUDY_OUT:-}" ]; then
  out="$MOTIF_STUDY_OUT"
  mkdir -p "$out"
else
  out="$(mktemp -d)"
  trap 'rm -rf "$out"' EXIT
fi

# The embeddings: trained once per skeleton family, single-threaded, seed 1 (the defaults).
train_embedding() {  # ARCHIVE: imported already
  local archive=$1
  [ -f "${archive%.mfs}.mwe" ] && return 0
  "$tool" words "$archive" --threads 1 --seed 1 --quiet --json "${archive%.mfs}.words.json" \
    >"${archive%.mfs}.words.txt"
}
if [ "${MOTIF_STUDY_EMBEDDING:-1}" != 0 ]; then
  mkdir -p "$out/words"
  (cd "$root" && scripts/import_cmu_takes.sh "$out/words/cmu.mfs" "$mocap")
  train_embedding "$out/words/cmu.mfs"
  if [ -d "$mocap/bvh_daz" ]; then
    [ -f "$out/words/daz.mfs" ] || "$tool" import "$out/words/daz.mfs" "$mocap/bvh_daz" --quiet \
      --threads 1 >/dev/null
    train_embedding "$out/words/daz.mfs"
  fi
fi

run="$out/runs/${MOTIF_STUDY_RUN:-default}"
rm -rf "$run"
mkdir -p "$run"
while IFS=$'\t' read -r clip file; do
  case "$clip" in clip | '#'* | '') continue ;; esac
  if [ -n "${MOTIF_EVAL_TAKES:-}" ] && ! grep -qw -- "$clip" <<<"$MOTIF_EVAL_TAKES"; then
    continue
  fi
  if [ ! -f "$mocap/$file" ]; then
    echo "eval_distance_study: $clip: $mocap/$file is missing" >&2
    exit 1
  fi
  [ -f "$out/$clip.mfs" ] || "$tool" import "$out/$clip.mfs" "$mocap/$file" --quiet --threads 1 \
    >/dev/null
  embedding=()
  if [ "${MOTIF_STUDY_EMBEDDING:-1}" != 0 ]; then
    case "$file" in
      bvh_daz/*) embedding=("embedding=$out/words/daz.mwe") ;;
      *) embedding=("embedding=$out/words/cmu.mwe") ;;
    esac
  fi
  "$study" "$out/$clip.mfs" "$labels/$clip.tsv" "${embedding[@]}" "out=$run/rows.tsv" \
    "movements_out=$run/movements.tsv" "$@" >"$run/$clip.txt"
  echo "eval_distance_study: $clip done" >&2
done <"$labels/takes.tsv"

python3 "$root/scripts/distance_study_table.py" "$run/rows.tsv" "$run/movements.tsv"
