#!/usr/bin/env bash
# Exports take the source's motion with them, as Blender sees it: a take of each BVH family in
# ../shared (CMU cgspeed BVH, CMU Daz BVH, the studio rig of bandai2, whose animated root Hips sits
# under a static joint_Root) is imported into an archive of its own, exported with
# `motifmine export`, and both files are opened by Blender's BVH importer
# (scripts/blender_bvh_roundtrip.py). Each joint's world position is compared over every exported
# frame; a family passes within 0.01 % of the body's height. Prints one line per take and
#   blender round trip: P of N takes within 0.01 % of body height
# and exits 1 if one is off. Blender is too heavy for CI, so this is a script, beside the three.js
# reader test (docs/reliability.md lists both).
#
#   scripts/check_blender_roundtrip.sh [TAKE.bvh ...]    (default: two takes per family)
# Environment: MOTIF_BUILD_DIR the build folder; BLENDER the Blender binary (default blender,
# `apt-get install blender` on Debian).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
shared="$root/../shared/data"
tool="${MOTIF_BUILD_DIR:-$root/build}/motifmine"
blender="${BLENDER:-blender}"
if ! command -v "$blender" >/dev/null; then
  echo "check_blender_roundtrip: skipped: no Blender (apt-get install blender)" >&2
  exit 0
fi
[ -x "$tool" ] || "$root/scripts/build.sh" >&2
takes=("$@")
if [ ${#takes[@]} -eq 0 ]; then
  for take in mocap/bvh/02_01.bvh mocap/bvh/07_05.bvh mocap/bvh_daz/02_01.bvh \
    mocap/bvh_daz/10_04.bvh bandai2/bvh/dataset-2_walk-turn-left_normal_001.bvh \
    bandai2/bvh/dataset-2_wave-right-hand_elderly_001.bvh; do
    [ -f "$shared/$take" ] && takes+=("$shared/$take")
  done
fi
if [ ${#takes[@]} -eq 0 ]; then
  echo "check_blender_roundtrip: skipped: no takes under $shared" >&2
  exit 0
fi
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
pairs=()
for i in "${!takes[@]}"; do
  take="${takes[$i]}"
  "$tool" import "$work/$i.mfs" "$take" --quiet >/dev/null
  clip="$("$tool" info "$work/$i.mfs" --json |
    /usr/bin/python3 -c 'import json,sys; c=json.load(sys.stdin)["clips"][0]; print(c["name"], c["source_first_frame"])')"
  "$tool" export "$work/$i.mfs" --clip "${clip% *}" --out "$work/$i.bvh" >/dev/null
  pairs+=("$take" "$work/$i.bvh" "${clip##* }")
done
# The summary of the ROUNDTRIP lines, one a take.
summary="$(cat <<'PY'
import json, sys
rows = [json.loads(line) for line in sys.stdin]
good = 0
for r in rows:
    ok = r["max_relative"] <= 1e-4
    good += ok
    only = ",".join(r["joints_only_in_source"]) or "-"
    name = r["source"].split("/data/")[-1]
    frame, joint = r["worst_frame_joint"] or (0, "-")
    verdict = "ok" if ok else "OFF"
    print(f"{name}: {r['frames']} frames, {r['joints_compared']} joints, body {r['body_height']:.1f},"
          f" max {r['max_distance']:.5f} ({100 * r['max_relative']:.4f} % of height, frame {frame}"
          f" {joint}); folded into the root: {only}; {verdict}")
print(f"blender round trip: {good} of {len(rows)} takes within 0.01 % of body height")
sys.exit(0 if rows and good == len(rows) else 1)
PY
)"
"$blender" -b --factory-startup --python "$root/scripts/blender_bvh_roundtrip.py" -- "${pairs[@]}" \
  2>/dev/null | sed -n 's/^ROUNDTRIP //p' | /usr/bin/python3 -c "$summary"
