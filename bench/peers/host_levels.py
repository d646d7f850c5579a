#!/usr/bin/python3
"""The host's two speeds, from the interleaved rounds of one or more run_all.sh runs.
usage: host_levels.py ROUNDS.csv [ROUNDS2.csv ...]
Per pair (label "pairs|..."), meshdev's 1-thread rounds split in two by a two-means fit (the cut
starts halfway between the least and the greatest rate and moves to the mean of the two groups'
means until it stays): each group's count, range and median, the slow median over the fast
one, and the cut. Then how many rounds (a round: one run's round number) hold both levels among their pairs,
only the fast one, or only the slow one; and per pair the 2-thread rounds: how many reached
10 M samples/s (issue 3's target), the greatest and the median. Last, over every pair's rounds:
how many 2-thread rounds gained less than 1.8x over the same round's 1-thread run, for meshdev
and for Embree (timed right after it), and how many runs fell more than 10 % below their pair's
and run's median; and, for files with meshdev's thread split (since the fifty-first session),
the 2-thread rounds split below table_md.kUneven and at or above it: their speed-ups, those
below 1.8x, the host probe before those and Embree's speed-up in them. docs/performance.md,
"Where the targets stand"."""
import csv
import statistics
import sys
from collections import OrderedDict

from table_md import kUneven


def two_means(values):
    """The cut between the two groups of `values` (at least two distinct values)."""
    cut = (min(values) + max(values)) / 2
    while True:
        low = [v for v in values if v < cut]
        high = [v for v in values if v >= cut]
        moved = (statistics.mean(low) + statistics.mean(high)) / 2
        if moved == cut:
            return cut
        cut = moved


def main(paths):
    one = OrderedDict()  # pair -> [(run, round, M/s)] on 1 thread
    two = OrderedDict()  # pair -> [M/s] on 2 threads
    for path in paths:
        for row in csv.DictReader(open(path)):
            if not row["label"].startswith("pairs|"):
                continue
            pair = row["label"].split("|", 1)[1]
            rate = float(row["meshdev_qps"]) / 1e6
            if row["threads"] == "1":
                one.setdefault(pair, []).append((path, row["round"], rate))
            elif row["threads"] == "2":
                two.setdefault(pair, []).append(rate)
    fast_in = {}  # (run, round) -> the levels of its pairs
    print("| pair | 1-thread rounds: fast | slow | slow ÷ fast (medians) | cut, M/s |")
    print("|---|---|---|---:|---:|")
    for pair, rounds in one.items():
        rates = [r for _, _, r in rounds]
        if len(set(rates)) < 2:
            continue
        cut = two_means(rates)
        fast = [r for r in rates if r >= cut]
        slow = [r for r in rates if r < cut]
        print(f"| {pair} | {len(fast)} at {min(fast):.2f}–{max(fast):.2f} "
              f"(median {statistics.median(fast):.2f}) | {len(slow)} at "
              f"{min(slow):.2f}–{max(slow):.2f} (median {statistics.median(slow):.2f}) "
              f"| {statistics.median(slow) / statistics.median(fast):.2f} | {cut:.2f} |")
        for run, number, rate in rounds:
            fast_in.setdefault((run, number), set()).add(rate >= cut)
    both = sum(1 for levels in fast_in.values() if len(levels) == 2)
    only_fast = sum(1 for levels in fast_in.values() if levels == {True})
    only_slow = sum(1 for levels in fast_in.values() if levels == {False})
    print(f"\n{len(fast_in)} rounds: {both} with both levels among their pairs, {only_fast} with "
          f"only the fast one, {only_slow} with only the slow one\n")
    print("| pair | 2-thread rounds | at 10 M/s or more | greatest | median |")
    print("|---|---:|---:|---:|---:|")
    for pair, rates in two.items():
        print(f"| {pair} | {len(rates)} | {sum(r >= 10 for r in rates)} | {max(rates):.2f} "
              f"| {statistics.median(rates):.2f} |")
    speedups(paths)


def speedups(paths):
    """The 2-thread rounds' own speed-ups, meshdev's beside Embree's, and by meshdev's split."""
    med = statistics.median
    rounds = []  # one dict per (run, pair, round) that ran both thread counts
    runs = OrderedDict()  # (run, pair, threads) -> [(meshdev M/s, Embree M/s)]
    for path in paths:
        by = {}
        for row in csv.DictReader(open(path)):
            if row["label"].startswith("pairs|"):
                by[(row["label"], row["round"], row["threads"])] = row
                runs.setdefault((path, row["label"], row["threads"]), []).append(
                    (float(row["meshdev_qps"]), float(row["embree_qps"])))
        for (label, number, threads), row in by.items():
            one = by.get((label, number, "1"))
            if threads != "2" or one is None:
                continue
            rounds.append({
                "meshdev": float(row["meshdev_qps"]) / float(one["meshdev_qps"]),
                "embree": float(row["embree_qps"]) / float(one["embree_qps"]),
                "probe": (float(one["probe_s"]) / float(row["probe_s"])
                          if row.get("probe_s") else None),
                "split": float(row["thread_split"]) if row.get("thread_split") else None})
    if not rounds:
        return
    print(f"\n{len(rounds)} rounds on 2 threads: speed-up below 1.8x in "
          f"{sum(r['meshdev'] < 1.8 for r in rounds)} for meshdev, "
          f"{sum(r['embree'] < 1.8 for r in rounds)} for Embree")
    slow = {"meshdev": [0, 0], "embree": [0, 0]}  # runs > 10 % below median: [1 thread, 2]
    for (_, _, threads), rates in runs.items():
        for k, engine in enumerate(slow):
            m = med([r[k] for r in rates])
            slow[engine][threads == "2"] += sum(r[k] < 0.9 * m for r in rates)
    total = [sum(len(v) for (_, _, t), v in runs.items() if t == t_) for t_ in ("1", "2")]
    print(f"runs more than 10 % below their pair's median in their run, 1 / 2 threads (of "
          f"{total[0]} / {total[1]}): meshdev {slow['meshdev'][0]} / {slow['meshdev'][1]}, "
          f"Embree {slow['embree'][0]} / {slow['embree'][1]}")
    split = [r for r in rounds if r["split"] is not None]
    for name, group in ((f"split below {kUneven}", [r for r in split if r["split"] < kUneven]),
                        (f"split {kUneven} or more", [r for r in split if r["split"] >= kUneven])):
        if not group:
            continue
        gains = [r["meshdev"] for r in group]
        below = [r for r in group if r["meshdev"] < 1.8]
        line = (f"{name}: {len(group)} rounds, splits {min(r['split'] for r in group):.2f}–"
                f"{max(r['split'] for r in group):.2f}, speed-up {min(gains):.2f}–"
                f"{max(gains):.2f} (median {med(gains):.2f}), {len(below)} below 1.8x")
        probes = [r["probe"] for r in below if r["probe"] is not None]
        if probes:
            line += f"; in those, the host probe {min(probes):.2f}–{max(probes):.2f}x"
        if below:
            line += (f"; Embree in them {min(r['embree'] for r in below):.2f}–"
                     f"{max(r['embree'] for r in below):.2f}x")
        print(line)


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    main(sys.argv[1:])
