#!/usr/bin/env python3
"""Labels of the CMU takes for `motifmine classify --labels`, derived from INDEX.tsv.

usage: scripts/mocap_labels.py [../shared/data/mocap/INDEX.tsv] > labels.tsv

Writes one line per BVH (MotionBuilder-friendly) or AMC take: clip<TAB>label<TAB>description,
after a header line, once per clip name (a take in both formats is listed once). The clip name is the file's stem, as `motifmine import` names the clip
("60_01", "07_05-walk"). The label comes from CMU's description of the trial (lower-cased), by
the first of these rules that matches:

  1. "salsa"                                   -> salsa
  2. a dance ("danc") by a subject CMU files
     under "modern dance" (subject 05)          -> modern dance
  3. "basketball"                               -> basketball
  4. "punch" or "boxing"                        -> punch/boxing
  5. any other dance ("danc")                   -> other dance
  6. "run" or "jog" as a word                   -> run
  7. "jump"                                     -> jump
  8. "walk"                                     -> walk
  otherwise the take gets no label (e.g. 131_04 "Start Hop Stop", 135_06 "Heiansyodan"); it
  stays in the archive but does not count in the supervised scores.

The subject descriptions come from the ASF rows ("Subject #5 (modern dance)"). The Daz BVH takes
(bvh_daz/, another skeleton) are left out: they cannot share an archive with the others.
"""
import csv
import os
import re
import sys


def label_of(description, subject_description):
    text = description.lower()
    subject = subject_description.lower()
    if "salsa" in text:
        return "salsa"
    if "danc" in text and "modern dance" in subject:
        return "modern dance"
    if "basketball" in text:
        return "basketball"
    if "punch" in text or "boxing" in text:
        return "punch/boxing"
    if "danc" in text:
        return "other dance"
    if re.search(r"\b(run|jog)\b", text):
        return "run"
    if "jump" in text:
        return "jump"
    if "walk" in text:
        return "walk"
    return ""


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    default = os.path.join(here, "..", "..", "shared", "data", "mocap", "INDEX.tsv")
    index_path = sys.argv[1] if len(sys.argv) > 1 else default
    with open(index_path, newline="") as index:
        rows = list(csv.DictReader(index, delimiter="\t"))
    subjects = {row["subject"]: row["description"] for row in rows if row["format"] == "asf"}
    out = sys.stdout
    out.write("clip\tlabel\tdescription\n")
    written = set()
    for row in rows:
        if row["format"] not in ("bvh", "amc"):
            continue
        clip = os.path.splitext(os.path.basename(row["file"]))[0]
        if clip in written:  # a take in both formats (05_01 in bvh/ and asfamc/): one line
            continue
        written.add(clip)
        label = label_of(row["description"], subjects.get(row["subject"], ""))
        if label:
            out.write(f"{clip}\t{label}\t{row['description']}\n")


if __name__ == "__main__":
    main()
