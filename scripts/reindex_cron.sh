#!/usr/bin/env bash
# One night's `motifmine reindex`, for cron: imports the new takes of DIR into ARCHIVE, updates
# the mined output in OUTDIR, logs JSON lines, and prints only when a person should look (cron
# mails whatever a job prints).
#
#   scripts/reindex_cron.sh ARCHIVE DIR OUTDIR [extra reindex options...]
#
# A ready crontab line (every night at 02:30):
#   30 2 * * *  /opt/motifmine/scripts/reindex_cron.sh /data/mocap/archive.mfs /data/mocap/incoming /data/mocap/mined
#
# Environment: MOTIFMINE (the binary; default build/motifmine beside this script),
# MOTIF_REINDEX_LOGS (the log folder; default OUTDIR/logs), MOTIF_REINDEX_KEEP_DAYS (30).
# Exit codes are reindex's (docs/guide.md): 0 done or up to date, and 17 (a previous run is still
# going: tonight's takes are done next time) stay silent; 3 (files not imported) prints which;
# any other code prints the error and the last log lines, and the previous version is intact.
set -u
if [ $# -lt 3 ]; then
  echo "usage: $0 ARCHIVE DIR OUTDIR [reindex options...]" >&2
  exit 2
fi
archive=$1
watch=$2
out=$3
shift 3
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
motifmine=${MOTIFMINE:-$root/build/motifmine}
logs=${MOTIF_REINDEX_LOGS:-$out/logs}
keep_days=${MOTIF_REINDEX_KEEP_DAYS:-30}
mkdir -p "$logs" || exit 14
log="$logs/reindex-$(date +%F).jsonl"
summary=$(mktemp)
trap 'rm -f "$summary"' EXIT

# Progress and notes (stderr) and the summary line (stdout) all go to the day's log.
nice -n 10 "$motifmine" reindex "$archive" --watch "$watch" --out "$out" --skip-bad \
  --progress=json "$@" >"$summary" 2>>"$log"
code=$?
cat "$summary" >>"$log"
find "$logs" -name 'reindex-*.jsonl' -mtime +"$keep_days" -delete 2>/dev/null

case $code in
  0 | 17)
    exit 0
    ;;
  3)
    echo "motifmine reindex: $out is up to date, with warnings (takes of $watch not imported, or a file not yet replaced):"
    python3 - "$summary" <<'EOF' 2>/dev/null || cat "$summary"
import json, sys
line = json.load(open(sys.argv[1]))
for message in line.get("changed", []) + line.get("failed", []) + line.get("warnings", []):
    print("  " + message)
EOF
    echo "(log: $log)"
    exit 3
    ;;
  *)
    echo "motifmine reindex failed with exit code $code; $out still holds the previous version."
    grep -h '"error"' "$summary" 2>/dev/null
    echo "last log lines ($log):"
    tail -n 15 "$log"
    exit "$code"
    ;;
esac
