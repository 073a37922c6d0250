#!/usr/bin/env python3
"""The least time each stage of `motifmine mine` could take on this machine, and measured/floor.

  scripts/stage_floor.py RUN_DIR... [--markdown]
      every MineScale row of scripts/bench.sh runs (bench-results/scale-*/; each job's rows from
      the last RUN_DIR that has it, as scripts/bench.sh report does)
  scripts/stage_floor.py RUN_DIR... --data synth|resequenced --frames N --mean-k K
                         [--trellis-bytes-per-frame B] [--evaluations-per-column E]
                         [--warped-pairs P --warped-samples S]
                         --measured trellis=S,grow=S,...
      one end-to-end run outside the suite (scripts/bench_mine_e2e.sh), with the rates of RUN_DIR

The floor of a stage is the larger of its two bounds on 2 cores (docs/benchmarks.md, "The floor"):
  compute: the distance evaluations it cannot avoid over the SIMD kernel's rate (DistanceScale,
           one thread, times the cores): a trellis column must evaluate at least the K
           neighbours it reports, so N * K evaluations;
  memory:  the bytes it must read and write over the machine's bandwidth (MemoryBandwidth,
           2 threads): the trellis reads the archive and writes the features and the trellis file,
           the grower reads the trellis file once.
The clustering's floor is its time-warped distances, P pairs of S samples each, P * S^2
evaluations, where the run says P and S (`motifmine cluster` prints them; --warped-pairs,
--warped-samples); otherwise, and for the report, there is no floor from these rates ("-").
Also printed: the kernel time of the evaluations the LSH search does today (evaluations_per_column
of TrellisBuild at that N, or the largest N below it), which says how much of the trellis stage
is the kernel.
"""
import argparse
import json
import os
import sys

CORES = 2
FEATURE_BYTES_PER_FRAME = 96  # int16 quaternions of the weighted joints (bench_kern_distance.cc)


def rows_of(run_dirs, job):
    """The rows of `job` in the last of `run_dirs` that has its JSON."""
    paths = [os.path.join(d, job + ".json") for d in run_dirs]
    paths = [p for p in paths if os.path.exists(p)]
    if not paths:
        return []
    path = paths[-1]
    try:
        benchmarks = json.load(open(path)).get("benchmarks", [])
    except json.JSONDecodeError:
        return []
    return [b for b in benchmarks if b.get("run_type") != "aggregate"
            and not b.get("error_occurred")]


def frames_of(row):
    for part in row["name"].split("/"):
        if part.startswith("frames:"):
            return int(part.split(":")[1])
    return None


def largest(rows, prefix):
    matching = [r for r in rows if r["name"].startswith(prefix) and frames_of(r)]
    return max(matching, key=frames_of) if matching else None


def nearest(rows, prefix, frames):
    """The row of `prefix` at `frames`, else the largest below it (its per-frame figures)."""
    matching = [r for r in rows if r["name"].startswith(prefix) and frames_of(r)]
    at_or_below = [r for r in matching if frames_of(r) <= frames] or matching
    return max(at_or_below, key=frames_of) if at_or_below else None


class Rates:
    """The machine's rates measured in one scripts/bench.sh run."""

    def __init__(self, run_dirs):
        self.run_dirs = run_dirs
        bandwidth = {r["name"].split("/")[1]: r["bytes_per_second"]
                     for r in rows_of(run_dirs, "bandwidth") if r["name"].endswith("threads:2")}
        if "read" not in bandwidth or "write" not in bandwidth:
            sys.exit("stage_floor.py: no bandwidth.json with MemoryBandwidth/{read,write}/threads:2 "
                     f"rows in {' '.join(run_dirs)} (run scripts/bench.sh quick bandwidth)")
        self.read_bytes_per_s = bandwidth["read"]
        self.write_bytes_per_s = bandwidth["write"]
        self.distance = rows_of(run_dirs, "distance")
        self.decode = rows_of(run_dirs, "decode")
        self.trellis = rows_of(run_dirs, "trellis_real") + rows_of(run_dirs, "trellis_synth")

    def kernel_per_s(self, data):
        row = largest(self.distance, f"DistanceScale/{data}/")
        if row is None:
            sys.exit(f"stage_floor.py: no distance.json with a DistanceScale/{data} row in "
                     f"{' '.join(self.run_dirs)}")
        return row["items_per_second"] * CORES

    def archive_bytes_per_frame(self, data):
        row = largest(self.decode, f"DecodeScale/{data}/")
        return row["archive_bytes_per_frame"] if row else 0.0

    def lsh_row(self, data, frames):
        return nearest(self.trellis, f"TrellisBuild/{data}/lsh/", frames)


def floors(rates, data, frames, mean_k, trellis_bytes_per_frame, warped_evaluations=None):
    """{stage: (floor seconds, what bounds it)}."""
    compute = frames * mean_k / rates.kernel_per_s(data)
    written = frames * (FEATURE_BYTES_PER_FRAME + trellis_bytes_per_frame)
    memory = (frames * rates.archive_bytes_per_frame(data) / rates.read_bytes_per_s
              + written / rates.write_bytes_per_s)
    trellis = (compute, "kernel") if compute >= memory else (memory, "memory")
    grow = (frames * trellis_bytes_per_frame / rates.read_bytes_per_s, "memory")
    cluster = (None, "-")
    if warped_evaluations:
        cluster = (warped_evaluations / rates.kernel_per_s(data), "kernel")
    return {"trellis": trellis, "grow": grow, "cluster": cluster, "report": (None, "-")}


def table(rates, runs):
    """runs: (label, data, frames, mean_k, trellis_bytes_per_frame, (evaluations a column, the N
    of the TrellisBuild row they come from) or None, {stage: seconds}, warped evaluations or
    None)."""
    header = ["run", "stage", "measured s", "floor s", "bound", "measured / floor"]
    lines = []
    for label, data, frames, mean_k, trellis_bytes, evaluations, measured, warped in runs:
        for stage, (floor, bound) in floors(rates, data, frames, mean_k, trellis_bytes,
                                            warped).items():
            seconds = measured.get(stage)
            ratio = f"{seconds / floor:,.0f}" if floor and seconds is not None else "-"
            lines.append([label, stage, "-" if seconds is None else f"{seconds:.2f}",
                          "-" if floor is None else f"{floor:.3g}", bound, ratio])
        if evaluations:
            per_column, at_frames = evaluations
            kernel = frames * per_column / rates.kernel_per_s(data)
            lines.append([label, "trellis: kernel at the LSH's evaluations", "", f"{kernel:.3g}",
                          f"{per_column:,.0f} a column (at {at_frames:,})", ""])
    return header, lines


def print_table(header, lines, markdown):
    if markdown:
        print("| " + " | ".join(header) + " |")
        print("| " + " | ".join("---" for _ in header) + " |")
        for line in lines:
            print("| " + " | ".join(line) + " |")
        return
    widths = [max(len(str(c)) for c in column) for column in zip(header, *lines)]
    for line in [header] + lines:
        print("  ".join(str(c).ljust(w) for c, w in zip(line, widths)).rstrip())


def suite_runs(rates):
    runs = []
    for job in ("mine_real", "mine_synth"):
        for row in rows_of(rates.run_dirs, job):
            frames, data = frames_of(row), row["name"].split("/")[1]
            lsh = rates.lsh_row(data, frames)
            if frames is None or lsh is None:
                continue
            measured = {s: row[s + "_s"] for s in ("trellis", "grow", "cluster", "report")
                        if s + "_s" in row}
            runs.append((f"{data} {frames:,}", data, frames, lsh["mean_k"],
                         lsh["trellis_bytes_per_frame"],
                         (lsh["evaluations_per_column"], frames_of(lsh)), measured, None))
    return runs


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("run_dirs", nargs="+", metavar="RUN_DIR")
    parser.add_argument("--markdown", action="store_true")
    parser.add_argument("--data", choices=("synth", "resequenced"))
    parser.add_argument("--frames", type=float)
    parser.add_argument("--mean-k", type=float)
    parser.add_argument("--trellis-bytes-per-frame", type=float)
    parser.add_argument("--evaluations-per-column", type=float,
                        help="the run's own (`motifmine trellis` prints it); default: the suite's")
    parser.add_argument("--warped-pairs", type=float)
    parser.add_argument("--warped-samples", type=float, default=32)
    parser.add_argument("--measured", default="", help="stage=seconds,... (trellis, grow, ...)")
    args = parser.parse_args()
    rates = Rates(args.run_dirs)
    if args.frames is None:
        runs = suite_runs(rates)
    else:
        if args.data is None or args.mean_k is None:
            parser.error("--frames needs --data and --mean-k")
        frames = int(args.frames)
        lsh = rates.lsh_row(args.data, frames)
        trellis_bytes = args.trellis_bytes_per_frame or (lsh["trellis_bytes_per_frame"] if lsh
                                                         else parser.error(
                                                             "--trellis-bytes-per-frame needed"))
        measured = {}
        for item in filter(None, args.measured.split(",")):
            stage, _, seconds = item.partition("=")
            measured[stage] = float(seconds)
        evaluations = (lsh["evaluations_per_column"], frames_of(lsh)) if lsh else None
        if args.evaluations_per_column:
            evaluations = (args.evaluations_per_column, frames)
        warped = args.warped_pairs * args.warped_samples ** 2 if args.warped_pairs else None
        runs = [(f"{args.data} {frames:,}", args.data, frames, args.mean_k, trellis_bytes,
                 evaluations, measured, warped)]
    print_table(*table(rates, runs), args.markdown)


if __name__ == "__main__":
    main()
