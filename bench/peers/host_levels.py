#!/usr/bin/python3
"""The host's two speeds, from the interleaved rounds of one or more run_all.sh runs.
usage: host_levels.py ROUNDS.csv [ROUNDS2.csv ...]
Per pair (label "pairs|..."), meshdev's 1-thread rounds split in two by a two-means fit (the cut
starts halfway between the least and the greatest rate and moves to the mean of the two groups'
means until it stays): each group's count, range and median, the slow median over the fast
one, and the cut. Then how many rounds (a round: one run's round number) hold both levels among their pairs,
only the fast one, or only the slow one; and per pair the 2-thread rounds: how many reached
10 M samples/s (issue 3's target), the greatest and the median. docs/performance.md, "Where the
targets stand"."""
import csv
import statistics
import sys
from collections import OrderedDict


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


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    main(sys.argv[1:])
