#!/usr/bin/env python3
"""Per-frame action labels of ../shared/data/mocap6 as the annotation TSV `motifmine score` reads.

usage: scripts/mocap6_labels.py MOCAP6_DIR > labels.tsv

labels/<take>.txt holds one integer per block of 12 frames (0.1 s at 120 fps): label i covers
clip frames [12 i, 12 i + 12) after import, the last block cut at the take's end (its frame
count is read from the AMC file: the lines that hold a frame number alone). Equal neighbouring
blocks are written as one run: clip<TAB>movement<TAB>start<TAB>end, the movement being the
action's name (docs/formats/repetitions_tsv.md).
"""
import os
import sys

NAMES = ["JumpJack", "Jog", "Squat", "KneeRaise", "ArmCircle", "Twist", "SideReach", "Box",
         "UpDown", "ToeTouchOneHand", "SideBend", "ToeTouchTwoHands"]
BLOCK = 12


def amc_frames(path):
    with open(path) as amc:
        return sum(1 for line in amc if line.strip().isdigit())


def runs(labels, frames):
    start = 0
    for index in range(1, len(labels) + 1):
        if index == len(labels) or labels[index] != labels[start]:
            yield labels[start], start * BLOCK, min(index * BLOCK, frames)
            start = index


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__.strip().splitlines()[2])
    folder = sys.argv[1]
    print("clip\tmovement\tstart\tend")
    for name in sorted(os.listdir(os.path.join(folder, "labels"))):
        take = os.path.splitext(name)[0]
        with open(os.path.join(folder, "labels", name)) as text:
            labels = [int(word) for word in text.read().split()]
        frames = amc_frames(os.path.join(folder, take + ".amc"))
        for label, start, end in runs(labels, frames):
            if start < end:
                print(f"{take}\t{NAMES[label - 1]}\t{start}\t{end}")


if __name__ == "__main__":
    main()
