#!/usr/bin/env bash
# The studio archive figure: ../shared/data/bandai2 (10 actions, each in 7 styles, 2 takes per
# action and style; the labels are in the file names dataset-2_{CONTENT}_{STYLE}_{ID}.bvh)
# mined as one folder with the defaults. Prints
#   motifs, instances
#   content purity: the share of instances whose take shows their motif's main content
#                   (instance-weighted: sum over motifs of the main content's count / instances)
#   styles: how many of the 10 contents own a motif (one whose main content it is) whose
#           instances of that content come from 3 or more styles (and, beside it, in any motif)
# and one line per content. The figures are defined as the studio's users ask: is one action
# found as one motif whatever the style it was performed in (docs/design/motif_quality.md).
#
#   scripts/eval_style_folder.sh [BANDAI2_BVH_DIR]    (default ../shared/data/bandai2/bvh)
# Environment: MOTIF_BUILD_DIR the build folder; MOTIF_EVAL_OUT the work folder (default a
# temporary one, removed).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
takes="${1:-$root/../shared/data/bandai2/bvh}"
if [ ! -d "$takes" ]; then
  echo "eval_style_folder: skipped: no studio takes at $takes" >&2
  exit 0
fi
tool="${MOTIF_BUILD_DIR:-$root/build}/motifmine"
[ -x "$tool" ] || "$root/scripts/build.sh" >&2
work="${MOTIF_EVAL_OUT:-}"
if [ -z "$work" ]; then
  work="$(mktemp -d)"
  trap 'rm -rf "$work"' EXIT
fi
mkdir -p "$work"
rm -rf "$work/out"
"$tool" mine "$takes" --out "$work/out" --quiet >"$work/mine.log"
/usr/bin/python3 - "$work/out/motifs.json" <<'PY'
import collections, json, re, sys
doc = json.load(open(sys.argv[1]))
pattern = re.compile(r"dataset-2_(?P<content>.+)_(?P<style>[a-z]+)_(?P<id>\d+)$")
labels = {c["name"]: pattern.match(c["name"]).groupdict() for c in doc["clips"]}
contents = sorted({l["content"] for l in labels.values()})
owned = collections.defaultdict(int)  # content -> most styles of one motif it owns
spanned = collections.defaultdict(int)  # content -> most styles of it in any one motif
pure = total = 0
for motif in doc["motifs"]:
    seen = collections.Counter(labels[i["clip"]]["content"] for i in motif["instances"])
    main, count = sorted(seen.items(), key=lambda kv: (-kv[1], kv[0]))[0]
    pure += count
    total += len(motif["instances"])
    styles = {labels[i["clip"]]["style"] for i in motif["instances"]
              if labels[i["clip"]]["content"] == main}
    owned[main] = max(owned[main], len(styles))
    for content in seen:
        of_it = {labels[i["clip"]]["style"] for i in motif["instances"]
                 if labels[i["clip"]]["content"] == content}
        spanned[content] = max(spanned[content], len(of_it))
print(f"motifs {len(doc['motifs'])}, instances {total}")
print(f"content purity {pure / total if total else 0:.3f}")
print(f"styles: {sum(owned[c] >= 3 for c in contents)} of {len(contents)} contents own a motif "
      f"spanning 3 or more styles")
print(f"  (in any motif, owned or not: {sum(spanned[c] >= 3 for c in contents)} of {len(contents)})")
for c in contents:
    print(f"  {c}: {owned[c]} styles in its best owned motif, {spanned[c]} in any")
PY
