#!/usr/bin/python3
"""The report of scripts/bench.sh runs: tables and plots of every stage against N.

    bench_report.py REPO_ROOT RUN_DIR [RUN_DIR...]

Reads RUN_DIR/machine.json, RUN_DIR/load.tsv and the Google Benchmark JSON of each job
(RUN_DIR/<job>.json; a file cut short by an interrupted run is read up to its last complete
benchmark). With several runs of one mode (a job rerun after a change), a job's rows come from
the last run that has it, and each run's machine and commit are listed. Writes REPO_ROOT/docs/benchmarks/<mode>-<stage>.svg (log-log time and peak resident
memory against N, every series of the stage on the same axes, extrapolated series dashed), and
replaces the section of REPO_ROOT/docs/benchmarks.md between "<!-- bench.sh <mode> begin -->"
and "<!-- bench.sh <mode> end -->" (appended at the end when the markers are absent).

Plots: matplotlib (Debian's python3-matplotlib, a bench-only dependency), SVG with text kept as
text, a fixed hash salt and no date, so that a rerun with the same figures gives the same file.
"""
import glob
import importlib.util
import json
import math
import os
import re
import sys

import matplotlib

matplotlib.use("svg")
import matplotlib.pyplot as plt  # noqa: E402

plt.rcParams["svg.fonttype"] = "none"
plt.rcParams["svg.hashsalt"] = "motifmine-bench"
plt.rcParams["font.size"] = 9


class Series:
    """One line of a plot: the rows whose name matches `pattern`.

    seconds(row) gives the wall time plotted and tabulated (default: the benchmark's own time),
    cpu(row) the CPU seconds of every thread (default: cpu_seconds below);
    extrapolated marks series whose times are not full measurements (dashed lines);
    reference_extrapolate: extend the series linearly (time and memory per frame) from its
    largest measured N up to the largest N of the stage (dotted, "EXTRAPOLATED").
    """

    def __init__(self, label, pattern, seconds=None, cpu=None, extrapolated=False, counters=(),
                 extend_linearly=False):
        self.label = label
        self.pattern = re.compile(pattern)
        self.seconds = seconds or (lambda row: row["seconds"])
        self.cpu = cpu or cpu_seconds
        self.extrapolated = extrapolated
        self.counters = counters
        self.extend_linearly = extend_linearly


class Stage:
    def __init__(self, key, title, job, series, note=""):
        self.key = key
        self.title = title
        self.job = job
        self.series = series
        self.note = note


def per_column_to_archive(block_columns, key="seconds"):
    return lambda row: row[key] * row["frames"] / min(block_columns, row["frames"])


def cpu_seconds(row):
    """CPU seconds of every thread for the row's whole archive: the benchmark's own counter where
    it has one (a child process's, a build's, an extrapolation's), else the process CPU time."""
    for key in ("cpu_s", "build_cpu_s", "exact_search_cpu_extrapolated_s"):
        if key in row:
            return row[key]
    if "faiss_cpu_us_per_column" in row:  # the range searches and verification of N columns
        return row["faiss_cpu_us_per_column"] * 1e-6 * row["frames"]
    return row["cpu_seconds"]


STAGES = [
    Stage("import", "Import and decode", ["import", "decode"], [
        Series("import: parse, convert, write (62 real BVH takes cycled, 1 thread)",
               r"^ImportScale/real/", counters=("archive_bytes_per_frame",)),
        Series("decode, procedural archive (FrameStream, 1 thread)", r"^DecodeScale/synth/",
               counters=("archive_bytes_per_frame",)),
        Series("decode, re-sequenced real archive", r"^DecodeScale/resequenced/",
               counters=("archive_bytes_per_frame",)),
    ], "Items are frames. Decoding streams the archive and releases the pages it has read, so "
       "memory stays flat; import holds one take at a time."),
    Stage("distance", "Distance kernel", ["distance"], [
        Series("64 queries x every frame, procedural (AVX2 block kernel, 1 thread)",
               r"^DistanceScale/synth/"),
        Series("64 queries x every frame, re-sequenced", r"^DistanceScale/resequenced/"),
    ], "Items are pair distances. Memory: the archive's PoseFeatures (96 bytes a frame)."),
    Stage("lsh_build", "LSH index build", ["lsh"], [
        Series("LSH index build, procedural (2 threads)", r"^LshScale/build/synth/",
               counters=("index_bytes_per_frame",)),
        Series("LSH index build, re-sequenced", r"^LshScale/build/resequenced/",
               counters=("index_bytes_per_frame",)),
    ], "LshSearch::Create: parameters from the data, hashing in shards, the merge. Memory "
       "includes the features held before the build."),
    Stage("search", "Every column's eps-neighbours: LSH query against the exact baselines",
          ["lsh", "exact", "faiss"], [
        Series("LSH query, procedural (2 threads; 4,096 columns timed, x N/4,096; the fit is of "
               "the 4,096 columns)",
               r"^LshScale/query/synth/", seconds=per_column_to_archive(4096),
               cpu=per_column_to_archive(4096, "cpu_seconds"), extrapolated=True,
               counters=("recall", "evaluations_per_column", "speedup_vs_exact")),
        Series("LSH query, re-sequenced", r"^LshScale/query/resequenced/",
               seconds=per_column_to_archive(4096), cpu=per_column_to_archive(4096, "cpu_seconds"),
               extrapolated=True,
               counters=("recall", "evaluations_per_column", "speedup_vs_exact")),
        Series("ExactSearch, procedural (2 threads, every column)", r"^ExactScale/synth/frames",
               counters=("mean_k", "cpu_s")),
        Series("ExactSearch, re-sequenced", r"^ExactScale/resequenced/frames",
               counters=("mean_k", "cpu_s")),
        Series("ExactSearch, procedural, EXTRAPOLATED (512 columns timed)",
               r"^ExactScale/synth/extrapolated/", extrapolated=True, counters=("cpu_s",)),
        Series("ExactSearch, re-sequenced, EXTRAPOLATED", r"^ExactScale/resequenced/extrapolated/",
               extrapolated=True, counters=("cpu_s",)),
        Series("FAISS IndexFlatL2 range search + verify, procedural (2 threads; "
               "EXTRAPOLATED above 2^14 from 1,024 columns)", r"^FaissScale/synth/",
               extrapolated=True, counters=("candidates_per_column", "exact_over_faiss")),
        Series("FAISS, re-sequenced", r"^FaissScale/resequenced/", extrapolated=True,
               counters=("candidates_per_column", "exact_over_faiss")),
    ], "The time to find every column of an N-frame archive (features in memory). The LSH rows "
       "time 4,096 columns and multiply; the exact rows are full searches up to 2^17 frames, "
       "then 512 timed columns multiplied by N; FAISS builds the same columns, checked equal to "
       "ExactSearch's bit for bit."),
    Stage("trellis", "Matching trellis build (features, eps, index, search, spill)", ["trellis",
                                                                                      "faiss"], [
        Series("LSH trellis, procedural (2 threads)", r"^TrellisBuild/synth/lsh/.*threads:2",
               counters=("recall", "build_cpu_s", "speedup_vs_exact", "cpu_speedup_vs_exact",
                         "mean_k")),
        Series("LSH trellis, re-sequenced (2 threads)",
               r"^TrellisBuild/resequenced/lsh/.*threads:2",
               counters=("recall", "build_cpu_s", "speedup_vs_exact", "cpu_speedup_vs_exact",
                         "mean_k")),
        Series("LSH trellis, procedural, 1 thread", r"^TrellisBuild/synth/lsh/.*threads:1",
               counters=("recall", "build_cpu_s")),
        Series("LSH trellis, re-sequenced, 1 thread", r"^TrellisBuild/resequenced/lsh/.*threads:1",
               counters=("recall", "build_cpu_s")),
        Series("exact trellis, procedural", r"^TrellisBuild/synth/exact/",
               counters=("build_cpu_s",)),
        Series("exact trellis, re-sequenced", r"^TrellisBuild/resequenced/exact/",
               counters=("build_cpu_s",)),
        Series("exact trellis, procedural, EXTRAPOLATED (1,024 columns timed)",
               r"^TrellisBuild/synth/exact_extrapolated/", extrapolated=True,
               counters=("exact_search_cpu_extrapolated_s",)),
        Series("exact trellis, re-sequenced, EXTRAPOLATED",
               r"^TrellisBuild/resequenced/exact_extrapolated/", extrapolated=True,
               counters=("exact_search_cpu_extrapolated_s",)),
        Series("FAISS exact range search (columns only), procedural, EXTRAPOLATED",
               r"^FaissScale/synth/", extrapolated=True),
        Series("FAISS, re-sequenced, EXTRAPOLATED", r"^FaissScale/resequenced/",
               extrapolated=True),
    ], "The whole `BuildTrellis` from the archive file (k_max 256). Recall: share of the exact "
       "k_max-nearest found, 500 sampled columns; speedup_vs_exact: the exact build's time "
       "(extrapolated from 1,024 columns, same process, right after) over the LSH build's."),
    Stage("spill", "Trellis spill (TrellisFileWriter, fsync per block)", ["spill"], [
        Series("spill K = 256 columns (1 thread)", r"^SpillScale/walk/",
               counters=("trellis_bytes_per_frame",)),
    ], "Encoding, compressing, writing and syncing 4,096-column blocks of K = 256, as the trellis "
       "builder's writer thread does beside the search."),
    Stage("grow", "Path grower: streaming against the O(N K^2) reference", ["grow"], [
        Series("streaming grower, K = 256 (1 thread)", r"^GrowScale/streaming/",
               counters=("entries_per_cpu_s", "grower_B_per_frame", "candidates")),
        Series("reference grower O(N K^2), K = 256", r"^GrowScale/reference/",
               counters=("entries_per_cpu_s",), extend_linearly=True),
    ], "Random-walk trellis files of N columns (bench/bench_trellises.h). The reference holds the "
       "whole trellis in memory (8 bytes an entry) and is measured up to 2^20 columns; above, "
       "its time and memory per column are extended linearly from its largest measured row "
       "(EXTRAPOLATED)."),
    Stage("cluster", "Clustering", ["cluster"], [
        Series("clustering, separate motifs, N/1024 instances (2 threads)",
               r"^ClusterScale/separate/", counters=("instances", "motifs", "planted")),
        Series("clustering, chained motifs (one connected graph)", r"^ClusterScale/chained/",
               counters=("instances", "motifs", "planted")),
    ], "ClusterMotifs on synthetic trellises (16-20 entries a column) with N / 1024 planted "
       "instances: similarity streamed from the trellis, then normalized cut."),
    Stage("mine", "Whole `motifmine mine` (child process)", ["mine"], [
        Series("mine, procedural archive (2 threads)", r"^MineScale/synth/",
               counters=("cpu_s", "trellis_s", "grow_s", "cluster_s", "report_s", "recall",
                         "precision", "ari")),
        Series("mine, re-sequenced real archive", r"^MineScale/resequenced/",
               counters=("cpu_s", "trellis_s", "grow_s", "cluster_s", "report_s", "recall",
                         "precision", "ari")),
    ], "`motifmine mine ARCHIVE --out DIR --threads 2 -q` on archives from `motifmine synth` "
       "(12-degree background variation; `--search auto`: exact below 90,000 frames, LSH above). "
       "Peak memory is the child's ru_maxrss; cpu_s its user + system time."),
]

UNIT_SECONDS = {"s": 1.0, "ms": 1e-3, "us": 1e-6, "ns": 1e-9}
BIG_O = {"(1)": lambda n: 1.0, "N": lambda n: n, "NlgN": lambda n: n * math.log2(n),
         "N^2": lambda n: n * n, "N^3": lambda n: n ** 3, "lgN": lambda n: math.log2(n)}


def load_benchmarks(path):
    """The benchmarks of a Google Benchmark JSON file, complete or cut short."""
    text = open(path).read()
    try:
        return json.loads(text).get("benchmarks", [])
    except ValueError:
        pass
    start = text.find('"benchmarks": [')
    if start < 0:
        return []
    decoder = json.JSONDecoder()
    position = start + len('"benchmarks": [')
    found = []
    while True:
        while position < len(text) and text[position] in " \n\r\t,":
            position += 1
        try:
            value, position = decoder.raw_decode(text, position)
        except ValueError:
            return found
        found.append(value)


def clean_name(name):
    return re.sub(r"/(iterations:\d+|real_time|manual_time|process_time)", "", name)


def job_files(run_dirs):
    """{job: (run_dir, path)}: each job's JSON from the last run that has it."""
    files = {}
    for run_dir in run_dirs:
        for path in sorted(glob.glob(os.path.join(run_dir, "*.json"))):
            job = os.path.basename(path)[:-5]
            if job != "machine" and load_benchmarks(path):
                files[job] = (run_dir, path)
    return files


def load_runs(files):
    rows, fits = [], {}
    for job, (_, path) in sorted(files.items()):
        for b in load_benchmarks(path):
            name = clean_name(b.get("name", ""))
            if b.get("run_type") == "aggregate":
                base = clean_name(b.get("run_name", name))
                entry = fits.setdefault((job, b.get("family_index"), base), {})
                if b.get("aggregate_name") == "BigO":
                    entry["big_o"] = b.get("big_o")
                    entry["coefficient"] = b.get("real_coefficient")
                    entry["unit"] = b.get("time_unit", "ns")
                elif b.get("aggregate_name") == "RMS":
                    entry["rms"] = b.get("rms")
                continue
            frames = re.search(r"frames:(\d+)", name)
            if not frames:
                continue
            row = dict(b)
            row["job"] = job
            row["name"] = name
            row["frames"] = int(frames.group(1))
            unit = UNIT_SECONDS.get(b.get("time_unit", "ns"), 1)
            row["seconds"] = b.get("real_time", 0) * unit
            row["cpu_seconds"] = b.get("cpu_time", 0) * unit
            rows.append(row)
    return rows, fits


def fmt(value, digits=3):
    if value is None:
        return "-"
    if isinstance(value, str):
        return value
    if value == 0:
        return "0"
    magnitude = abs(value)
    if magnitude >= 1000:
        return f"{value:,.0f}"
    return f"{value:.{max(0, digits - 1 - int(math.floor(math.log10(magnitude))))}f}"


def power_of_two(n):
    exponent = math.log2(n)
    return f"2^{int(exponent)}" if exponent == int(exponent) else f"{n:,}"


def slope(points):
    """Least-squares slope of log(y) against log(x): the empirical exponent."""
    points = [(x, y) for x, y in points if x > 0 and y and y > 0]
    if len(points) < 2:
        return None
    xs = [math.log(x) for x, _ in points]
    ys = [math.log(y) for _, y in points]
    mean_x, mean_y = sum(xs) / len(xs), sum(ys) / len(ys)
    denominator = sum((x - mean_x) ** 2 for x in xs)
    if denominator == 0:
        return None
    return sum((x - mean_x) * (y - mean_y) for x, y in zip(xs, ys)) / denominator


def series_rows(series, rows, jobs):
    """The rows of `series` from the stage's jobs ("trellis" covers trellis_real and
    trellis_synth)."""
    return sorted((r for r in rows
                   if r["job"].split("_")[0] in jobs and series.pattern.search(r["name"])),
                  key=lambda r: r["frames"])


def fit_of(series, rows, fits):
    """Google Benchmark's complexity fit of the family the series' rows come from."""
    for (job, family, base), fit in fits.items():
        if "big_o" not in fit:
            continue
        if any(r["job"] == job and r.get("family_index") == family for r in rows):
            return fit
    return None


def extension(series, measured, largest):
    """Linear extension of a series from its largest measured row up to `largest` frames."""
    if not measured:
        return []
    last = measured[-1]
    out = []
    n = last["frames"] * 2
    while n <= largest:
        ratio = n / last["frames"]
        out.append({"frames": n, "time": series.seconds(last) * ratio,
                    "cpu": series.cpu(last) * ratio,
                    "memory": last.get("peak_rss_bytes", 0) * ratio})
        n *= 2
    return out


PANELS = (("wall time (s)", lambda series, r: series.seconds(r), "time"),
          ("CPU time, every thread (s)", lambda series, r: series.cpu(r), "cpu"),
          ("peak resident memory (MiB)",
           lambda series, r: r.get("peak_rss_bytes", float("nan")) / 2 ** 20, "memory"))


def plot_stage(stage, per_series, path, largest):
    fig, axes = plt.subplots(1, 3, figsize=(12, 4.2))
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    handles = []
    for idx, (series, measured, extended) in enumerate(per_series):
        good = [r for r in measured if not r.get("error_occurred")]
        if not good:
            continue
        color = colors[idx % len(colors)]
        style = "--" if series.extrapolated else "-"
        face = "none" if series.extrapolated else color
        xs = [r["frames"] for r in good]
        for ax, (_, value, key) in zip(axes, PANELS):
            ys = [value(series, r) for r in good]
            (line,) = ax.plot(xs, ys, style, marker="o", color=color, mfc=face, ms=4,
                              label=series.label)
            if extended:
                scale = 2 ** 20 if key == "memory" else 1
                ax.plot([xs[-1]] + [e["frames"] for e in extended],
                        [ys[-1]] + [e[key] / scale for e in extended], ":", color=color)
        handles.append(line)
    for ax, (ylabel, _, _) in zip(axes, PANELS):
        ax.set_xscale("log", base=2)
        ax.set_yscale("log")
        ax.set_xlabel("N (frames)")
        ax.set_ylabel(ylabel)
        ax.grid(True, which="major", alpha=0.3)
    # Guides on the time panels: O(N) and O(N^2) through the first point of the first series.
    first = next(((series, m) for series, m, _ in per_series
                  if [r for r in m if not r.get("error_occurred")]), None)
    if first:
        series, measured = first
        row = [r for r in measured if not r.get("error_occurred")][0]
        n0 = row["frames"]
        for ax, (_, value, key) in zip(axes[:2], PANELS[:2]):
            t0 = value(series, row)
            if not t0 or t0 <= 0 or largest <= n0:
                continue
            ax.plot([n0, largest], [t0, t0 * largest / n0], color="0.6", lw=0.8, zorder=0)
            ax.plot([n0, largest], [t0, t0 * (largest / n0) ** 2], color="0.8", lw=0.8, zorder=0)
            ax.text(largest, t0 * largest / n0, " O(N)", color="0.5", fontsize=7, va="center")
            ax.text(largest, t0 * (largest / n0) ** 2, " O(N²)", color="0.6", fontsize=7,
                    va="center")
    fig.suptitle(stage.title, fontsize=10, x=0.01, ha="left")
    fig.legend(handles=handles, loc="lower center", ncol=2, fontsize=7, frameon=False)
    rows_of_legend = (len(handles) + 1) // 2
    fig.tight_layout(rect=(0, 0.045 * rows_of_legend + 0.02, 1, 0.96))
    fig.savefig(path, metadata={"Date": None})
    plt.close(fig)


def stage_markdown(stage, per_series, fits, image):
    lines = [f"#### {stage.title}", "", stage.note, "", f"![{stage.title}]({image})", ""]
    lines.append("| series | N | wall s | CPU s | items / wall s | peak RSS MiB | peak B/frame "
                 "| other |")
    lines.append("| --- | ---: | ---: | ---: | ---: | ---: | ---: | --- |")
    for series, measured, extended in per_series:
        for r in measured:
            if r.get("error_occurred"):
                lines.append(f"| {series.label} | {power_of_two(r['frames'])} | skipped: "
                             f"{r.get('error_message', '')[:120]} | | | | | |")
                continue
            other = ", ".join(f"{c} {fmt(r[c])}" for c in series.counters if c in r)
            label = r.get("label", "")
            if "EXTRAPOLATED" in label and "EXTRAPOLATED" not in series.label:
                other = (other + ", " if other else "") + label
            peak = r.get("peak_rss_bytes")
            lines.append(
                f"| {series.label} | {power_of_two(r['frames'])} | {fmt(series.seconds(r))} | "
                f"{fmt(series.cpu(r))} | {fmt(r.get('items_per_second'))} | "
                f"{fmt(peak / 2 ** 20) if peak else '-'} | "
                f"{fmt(peak / r['frames']) if peak else '-'} | {other} |")
        for e in extended:
            lines.append(f"| {series.label}, EXTRAPOLATED linearly | {power_of_two(e['frames'])} "
                         f"| {fmt(e['time'])} | {fmt(e['cpu'])} | | {fmt(e['memory'] / 2 ** 20)} "
                         f"| {fmt(e['memory'] / e['frames'])} | |")
    lines.append("")
    fit_lines = []
    for series, measured, _ in per_series:
        good = [r for r in measured if not r.get("error_occurred")]
        if len(good) < 2:
            continue
        parts = []
        fit = fit_of(series, good, fits)
        if fit:
            coefficient = fit.get("coefficient", 0) * UNIT_SECONDS.get(fit.get("unit", "ns"), 1)
            rms = f"{100 * fit['rms']:.0f} %" if "rms" in fit else "-"
            parts.append(f"Google Benchmark's fit {fmt(coefficient * 1e9)} ns x {fit['big_o']} "
                         f"(RMS {rms})")
        upper = good[len(good) // 2:] if len(good) >= 4 else good
        span = f"{power_of_two(upper[0]['frames'])}-{power_of_two(upper[-1]['frames'])}"
        time_slope = slope([(r["frames"], series.seconds(r)) for r in upper])
        cpu_slope = slope([(r["frames"], series.cpu(r)) for r in upper])
        memory_slope = slope([(r["frames"], r.get("peak_rss_bytes")) for r in upper])
        exponents = []
        if time_slope is not None:
            exponents.append(f"wall ~ N^{time_slope:.2f}")
        if cpu_slope is not None:
            exponents.append(f"CPU ~ N^{cpu_slope:.2f}")
        if memory_slope is not None:
            exponents.append(f"peak memory ~ N^{memory_slope:.2f}")
        if exponents:
            parts.append(", ".join(exponents) + f" over {span}")
        a, b = good[-2], good[-1]
        if a.get("peak_rss_bytes") and b.get("peak_rss_bytes"):
            marginal = (b["peak_rss_bytes"] - a["peak_rss_bytes"]) / (b["frames"] - a["frames"])
            parts.append(f"marginal memory {fmt(marginal)} B/frame "
                         f"({power_of_two(a['frames'])} to {power_of_two(b['frames'])})")
        fit_lines.append(f"- {series.label}: " + "; ".join(parts))
    if fit_lines:
        lines += ["Fits (Google Benchmark's ->Complexity() on the benchmark's own time; "
                  "exponents: least-squares slopes of log time and log peak memory against "
                  "log N over the upper half of the sizes):", ""] + fit_lines + [""]
    return lines


def load_summary(run_dir):
    loads = []
    path = os.path.join(run_dir, "load.tsv")
    if os.path.exists(path):
        for line in open(path):
            parts = line.split()
            if len(parts) >= 2:
                loads.append(float(parts[1]))
    if not loads:
        return "not sampled"
    return (f"1-minute load average {min(loads):.1f}-{max(loads):.1f} "
            f"(mean {sum(loads) / len(loads):.1f}, {len(loads)} samples, every 30 s)")


def run_lines(run_dir, jobs):
    machine = json.load(open(os.path.join(run_dir, "machine.json")))
    return [
        f"- run `bench-results/{os.path.basename(os.path.normpath(run_dir))}/` (raw JSON, "
        f"git-ignored; jobs {', '.join(sorted(jobs))}): command `{machine.get('command')}`, "
        f"commit `{machine.get('commit')}`"
        + (" **with uncommitted changes**" if machine.get("dirty") else "")
        + f", Release build; {machine.get('started')} to "
        f"{machine.get('finished', '(unfinished)')}",
        f"  - machine: {machine.get('nproc')} cores ({machine.get('cpu_model')}), "
        f"{machine.get('memory_gib')} GiB, {machine.get('kernel')}, shared with other engineers' "
        "builds (compare ratios within a run); load average (1, 5, 15 min) "
        f"{machine.get('load_at_start')} at the start, {machine.get('load_at_end', '-')} at the "
        f"end; {load_summary(run_dir)}"]


def floor_markdown(run_dirs):
    """The mine rows against their floor (scripts/stage_floor.py); nothing when no run measured
    the bandwidth."""
    if not any(os.path.exists(os.path.join(d, "bandwidth.json")) for d in run_dirs):
        return []
    spec = importlib.util.spec_from_file_location(
        "stage_floor", os.path.join(os.path.dirname(os.path.abspath(__file__)), "stage_floor.py"))
    stage_floor = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(stage_floor)
    rates = stage_floor.Rates(run_dirs)
    header, lines = stage_floor.table(rates, stage_floor.suite_runs(rates))
    if not lines:
        return []
    return (["#### The mine rows against their floor", "",
             "`scripts/stage_floor.py "
             + " ".join(os.path.basename(os.path.normpath(d)) for d in run_dirs) + "`: "
             "the least time of each stage from these runs' kernel rate and memory bandwidth "
             "(docs/benchmarks.md, \"The floor\"). The small mine rows use the exact search; the "
             "LSH's evaluations are those of TrellisBuild at that N.", "",
             "| " + " | ".join(header) + " |", "| " + " | ".join("---" for _ in header) + " |"]
            + ["| " + " | ".join(line) + " |" for line in lines] + [""])


def main():
    root, run_dirs = sys.argv[1], sys.argv[2:]
    mode = json.load(open(os.path.join(run_dirs[-1], "machine.json"))).get("mode", "quick")
    files = job_files(run_dirs)
    rows, fits = load_runs(files)
    image_dir = os.path.join(root, "docs", "benchmarks")
    os.makedirs(image_dir, exist_ok=True)
    body = [f"<!-- bench.sh {mode} begin -->",
            f"### Scaling, {mode} mode",
            "",
            "Generated by `scripts/bench.sh` (tables and plots; edit the script, not this "
            "section).",
            ""]
    for run_dir in run_dirs:
        jobs = [job for job, (d, _) in files.items() if d == run_dir]
        if jobs:
            body += run_lines(run_dir, jobs)
    body.append("")
    for stage in STAGES:
        per_series = []
        for series in stage.series:
            measured = series_rows(series, rows, stage.job)
            per_series.append([series, measured, []])
        if not any(m for _, m, _ in per_series):
            continue
        largest = max(r["frames"] for _, m, _ in per_series for r in m)
        for entry in per_series:
            if entry[0].extend_linearly:
                entry[2] = extension(entry[0], [r for r in entry[1]
                                                if not r.get("error_occurred")], largest)
        per_series = [entry for entry in per_series if entry[1]]
        image = f"{mode}-{stage.key}.svg"
        plot_stage(stage, per_series, os.path.join(image_dir, image), largest)
        body += stage_markdown(stage, per_series, fits, f"benchmarks/{image}")
    body += floor_markdown(run_dirs)
    body.append(f"<!-- bench.sh {mode} end -->")

    doc_path = os.path.join(root, "docs", "benchmarks.md")
    doc = open(doc_path).read()
    begin, end = f"<!-- bench.sh {mode} begin -->", f"<!-- bench.sh {mode} end -->"
    section = "\n".join(body)
    if begin in doc and end in doc:
        doc = doc[:doc.index(begin)] + section + doc[doc.index(end) + len(end):]
    else:
        doc = doc.rstrip("\n") + "\n\n" + section + "\n"
    with open(doc_path + ".tmp", "w") as out:
        out.write(doc)
    os.replace(doc_path + ".tmp", doc_path)
    print(f"wrote the {mode} section of {doc_path} and {image_dir}/{mode}-*.svg")


if __name__ == "__main__":
    main()
