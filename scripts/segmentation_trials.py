#!/usr/bin/env python3
"""Joined-takes trials for the segmentation evaluation (scripts/eval_segmentation.sh).

usage: scripts/segmentation_trials.py TOOL SOURCE.mfs LABELS.tsv OUT_DIR TRIALS [PIECE_SECONDS]

Each trial t (seed t, 1 .. TRIALS) is one take made of one piece of each activity of ACTIVITIES,
in a seeded random order: for each activity a seeded random take of that label in LABELS.tsv
(scripts/mocap_labels.py), and a seeded random range of PIECE_SECONDS (default 6) of it, the
whole take when shorter. The pieces are exported from SOURCE.mfs (`TOOL export --names
canonical`: one hierarchy for every take of the archive) and joined into OUT_DIR/trial_TT.bvh:
the first piece's hierarchy and offsets, then every piece's frames, each piece moved on the
floor (X, Z) so that its first root position is the previous piece's last: the root is
continuous at each junction (its heading is not turned).

Per trial it also writes
  trial_TT.truth.tsv   start<TAB>end<TAB>label per piece (frames of the joined take, end
                       exclusive), after a header line
  trial_TT.labels.tsv  the training labels: every labelled take of LABELS.tsv except the trial's
                       source takes and, for salsa, their partner takes (60_NN and 61_NN are one
                       couple recorded together), so no motion of the trial is in the training set
and OUT_DIR/trials.json with every piece.

Only activities with at least 4 labelled takes are used (walk, run, modern dance, basketball,
salsa), so at least 3 remain to train on; "other dance" is left out because its takes are five
different dances with nothing in common but the word.
"""
import csv
import json
import os
import random
import subprocess
import sys

ACTIVITIES = ["walk", "run", "modern dance", "basketball", "salsa"]


def read_labels(path):
    with open(path, newline="") as handle:
        rows = [row for row in csv.reader(handle, delimiter="\t") if row and not row[0].startswith("#")]
    return {row[0]: row[1] for row in rows[1:] if len(row) > 1 and row[1]}


def partners(clip):
    subject, _, trial = clip.partition("_")
    if subject in ("60", "61"):
        return {f"60_{trial}", f"61_{trial}"}
    return {clip}


def read_bvh(path):
    with open(path) as handle:
        text = handle.read()
    head, motion = text.split("MOTION", 1)
    lines = motion.strip().splitlines()
    frames = [[float(value) for value in line.split()] for line in lines[2:]]
    return head, lines[1], frames


def join(pieces, path):
    head, frame_time, joined = None, None, []
    for piece in pieces:
        piece_head, piece_time, frames = read_bvh(piece)
        if head is None:
            head, frame_time = piece_head, piece_time
        if joined:
            dx = joined[-1][0] - frames[0][0]
            dz = joined[-1][2] - frames[0][2]
            for frame in frames:
                frame[0] += dx
                frame[2] += dz
        joined.extend(frames)
    with open(path, "w") as out:
        out.write(head + "MOTION\nFrames: %d\n%s\n" % (len(joined), frame_time))
        for frame in joined:
            out.write(" ".join("%.6f" % value for value in frame) + "\n")
    return len(joined)


def main():
    tool, source, labels_path, out_dir, trials = sys.argv[1:6]
    piece_seconds = float(sys.argv[6]) if len(sys.argv) > 6 else 6.0
    labels = read_labels(labels_path)
    info = json.loads(subprocess.run([tool, "info", source, "--json"], check=True,
                                     capture_output=True, text=True).stdout)
    frames = {clip["name"]: clip["frames"] for clip in info["clips"]}
    fps = info["fps"]
    by_label = {}
    for clip, label in sorted(labels.items()):
        if clip in frames:
            by_label.setdefault(label, []).append(clip)
    os.makedirs(out_dir, exist_ok=True)
    plan = []
    for trial in range(1, int(trials) + 1):
        rng = random.Random(trial)
        order = ACTIVITIES[:]
        rng.shuffle(order)
        pieces, paths, used, start = [], [], set(), 0
        for index, activity in enumerate(order):
            clip = rng.choice(by_label[activity])
            length = min(frames[clip], int(round(piece_seconds * fps)))
            first = rng.randrange(0, frames[clip] - length + 1)
            path = os.path.join(out_dir, "trial_%02d_piece_%d.bvh" % (trial, index))
            subprocess.run([tool, "export", source, "--clip", clip, "--start", str(first),
                            "--end", str(first + length), "--out", path, "--names", "canonical"],
                           check=True, capture_output=True)
            pieces.append({"clip": clip, "label": activity, "source_start": first,
                           "source_end": first + length, "start": start, "end": start + length})
            paths.append(path)
            used |= partners(clip)
            start += length
        name = "trial_%02d" % trial
        total = join(paths, os.path.join(out_dir, name + ".bvh"))
        assert total == start, (total, start)
        for path in paths:
            os.remove(path)
        with open(os.path.join(out_dir, name + ".truth.tsv"), "w") as out:
            out.write("start\tend\tlabel\n")
            for piece in pieces:
                out.write("%d\t%d\t%s\n" % (piece["start"], piece["end"], piece["label"]))
        with open(os.path.join(out_dir, name + ".labels.tsv"), "w") as out:
            out.write("clip\tlabel\n")
            for clip, label in sorted(labels.items()):
                if clip not in used:
                    out.write("%s\t%s\n" % (clip, label))
        plan.append({"trial": name, "frames": total, "pieces": pieces})
    with open(os.path.join(out_dir, "trials.json"), "w") as out:
        json.dump({"fps": fps, "trials": plan}, out, indent=1)


if __name__ == "__main__":
    main()
