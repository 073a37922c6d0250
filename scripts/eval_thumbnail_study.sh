#!/usr/bin/env bash
# The thumbnail prototype (bench/studies/thumbnail_study.cc) on the labelled takes, scored as
# scripts/eval_repetitions.sh scores `mine`: each take's thumbnail family is written as the one
# motif of a motifs.json and `motifmine score` gives its top-1 precision and recall against the
# annotated occurrences (docs/design/motif_quality.md, section 10).
#
#   scripts/eval_thumbnail_study.sh EVAL_OUT [key=value ...]
# EVAL_OUT: the MOTIF_EVAL_OUT folder of an earlier scripts/eval_repetitions.sh run (its
# archives and motifs.json are reused); key=value: options of thumbnail_study, @DIR@ standing for
# the take's folder there (candidates=@DIR@/paths.mpa: the miner's paths). MOTIF_STUDY names
# another study with the same output (family_trellis_study, given `@DIR@/trellis.mtr
# @DIR@/paths.mpa` first). Ends with one line
#   mean top-1 precision P recall R
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
evals="${1:?usage: eval_thumbnail_study.sh EVAL_OUT [key=value ...]}"
shift
build="${MOTIF_BUILD_DIR:-$root/build}"
study="$build/bench/studies/${MOTIF_STUDY:-thumbnail_study}"
[ -x "$study" ] || "$root/scripts/build.sh" >&2
labels="$root/tests/data/repetitions"
for dir in "$evals"/*/; do
  clip="$(basename "$dir")"
  if [ ! -f "$dir/archive.mfs" ] || [ ! -f "$labels/$clip.tsv" ]; then continue; fi
  "$study" "$dir/archive.mfs" "${@//@DIR@/$dir}" >"$dir/thumbnail.txt"
  python3 - "$dir" <<'PY'
import json, os, sys
folder = sys.argv[1]
motifs = []  # a 5-field line starts a family, the 2-field lines after it are its segments
for fields in (line.split() for line in open(os.path.join(folder, "thumbnail.txt"))):
    if len(fields) == 5:
        motifs.append([])
    elif len(fields) == 2 and motifs:
        motifs[-1].append((int(fields[0]), int(fields[1])))
doc = json.load(open(os.path.join(folder, "motifs.json")))
clip = doc["clips"][0]
doc["motifs"] = []
for segments in motifs:
    instances = [{"clip": clip["name"], "start": a, "end": b, "frame": a, "length": b - a}
                 for a, b in segments]
    mean = sum(i["length"] for i in instances) / max(1, len(instances))
    doc["motifs"].append({"id": len(doc["motifs"]), "instance_count": len(instances),
                          "mean_length": mean, "mean_seconds": mean / clip["fps"], "score": mean,
                          "instances": instances})
doc["summary"] = {"motifs": len(doc["motifs"]),
                  "instances": sum(len(m["instances"]) for m in doc["motifs"]),
                  "covered_frames": sum(i["length"] for m in doc["motifs"] for i in m["instances"])}
json.dump(doc, open(os.path.join(folder, "thumbnail.json"), "w"))
PY
  "$build/motifmine" score "$dir/thumbnail.json" "$labels/$clip.tsv" --json >"$dir/thumbnail_score.json"
done
python3 - "$evals" <<'PY'
import json, os, sys
evals = sys.argv[1]
total_p = total_r = 0.0
takes = 0
for clip in sorted(os.listdir(evals)):
    path = os.path.join(evals, clip, "thumbnail_score.json")
    if not os.path.exists(path):
        continue
    top = json.load(open(path)).get("top1") or {}
    p, r = top.get("precision", 0.0), top.get("recall", 0.0)
    print("%-20s %3d instances  %-28s precision %.3f recall %.3f" % (
        clip, top.get("instances", 0), top.get("movement", "-"), p, r))
    total_p += p
    total_r += r
    takes += 1
print("mean top-1 precision %.3f recall %.3f" % (total_p / takes, total_r / takes))
PY
