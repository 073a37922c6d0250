#!/usr/bin/env python3
"""Runs a command and prints its wall time and peak resident memory (of the child) as one line:
   peak_rss_mb=<MB> wall_s=<s> exit=<code>
Used by scripts/bench_frame_store.sh; needs only the standard library."""
import resource
import subprocess
import sys
import time

start = time.monotonic()
completed = subprocess.run(sys.argv[1:], stdout=subprocess.DEVNULL)
wall = time.monotonic() - start
peak_kb = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
print(f"peak_rss_mb={peak_kb / 1024:.1f} wall_s={wall:.2f} exit={completed.returncode}")
sys.exit(completed.returncode)
