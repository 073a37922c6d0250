#!/usr/bin/env python3
"""Where the folder figure loses against the takes mined alone.

    scripts/folder_against_takes.py TAKES_OUT FOLDER_OUT

TAKES_OUT is a work folder of scripts/eval_repetitions.sh (MOTIF_EVAL_OUT: one folder per take
with motifs.json), FOLDER_OUT one of scripts/eval_repetitions_folder.sh (truth.tsv and
mined/motifs.json). For each take: its annotated occurrences, how many of them some instance
hits (same clip, IoU >= 0.5, any motif) and how many instances hit one, mined alone and in the
folder; then both pooled over the takes. The pooled "alone" line is what the folder figure
would be if mining the takes together lost nothing.
"""
import collections
import csv
import json
import os
import sys


def iou(a, b):
    inter = max(0, min(a[1], b[1]) - max(a[0], b[0]))
    union = max(a[1], b[1]) - min(a[0], b[0])
    return inter / union if union else 0.0


def instances_by_clip(motifs_json):
    by_clip = collections.defaultdict(list)
    for motif in json.load(open(motifs_json))["motifs"]:
        for instance in motif["instances"]:
            by_clip[instance["clip"]].append((instance["start"], instance["end"]))
    return by_clip


def hits(occurrences, instances):
    occurrences_hit = sum(any(iou(o, i) >= 0.5 for i in instances) for o in occurrences)
    instances_hitting = sum(any(iou(o, i) >= 0.5 for o in occurrences) for i in instances)
    return occurrences_hit, instances_hitting, len(instances)


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    takes_out, folder_out = sys.argv[1:]
    truth = collections.defaultdict(list)
    with open(os.path.join(folder_out, "truth.tsv")) as f:
        for row in csv.DictReader(f, delimiter="\t"):
            truth[row["clip"]].append((int(row["start"]), int(row["end"])))
    folder = instances_by_clip(os.path.join(folder_out, "mined", "motifs.json"))
    print(f"{'take':<20} {'occurrences':>11}   alone: hit  instances hitting   folder: hit  instances hitting")
    total = {"alone": [0, 0, 0], "folder": [0, 0, 0]}
    for clip, occurrences in truth.items():
        alone_json = os.path.join(takes_out, clip, "motifs.json")
        alone = instances_by_clip(alone_json)[clip] if os.path.exists(alone_json) else []
        rows = {"alone": hits(occurrences, alone), "folder": hits(occurrences, folder[clip])}
        for name, row in rows.items():
            total[name] = [t + r for t, r in zip(total[name], row)]
        a, f = rows["alone"], rows["folder"]
        print(f"{clip:<20} {len(occurrences):>11}   {a[0]:>10}  {a[1]:>6} of {a[2]:<6}"
              f"   {f[0]:>11}  {f[1]:>6} of {f[2]:<6}")
    occurrences = sum(len(o) for o in truth.values())
    for name, (hit, hitting, instances) in total.items():
        print(f"pooled {name:<6} recall {hit / occurrences:.3f} ({hit} of {occurrences}) "
              f"precision {hitting / max(instances, 1):.3f} ({hitting} of {instances})")


if __name__ == "__main__":
    main()
