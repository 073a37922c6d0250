#!/usr/bin/env bash
# The README's screenshot of a mining report (docs/images/report.png): mines one real take, CMU
# 02_05 (punches and strikes), when the motion-capture folder is present, else the built-in
# synthetic archive, and photographs report.html in headless Chromium from its timeline down
# (the timeline and the first motifs' stick figures).
#
#   scripts/report_screenshot.sh [OUT.png]   (default docs/images/report.png)
#
# Environment: MOTIF_MOCAP_DIR the takes (default ../shared/data/mocap beside the clone);
# MOTIF_BUILD_DIR the build folder (built when the tool is missing). Needs chromium. A page
# larger than 150 KB is shrunk with pngquant when it is installed (apt-get install pngquant).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
png="$(realpath -m "${1:-$root/docs/images/report.png}")"
mocap="${MOTIF_MOCAP_DIR:-$root/../shared/data/mocap}"
tool="${MOTIF_BUILD_DIR:-$root/build}/motifmine"
[ -x "$tool" ] || "$root/scripts/build.sh" >&2
command -v chromium >/dev/null || { echo "report_screenshot: chromium is not installed" >&2; exit 1; }

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
take="$mocap/bvh/02_05.bvh"
if [ -f "$take" ]; then
  "$tool" mine "$take" --out "$work/mined" --quiet
else
  echo "report_screenshot: no take at $take: mining the synthetic archive" >&2
  "$tool" mine --out "$work/mined" --quiet
fi

# The page scrolled to its timeline: headless Chromium's --screenshot ignores a top-level page's
# #fragment, but a frame honours it, so the report is shown in a frame the size of the window.
cat >"$work/frame.html" <<EOF
<!doctype html><html><body style="margin:0;overflow:hidden">
<iframe src="file://$work/mined/report.html#timeline" style="border:0;width:1280px;height:900px"></iframe>
</body></html>
EOF
mkdir -p "$(dirname "$png")"
# The figures are drawn by the page's scripts: the virtual time budget lets them finish.
chromium --headless --no-sandbox --disable-gpu --disable-background-networking \
  --disable-component-update --disable-sync --no-first-run --user-data-dir="$work/profile" \
  --window-size=1280,900 --virtual-time-budget=5000 --screenshot="$work/shot.png" \
  "file://$work/frame.html" >/dev/null 2>&1
[ -s "$work/shot.png" ] || { echo "report_screenshot: chromium wrote no screenshot" >&2; exit 1; }
if [ "$(stat -c %s "$work/shot.png")" -gt 153600 ] && command -v pngquant >/dev/null; then
  pngquant --force --output "$work/shot.png" -- "$work/shot.png"
fi
cp "$work/shot.png" "$png.tmp-$$"  # then renamed: a reader never sees half a file
mv "$png.tmp-$$" "$png"
echo "report_screenshot: wrote $png ($(stat -c %s "$png") bytes)"
