#!/usr/bin/env python3
"""Tables of the distance study (scripts/eval_distance_study.sh, docs/design/motion_distance.md).

usage: distance_study_table.py ROWS.tsv [MOVEMENTS.tsv]

ROWS.tsv: one row per take and candidate, as bench/studies/distance_study writes it (out=);
MOVEMENTS.tsv: one row per take, candidate and movement (movements_out=). Standard library only.
"""
import csv
import statistics
import sys
from collections import OrderedDict, defaultdict

HARD_TAKES = ("17_10", "06_13", "60_01")


def read(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f, delimiter="\t"))


def mean(values):
    return statistics.mean(values) if values else float("nan")


def by_candidate(rows):
    groups = OrderedDict()
    for row in rows:
        groups.setdefault(row["candidate"], []).append(row)
    return groups


def summary(groups):
    print("| candidate | column | takes | 1-NN, mean over takes | 1-NN, pooled over queries | "
          "nearest is partial, pooled | AUC, pooled per take (mean) | AUC per query (mean) | "
          "one pair of 1 s stretches, us | one column pair, ns | one column, ns | one frame, ns |")
    print("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for name, rows in groups.items():
        takes = [r for r in rows if int(r["queries"]) > 0]
        nn = [int(r["hits"]) / int(r["queries"]) for r in takes]
        queries = max(1, sum(int(r["queries"]) for r in takes))
        pooled = sum(int(r["hits"]) for r in takes) / queries
        partial = sum(int(r["partial_misses"]) for r in takes) / queries
        auc = [float(r["auc_pooled"]) for r in takes if float(r["auc_pooled"]) >= 0]
        auc_q = [float(r["auc_query"]) for r in takes if float(r["auc_query"]) >= 0]
        cost = lambda key: statistics.median(float(r[key]) for r in rows)
        print(f"| {name} | {rows[0]['column']} | {len(takes)} | {mean(nn):.3f} | {pooled:.3f} | "
              f"{partial:.3f} | {mean(auc):.3f} ({len(auc)}) | {mean(auc_q):.3f} | "
              f"{cost('pair_ns') / 1000:.2f} | "
              f"{cost('column_pair_ns'):.0f} | {cost('column_ns'):.0f} | {cost('frame_ns'):.0f} |")


def bootstrap(groups, reference="quat_dtw", draws=2000, seed=1):
    """Each candidate against `reference`: the difference of the mean 1-NN fraction over takes,
    of the 1-NN fraction pooled over queries and of the mean pooled AUC, with 90 % intervals from
    resampling the takes with replacement (seeded)."""
    if reference not in groups:
        return
    import random
    rng = random.Random(seed)
    ref = {r["take"]: r for r in groups[reference]}
    takes = [t for t in ref if int(ref[t]["queries"]) > 0]
    samples = [[rng.choice(takes) for _ in takes] for _ in range(draws)]

    def stats(rows, chosen):
        nn = mean([int(rows[t]["hits"]) / int(rows[t]["queries"]) for t in chosen])
        queries = sum(int(rows[t]["queries"]) for t in chosen)
        pooled = sum(int(rows[t]["hits"]) for t in chosen) / queries
        aucs = [float(rows[t]["auc_pooled"]) for t in chosen if float(rows[t]["auc_pooled"]) >= 0]
        return nn, pooled, mean(aucs)

    def interval(values):
        values = sorted(values)
        return values[int(0.05 * len(values))], values[int(0.95 * len(values)) - 1]

    print(f"| candidate | 1-NN mean over takes minus {reference}'s | 1-NN pooled, minus | "
          "AUC (pooled per take, mean), minus |")
    print("|---|---:|---:|---:|")
    for name, rows in groups.items():
        mine = {r["take"]: r for r in rows}
        if name == reference or any(t not in mine for t in takes):
            continue
        point = [a - b for a, b in zip(stats(mine, takes), stats(ref, takes))]
        diffs = [[a - b for a, b in zip(stats(mine, c), stats(ref, c))] for c in samples]
        cells = []
        for k in range(3):
            low, high = interval([d[k] for d in diffs])
            cells.append(f"{point[k]:+.3f} [{low:+.3f}, {high:+.3f}]")
        print(f"| {name} | " + " | ".join(cells) + " |")


def distribution(groups):
    print("| candidate | aligned cells' percentile in the take, median (mean over takes) | "
          "their 90th percentile (mean) | aligned cells within the take's 10 % quantile (mean) | "
          "take's q10 / q50 (mean) | q10 across takes: mean, coefficient of variation |")
    print("|---|---:|---:|---:|---:|---:|")
    for name, rows in groups.items():
        rows = [r for r in rows if r["stats"] == "1" and int(r["aligned_cells"]) > 0]
        if not rows:
            continue
        q10 = [float(r["random_q10"]) for r in rows]
        ratio = [float(r["random_q10"]) / float(r["random_q50"]) for r in rows]
        cv = statistics.pstdev(q10) / mean(q10) if mean(q10) > 0 else float("nan")
        print(f"| {name} | {mean([float(r['aligned_pct_median']) for r in rows]):.3f} | "
              f"{mean([float(r['aligned_pct_p90']) for r in rows]):.3f} | "
              f"{mean([float(r['aligned_within_q10']) for r in rows]):.3f} | {mean(ratio):.3f} | "
              f"{mean(q10):.4f}, {cv:.2f} |")


def per_take(groups, key, title):
    names = list(groups)
    takes = list(OrderedDict.fromkeys(r["take"] for rows in groups.values() for r in rows))
    cell = {(r["take"], r["candidate"]): r for rows in groups.values() for r in rows}
    print(f"{title}")
    print("| take | queries | " + " | ".join(names) + " |")
    print("|---|---:|" + "---:|" * len(names))
    for take in takes:
        first = next(cell[(take, n)] for n in names if (take, n) in cell)
        values = []
        for name in names:
            row = cell.get((take, name))
            if row is None or int(row["queries"]) == 0:
                values.append("-")
            elif key == "nn":
                values.append(f"{int(row['hits']) / int(row['queries']):.2f}")
            else:
                value = float(row[key])
                values.append(f"{value:.2f}" if value >= 0 else "-")
        print(f"| {take} | {first['queries']} | " + " | ".join(values) + " |")


def movements(path, names):
    rows = read(path)
    table = defaultdict(dict)
    counts = {}
    for row in rows:
        key = (row["take"], row["movement"])
        table[key][row["candidate"]] = (int(row["hits"]), int(row["queries"]))
        counts[key] = int(row["queries"])
    print("1-NN hits by movement (hits of queries):")
    print("| take | movement | queries | " + " | ".join(names) + " |")
    print("|---|---|---:|" + "---:|" * len(names))
    for take, movement in table:
        cells = table[(take, movement)]
        values = [f"{cells[n][0]}" if n in cells else "-" for n in names]
        print(f"| {take} | {movement} | {counts[(take, movement)]} | " + " | ".join(values) + " |")


def main():
    rows = read(sys.argv[1])
    groups = by_candidate(rows)
    print(f"{len(OrderedDict.fromkeys(r['take'] for r in rows))} takes")
    print()
    summary(groups)
    print()
    bootstrap(groups)
    print()
    distribution(groups)
    print()
    per_take(groups, "nn", "1-NN fraction by take:")
    print()
    per_take(groups, "auc_pooled", "ROC AUC (pooled over the take's queries) by take:")
    print()
    print("What each candidate is:")
    for name, rows in groups.items():
        print(f"- {name}: column = {rows[0]['column']}; {rows[0]['properties']}")
    for name, rows in groups.items():
        notes = [f"{r['take']}: {r['note']}" for r in rows if r.get("note")]
        if notes:
            print(f"- {name}, by take: " + "; ".join(notes))
    if len(sys.argv) > 2:
        print()
        movements(sys.argv[2], list(groups))


if __name__ == "__main__":
    main()
