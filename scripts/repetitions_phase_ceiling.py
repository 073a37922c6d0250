#!/usr/bin/env python3
"""What a miner that does not know where annotators start a cycle can score on the labelled set.

For each take of tests/data/repetitions, and each annotated movement, imagine a perfect top
motif: exactly that movement's occurrences, except that a movement done back to back (the rule of
engine/evaluation/truth_score.h: at least half its occurrences end within 2 frames of where
another starts) is found at a phase of its own, every instance shifted by the same s frames, s
uniform over half a cycle either way (a cycle has no start of its own; the annotators chose a
heel strike, the hand's highest point, ...). Its expected top-1 precision under the hit rule
(same clip, IoU >= 0.5) is printed; a take scores its best movement (the one a phase-agnostic
miner should name). Movements done apart score 1. Ends with one line
    mean expected top-1 precision P
(recall is the same here: one instance per occurrence). docs/design/motif_quality.md, section 11.

    python3 scripts/repetitions_phase_ceiling.py [LABELS_DIR]
"""
import collections
import os
import sys

GAP = 2      # frames: kBackToBackGap
HIT = 0.5    # kTruthHitIoU
STEPS = 200  # shifts tried, evenly over [-L/2, L/2)


def iou(a, b):
    inter = max(0, min(a[1], b[1]) - max(a[0], b[0]))
    union = (a[1] - a[0]) + (b[1] - b[0]) - inter
    return inter / union if union > 0 else 0.0


def back_to_back(occurrences):
    followed = sum(1 for a in occurrences
                   if any(b is not a and abs(a[1] - b[0]) <= GAP for b in occurrences))
    return followed > 0 and 2 * followed >= len(occurrences)


def expected_precision(occurrences):
    if not back_to_back(occurrences):
        return 1.0
    lengths = sorted(b - a for a, b in occurrences)
    cycle = lengths[len(lengths) // 2]
    total = 0.0
    for step in range(STEPS):
        shift = round((step / STEPS - 0.5) * cycle)
        moved = [(a + shift, b + shift) for a, b in occurrences]
        total += sum(any(iou(m, o) >= HIT for o in occurrences) for m in moved) / len(moved)
    return total / STEPS


def main():
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
    labels = sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "tests", "data",
                                                                "repetitions")
    takes = collections.defaultdict(lambda: collections.defaultdict(list))
    for name in sorted(os.listdir(labels)):
        if not name.endswith(".tsv") or name == "takes.tsv":
            continue
        for line in open(os.path.join(labels, name)):
            fields = line.rstrip("\n").split("\t")
            if len(fields) != 4 or fields[0] == "clip" or fields[0].startswith("#"):
                continue
            takes[fields[0]][fields[1]].append((int(fields[2]), int(fields[3])))
    total = 0.0
    for clip in sorted(takes):
        scored = [(expected_precision(occ), movement, back_to_back(occ))
                  for movement, occ in sorted(takes[clip].items())]
        best = max(scored, key=lambda entry: entry[0])
        total += best[0]
        print("%-20s %-28s %-13s expected precision %.3f" % (
            clip, best[1], "back to back" if best[2] else "apart", best[0]))
    print("mean expected top-1 precision %.3f" % (total / max(1, len(takes))))


if __name__ == "__main__":
    main()
