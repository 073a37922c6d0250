#!/usr/bin/env bash
# The length of every function of common/, formats/ and engine/, longest first, measured with
# Universal Ctags (Debian's universal-ctags: `ctags --version` says "Universal Ctags"): a
# function's lines from its first to its last, as ctags's `end` field gives them.
#
#   scripts/function_lengths.sh [--over N]     (default: every function; --over 100: the count
#                                               and the list of those longer than N lines)
# The project's bound (docs/reliability.md, "Code size"): none over 150 lines, at most 5 over 100.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
over=0
if [ "${1:-}" = "--over" ]; then over="${2:?--over N}"; fi
if ! ctags --version 2>/dev/null | grep -q "Universal Ctags"; then
  echo "function_lengths: needs Universal Ctags (apt-get install universal-ctags)" >&2
  exit 1
fi
cd "$root"
lengths="$(ctags -R --languages=C++ --kinds-C++=f --fields=+ne -x \
  --_xformat='%{line} %{end} %N %F' common formats engine |
  awk '{ print $2 - $1 + 1, $3, $4 }' | sort -rn)"
if [ "$over" -gt 0 ]; then
  selected="$(awk -v n="$over" '$1 > n' <<<"$lengths")"
  echo "$(grep -c . <<<"$selected" || true) functions over $over lines"
  [ -z "$selected" ] || echo "$selected"
else
  echo "$lengths"
fi
