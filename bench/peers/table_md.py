#!/usr/bin/python3
"""Markdown tables for docs/performance.md from results/performance/peers.csv (and meshlab.csv).
usage: table_md.py peers.csv [meshlab.csv]
       table_md.py --rounds ROUNDS.csv[,PEERS.csv] [ROUNDS2.csv[,PEERS2.csv] ...]
       table_md.py --targets ROUNDS.csv PEERS.csv PEERS.log [MESHLAB.csv ...]
The second form: the interleaved rounds (peer_compare --rounds-csv) as medians per pair, one
value per run in each cell (separated by " · "); with the run's PEERS.csv (its --csv) the
2-thread speed-up of the best-of rows too.
The third form: issue 3's targets against one run_all.sh run (its rounds.csv, peers.csv,
peers.log and any MeshLab CSVs), one row per target with the measured values and whether each
is met: the "latest run" column of the table at the top of docs/performance.md. Pairs missing
from the run are said to be."""
import csv
import re
import statistics
import sys
from collections import OrderedDict


def peers(path):
    rows = list(csv.DictReader(open(path)))
    print("| pair (A→B) | faces A→B | samples | engine | thr | build s | M q/s | CPU share "
          "| M q/CPU-s | meshdev ÷ this (wall) | (per CPU-s) | B/face |")
    print("|---|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    for r in rows:
        series, name = r["label"].split("|", 1) if "|" in r["label"] else ("", r["label"])
        if series != "pairs":
            continue
        print(f"| {name} | {int(r['a_faces']):,}→{int(r['b_faces']):,} | {int(r['samples']):,} "
              f"| {r['engine']} | {r['threads']} | {float(r['build_s']):.3f} "
              f"| {float(r['qps']) / 1e6:.2f} | {float(r['cpu_share']):.2f} "
              f"| {float(r['qps_per_cpu_s']) / 1e6:.2f} | {float(r['meshdev_over_engine']):.2f} "
              f"| {float(r['meshdev_over_engine_per_cpu']):.2f} "
              f"| {float(r['struct_bytes_per_face']):.0f} |")
    print()
    for series, key, title in (("faces", "b_faces", "faces of B"), ("samples", "samples", "samples")):
        table = OrderedDict()
        engines = []
        for r in rows:
            if not r["label"].startswith(series + "|"):
                continue
            col = f"{r['engine']} {r['threads']}t"
            if col not in engines:
                engines.append(col)
            table.setdefault(int(r[key]), {})[col] = (float(r["qps"]) / 1e6,
                                                     float(r["qps_per_cpu_s"]) / 1e6)
        if not table:
            continue
        print(f"| {title} | " + " | ".join(engines) + " |")
        print("|---:|" + "---:|" * len(engines))
        for x in sorted(table):
            cells = [f"{table[x][e][0]:.2f} ({table[x][e][1]:.2f})" if e in table[x] else "–"
                     for e in engines]
            print(f"| {x:,} | " + " | ".join(cells) + " |")
        print("\nM q/s wall (M q per CPU-second in brackets).\n")


def meshlab(path):
    rows = list(csv.DictReader(open(path)))
    geometry = bool(rows) and "meshdev_geometry_s" in rows[0]  # files before session 7 lack it
    print("| A | B | faces | samples/dir | meshdev s | MeshLab xvfb-run s | MeshLab warm s "
          "| ratio (xvfb) | ratio (warm) |"
          + (" meshdev geometry-only s | ratio geometry-only (xvfb / warm) |" if geometry else "")
          + " mean A→B meshdev / MeshLab | load |")
    print("|---|---|---|---:|---:|---:|---:|---:|---:|" + ("---:|---:|" if geometry else "")
          + "---|---|")
    for r in rows:
        extra = (f" {float(r['meshdev_geometry_s']):.3f} | {r['ratio_geometry_xvfb']} / "
                 f"{r['ratio_geometry_warm']} |" if geometry else "")
        print(f"| {r['a']} | {r['b']} | {int(r['a_faces']):,}/{int(r['b_faces']):,} "
              f"| {int(r['samples_per_direction']):,} | {float(r['meshdev_s']):.3f} "
              f"| {float(r['meshlab_xvfb_s']):.2f} | {float(r['meshlab_warm_s']):.2f} "
              f"| {r['ratio_xvfb']} | {r['ratio_warm']} |" + extra
              + f" {float(r['meshdev_mean_ab']):.6g} / {r['meshlab_mean_ab']} "
              f"| {r['load_start']}–{r['load_end']} |")


def pair_name(label):
    return (label.split("|", 1)[1] if "|" in label else label).replace("->", "→")


def labels_of(rows):
    """The rows' labels, each once, in their first order."""
    return list(OrderedDict.fromkeys(r["label"] for r in rows))


def by_round(rows, label, column):
    """One pair's rounds in a rounds CSV: {thread count: {round: float(column)}} for 1 and 2."""
    return {t: {r["round"]: float(r[column]) for r in rows
                if r["label"] == label and r["threads"] == t} for t in ("1", "2")}


def speedup_of(rows, label):
    """meshdev's 2-thread speed-up on one pair of a rounds CSV: (value, paired). Rounds that ran
    both thread counts seconds apart (files with a start_s column, since the forty-seventh
    session) give the median of each round's ratio; older files, whose 1-thread rounds all ran
    before the 2-thread ones, the ratio of the two medians. None if a thread count is missing."""
    med = statistics.median
    by = by_round(rows, label, "meshdev_qps")
    if not by["1"] or not by["2"]:
        return None
    if "start_s" in rows[0]:
        common = [k for k in by["1"] if k in by["2"]]
        return med([by["2"][k] / by["1"][k] for k in common]), True
    return med(by["2"].values()) / med(by["1"].values()), False


def host_rounds(rows, label):
    """The host probe before each meshdev run of one pair's rounds (files with a probe_s column,
    since the forty-seventh session): {round: the probe's 2-thread speed-up}, 1-thread time over
    2-thread time (2 where the host gave two physical cores). Empty for older files."""
    if not rows or "probe_s" not in rows[0]:
        return {}
    by = by_round(rows, label, "probe_s")
    return {k: by["1"][k] / by["2"][k] for k in by["1"] if k in by["2"]}


# A round whose host probe gave at least this 2-thread speed-up is taken to have had two physical
# cores (in the forty-seventh session 68 of 90 rounds' probes gave 1.90-2.39x, the others
# 1.03-1.89x).
kFullHost = 1.9

# A 2-thread run whose threads answered samples in a ratio of at least this (peer_compare's
# thread_split) had one core slower than the other through it: the fifty-first session's
# undisturbed runs split 1.00-1.09 (host_levels.py on its rounds; docs/performance-log.md §3).
kUneven = 1.1


def rounds(runs):
    """runs: [(rounds rows, peers rows or None)], one per run."""
    med = statistics.median

    def span(values):
        return f"{med(values):.2f} ({min(values):.2f}–{max(values):.2f})"

    pairs = labels_of([r for rows, _ in runs for r in rows])
    print("| pair | meshdev M/s, 1 / 2 threads | ÷ Embree, 1 thread | ÷ Embree, 2 threads "
          "| ÷ Embree+hint, 2 threads | 2-thread speed-up (best-of; rounds) "
          "| the host probe's 2-thread speed-up | meshdev's thread split, 2 threads |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|")
    for label in pairs:
        cells = [[], [], [], [], [], [], []]
        for rows, best in runs:
            by = {t: [r for r in rows if r["label"] == label and r["threads"] == t]
                  for t in ("1", "2")}
            if not by["1"] or not by["2"]:
                for c in cells:
                    c.append("–")
                continue
            q = {t: med([float(r["meshdev_qps"]) / 1e6 for r in by[t]]) for t in by}
            over = {t: [float(r["meshdev_over_embree"]) for r in by[t]] for t in by}
            hint = [float(r["meshdev_over_embree_hint"]) for r in by["2"]]
            cells[0].append(f"{q['1']:.2f} / {q['2']:.2f}")
            cells[1].append(span(over["1"]))
            cells[2].append(span(over["2"]))
            cells[3].append("–" if any(h != h for h in hint) else f"{med(hint):.2f}")
            speedup = f"{speedup_of(rows, label)[0]:.2f}"
            if best is not None:
                m = {r["threads"]: float(r["qps"]) for r in best
                     if r["label"] == label and r["engine"] == "meshdev"}
                if "1" in m and "2" in m:
                    speedup = f"{m['2'] / m['1']:.2f}; " + speedup
            cells[4].append(speedup)
            host = list(host_rounds(rows, label).values())
            cells[5].append(span(host) if host else "–")
            split = [float(r["thread_split"]) for r in by["2"] if r.get("thread_split")]
            cells[6].append(span(split) if split else "–")
        print(f"| {pair_name(label)} | " + " | ".join(" · ".join(c) for c in cells) + " |")
    print("\nMedians over each run's rounds (range); runs separated by \" · \". The rounds' "
          "speed-up: the median of each round's 2-thread over 1-thread throughput where the "
          "round ran both (files with `start_s`), else the ratio of the two medians. The host "
          "probe (files with `probe_s`): 16 chains of multiply-adds timed before each meshdev "
          "run, its 1-thread over 2-thread time in each round (2: two physical cores). The "
          "thread split (files with `thread_split`, since the fifty-first session): in each "
          "2-thread meshdev run, the samples one thread answered over the other's (1: both "
          "cores at one speed through the run).\n")


def build_lines(log_path, pair):
    """peer_compare's two build-against-query ratios on 2 threads for one pair of its log:
    (first build s, first query s, ratio), (best build s, best query s, ratio)."""
    first = best = None
    section = None
    for line in open(log_path):
        if line.startswith("-- "):
            section = line[3:].strip()
        if section != pair or "2 thread" not in line or "build" not in line:
            continue
        numbers = re.findall(r"([0-9.]+) s(?![a-z])", line)
        ratio = float(line.rsplit("=", 1)[1])
        if "first build" in line:
            first = (float(numbers[0]), float(numbers[1]), ratio)
        elif "best of" in line:
            best = (float(numbers[0]), float(numbers[1]), ratio)
    return first, best


def targets(rounds_path, peers_path, log_path, meshlab_paths):
    med = statistics.median
    rows = list(csv.DictReader(open(rounds_path)))
    best = list(csv.DictReader(open(peers_path)))

    def rounds_of(label, threads):
        return [r for r in rows if r["label"] == label and r["threads"] == threads]

    def verdict(ok):
        return "met" if ok else "**missed**"

    def full_host(label):
        """A note on the rounds whose host probe gave two physical cores (files with probe_s):
        their 2-thread median, beside the verdict on every round (which stays the verdict)."""
        host = host_rounds(rows, label)
        if not host:
            return ""
        full = [float(r["meshdev_qps"]) / 1e6 for r in rounds_of(label, "2")
                if host.get(r["round"], 0.0) >= kFullHost]
        text = f"; the host probe {min(host.values()):.2f}–{max(host.values()):.2f}×"
        if not full:
            return text + f", no round at {kFullHost}× or more"
        return text + (f"; in the {len(full)} of {len(host)} rounds where it gave {kFullHost}× "
                       f"or more, {med(full):.2f} M/s")

    samples = max((int(r["samples"]) for r in rows), default=0)
    print(f"| target (2 threads unless said) | measured (rounds' medians unless said; up to "
          f"{samples:,} samples, the targets' are 1M) | |")
    print("|---|---|---|")
    issue_pairs = ["pairs|torus100k->10k", "pairs|torus100k->1m", "pairs|torus1m->100k"]
    for label in issue_pairs:
        if not rounds_of(label, "2"):
            print(f"| ≥ 10 M samples/s on {pair_name(label)} | not in this run | – |")
            continue
        q = med([float(r["meshdev_qps"]) for r in rounds_of(label, "2")]) / 1e6
        print(f"| ≥ 10 M samples/s on {pair_name(label)} | {q:.2f} M/s{full_host(label)} "
              f"| {verdict(q >= 10)} |")
    for label in issue_pairs:
        if not rounds_of(label, "1") or not rounds_of(label, "2"):
            print(f"| ≥ 3× Embree on {pair_name(label)} | not in this run | – |")
            continue
        x2 = med([float(r["meshdev_over_embree"]) for r in rounds_of(label, "2")])
        x1 = med([float(r["meshdev_over_embree"]) for r in rounds_of(label, "1")])
        print(f"| ≥ 3× Embree on {pair_name(label)} | {x2:.2f}× (1 thread {x1:.2f}×) "
              f"| {verdict(x2 >= 3)} |")
    for path in meshlab_paths:
        for r in csv.DictReader(open(path)):
            ratio = float(r["ratio_xvfb"])
            print(f"| whole process ≥ 10× MeshLab (`xvfb-run`), {r['a']} ↔ {r['b']} "
                  f"({path.rsplit('/', 1)[-1]}) | {ratio:.2f}× (meshdev {float(r['meshdev_s']):.3f}"
                  f" s, MeshLab {float(r['meshlab_xvfb_s']):.2f} s; "
                  f"{int(r['samples_per_direction']):,} samples per direction) "
                  f"| {verdict(ratio >= 10)} |")
    sizes = [float(r["struct_bytes_per_face"]) for r in best if r["engine"] == "meshdev"]
    if sizes:
        print(f"| structure ≤ 64 bytes per face | {min(sizes):.1f}–{max(sizes):.1f} (every "
              f"target) | {verdict(max(sizes) <= 64)} |")
    speedups = []
    paired = True
    for label in labels_of(rows):
        found = speedup_of(rows, label)
        if found is None:
            continue
        speedups.append((found[0], pair_name(label)))
        paired = paired and found[1]
    if not speedups:
        print("| 2-thread speed-up ≥ 1.8× | not in this run | – |")
    else:
        below = [f"{name} {x:.2f}×" for x, name in sorted(speedups) if x < 1.8]
        met = len(speedups) - len(below)
        how = ("median of the rounds' own ratios" if paired
               else "ratio of the 1- and 2-thread medians")
        # Beside it, the host probe's speed-ups in the same rounds, and meshdev's own in the
        # rounds where the probe gave two physical cores (notes: the verdict is on every round).
        probes, full = [], []
        for label in labels_of(rows):
            host = host_rounds(rows, label)
            probes += host.values()
            q = by_round(rows, label, "meshdev_qps")
            full += [q["2"][k] / q["1"][k] for k, x in host.items()
                     if x >= kFullHost and k in q["1"] and k in q["2"]]
        if probes:
            how += (f"; the host probe {min(probes):.2f}–{max(probes):.2f}× in those rounds, "
                    f"{sum(x < kFullHost for x in probes)} of {len(probes)} below {kFullHost}×")
        if full:
            how += (f"; meshdev in the {len(full)} rounds at {kFullHost}× or more: median "
                    f"{med(full):.2f}×, {sum(x < 1.8 for x in full)} below 1.8×")
        # And how its two threads shared the samples of the rounds below 1.8× (files with a
        # thread_split column, since the fifty-first session): a split of kUneven or more says one
        # core ran slower than the other during that very run.
        slow = []
        if rows and "thread_split" in rows[0]:
            for label in labels_of(rows):
                q = by_round(rows, label, "meshdev_qps")
                split = by_round(rows, label, "thread_split")["2"]
                slow += [split[k] for k in q["2"] if k in q["1"] and q["2"][k] / q["1"][k] < 1.8]
        if slow:
            uneven = sum(x >= kUneven for x in slow)
            how += (f"; rounds below 1.8×: {len(slow)}, of which {uneven} had one thread "
                    f"answer {kUneven}× the other's samples or more")
        print(f"| 2-thread speed-up ≥ 1.8× | {min(speedups)[0]:.2f}–{max(speedups)[0]:.2f}× on "
              f"{len(speedups)} pairs ({how}) | " + (verdict(True) if not below else
                                              f"met on {met} of {len(speedups)}; below: "
                                              + ", ".join(below)) + " |")
    first, best_build = build_lines(log_path, "pairs|torus100k->1m")
    n = max((int(r["samples"]) for r in rounds_of("pairs|torus100k->1m", "2")), default=0)
    if first is None or best_build is None:
        print("| build of torus1m below the query of 1M samples | not in the log | – |")
    else:
        print(f"| build of torus1m below the query of 1M samples (here {n:,}) | first build "
              f"{first[0]:.3f} s "
              f"against the first query {first[1]:.3f} s ({first[2]:.0%}); best of the builds "
              f"{best_build[0]:.3f} s against the best query {best_build[1]:.3f} s "
              f"({best_build[2]:.0%}) | {verdict(first[2] < 1 and best_build[2] < 1)} |")


if __name__ == "__main__":
    if len(sys.argv) >= 5 and sys.argv[1] == "--targets":
        targets(sys.argv[2], sys.argv[3], sys.argv[4], sys.argv[5:])
        sys.exit(0)
    if len(sys.argv) >= 3 and sys.argv[1] == "--rounds":
        runs = []
        for arg in sys.argv[2:]:
            paths = arg.split(",")
            runs.append((list(csv.DictReader(open(paths[0]))),
                         list(csv.DictReader(open(paths[1]))) if len(paths) > 1 else None))
        rounds(runs)
        sys.exit(0)
    if len(sys.argv) not in (2, 3):
        sys.exit(__doc__)
    peers(sys.argv[1])
    if len(sys.argv) == 3:
        meshlab(sys.argv[2])
