#!/usr/bin/python3
"""Plots results/performance/peers.csv: query throughput (samples/s) against the faces of B and
against the number of samples, one line per engine and thread count. Debian's python3-matplotlib.
usage: plot_peers.py peers.csv peers.png [wall|cpu]
  wall (default): samples per wall-clock second of the query loop;
  cpu: samples per CPU-second actually consumed (the fairer view on a loaded machine)."""
import csv
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(path, png, metric="wall"):
    key = "qps" if metric == "wall" else "qps_per_cpu_s"
    rows = list(csv.DictReader(open(path)))
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.8))
    for ax, series, xkey, xlabel in (
        (axes[0], "faces", "b_faces", "faces of B (A = torus100k, 1M samples)"),
        (axes[1], "samples", "samples", "samples on A (torus100k -> 10k)"),
    ):
        lines = defaultdict(list)
        for r in rows:
            if r["label"].split("|")[0] != series:
                continue
            lines[(r["engine"], int(r["threads"]))].append(
                (int(r[xkey]), float(r[key]) / 1e6, float(r["cpu_share"])))
        for (engine, threads), pts in sorted(lines.items()):
            pts.sort()
            style = "-" if threads == 2 else "--"
            ax.plot([p[0] for p in pts], [p[1] for p in pts], style, marker="o",
                    label=f"{engine}, {threads} thr")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel(xlabel)
        ax.set_ylabel("M samples/s (query loop)" if metric == "wall"
                      else "M samples per CPU-second (query loop)")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    shares = [float(r["cpu_share"]) for r in rows]
    loads = [float(r["load_start"]) for r in rows if r["load_start"]]
    fig.suptitle("meshdev (full deviation unit) vs Embree 3 / CGAL closest point — "
                 f"CPU share {min(shares):.2f}-{max(shares):.2f}, load avg up to {max(loads):.1f}",
                 fontsize=10)
    fig.tight_layout()
    fig.savefig(png, dpi=110)
    print(f"wrote {png}")


if __name__ == "__main__":
    if len(sys.argv) not in (3, 4) or (len(sys.argv) == 4 and sys.argv[3] not in ("wall", "cpu")):
        sys.exit(__doc__)
    main(*sys.argv[1:])
