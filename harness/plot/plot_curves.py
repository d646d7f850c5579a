#!/usr/bin/python3
"""Fig. 8-style curves from a meshdev results CSV (meshdev sweep), drawn with matplotlib.

For every mesh and measure: the mean symmetric deviation (paper §3.3: the average of the two
directions' means) against the reduction ratio, one line per simplifier (with its options).
Also one two-panel figure per mesh, "(a) geometric deviation" and "(b) normal deviation", like the
paper's Fig. 8. Run by `meshdev plot` with Debian's /usr/bin/python3 (package python3-matplotlib).

Usage: plot_curves.py CSV --out DIR [--statistic symmetric_mean] [--relative] [--log]
                      [--measures geometry,normal] [--formats png,svg,pdf] [--x ratio|faces]
Exit codes: 0 ok, 2 usage, 3 unreadable CSV, 4 nothing to plot, 5 a plot not written.
"""
import argparse
import csv
import math
import os
import sys

OK_STATUSES = ("ok", "target-not-reached")


def die(code, message):
    print("meshdev plot: error: " + message, file=sys.stderr)
    sys.exit(code)


def read_rows(path):
    try:
        with open(path, newline="", encoding="utf-8") as f:
            text = f.read()
    except OSError as e:
        die(3, "%s: %s" % (path, e.strerror))
    except UnicodeDecodeError as e:  # was a traceback (exit 70)
        die(3, "%s: not a meshdev results CSV (not UTF-8 text: byte %d)" % (path, e.start))
    # A torn last line (an interrupted sweep) is ignored, as meshdev itself does.
    if text and not text.endswith("\n"):
        text = text[: text.rfind("\n") + 1]
    try:
        rows = list(csv.DictReader(text.splitlines()))
    except csv.Error as e:  # e.g. a NUL byte
        die(3, "%s: not a meshdev results CSV (%s)" % (path, e))
    if rows and "symmetric_mean" not in rows[0]:
        die(3, "%s: not a meshdev results CSV (no symmetric_mean column)" % path)
    return rows


def number(text):
    try:
        v = float(text)
    except (TypeError, ValueError):
        return None
    return v if math.isfinite(v) else None


def label_of(row):
    return row["simplifier"] + (" [" + row["options"] + "]" if row["options"] else "")


def series(rows, mesh, measure, column, xmode):
    """{simplifier label: sorted [(x, y, reached)]} for one mesh and measure."""
    out = {}
    for r in rows:
        if r["mesh"] != mesh or r["measure"] != measure or r["status"] not in OK_STATUSES:
            continue
        y = number(r.get(column))
        if y is None:
            continue
        if xmode == "faces":
            x = number(r["reached_faces"])
        else:
            x = number(r["reduction_percent"])
        if x is None:
            continue
        out.setdefault(label_of(r), []).append((x, y, r["status"] == "ok"))
    for v in out.values():
        v.sort()
    return out


PRETTY = {"geometry": "geometric deviation", "normal": "normal deviation",
          "normal_angle": "normal angle deviation", "color": "colour deviation",
          "color_de76": "colour deviation (ΔE76)", "texcoord": "texture coordinate deviation"}
STAT = {"symmetric_mean": "mean symmetric", "symmetric_rms": "RMS symmetric",
        "symmetric_max": "max symmetric (average of the two maxima)",
        "symmetric_p95": "p95 symmetric", "hausdorff": "Hausdorff (max of both directions)",
        "forward_mean": "mean forward (input → simplified)",
        "backward_mean": "mean backward (simplified → input)"}


def draw(ax, data, measure, unit, args, styles):
    for label in sorted(data):
        pts = data[label]
        xs = [p[0] for p in pts]
        ys = [p[1] for p in pts]
        color, marker = styles[label]
        ax.plot(xs, ys, marker=marker, color=color, label=label, linewidth=1.5, markersize=5)
        # Target not reached: hollow marker on that point.
        miss = [p for p in pts if not p[2]]
        if miss:
            ax.plot([p[0] for p in miss], [p[1] for p in miss], linestyle="none", marker="o",
                    markersize=10, markerfacecolor="none", markeredgecolor=color)
    ax.set_xlabel("faces reached" if args.x == "faces" else "reduction (% of faces removed)")
    ylab = STAT.get(args.statistic, args.statistic) + " " + PRETTY.get(measure, measure + " deviation")
    if args.relative and measure == "geometry":
        ylab += " (fraction of bbox diagonal)"
    elif unit:
        ylab += " (" + unit + ")"
    ax.set_ylabel(ylab, fontsize=8)
    if args.log:
        ax.set_yscale("log")
    if args.x == "faces":
        ax.set_xscale("log")
        ax.invert_xaxis()
    ax.grid(True, which="both", alpha=0.3)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("csv")
    p.add_argument("--out", required=True)
    p.add_argument("--statistic", default="symmetric_mean")
    p.add_argument("--relative", action="store_true", help="geometry in fractions of the bbox diagonal")
    p.add_argument("--log", action="store_true", help="logarithmic y axis")
    p.add_argument("--measures", default="", help="comma-separated; default: every measure")
    p.add_argument("--formats", default="png,svg,pdf")
    p.add_argument("--x", choices=("ratio", "faces"), default="ratio")
    args = p.parse_args()

    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        die(4, "matplotlib is missing: apt-get install python3-matplotlib")
    matplotlib.rcParams["svg.hashsalt"] = "meshdev"  # reproducible SVG ids

    rows = read_rows(args.csv)
    ok_rows = [r for r in rows if r["status"] in OK_STATUSES and r["measure"]]
    if not ok_rows:
        die(4, "%s: no successful rows to plot" % args.csv)
    measures = [m for m in args.measures.split(",") if m] or \
        sorted({r["measure"] for r in ok_rows}, key=lambda m: (m != "geometry", m != "normal", m))
    meshes = sorted({r["mesh"] for r in ok_rows})
    labels = sorted({label_of(r) for r in ok_rows})
    cmap = plt.get_cmap("tab10")
    markers = "osD^v<>ph*"
    styles = {l: (cmap(i % 10), markers[i % len(markers)]) for i, l in enumerate(labels)}
    units = {r["measure"]: r["unit"] for r in ok_rows}
    # Formats and the output folder are checked before any figure is drawn (an unknown format
    # and a folder under a file were tracebacks, exit 70, after the work).
    supported = plt.figure().canvas.get_supported_filetypes()
    plt.close("all")
    formats = [f for f in args.formats.split(",") if f]
    unknown = [f for f in formats if f not in supported]
    if unknown or not formats:
        die(2, "--formats: %s not supported; choose from %s"
            % (",".join(unknown) or "none given", ", ".join(sorted(supported))))
    try:
        os.makedirs(args.out, exist_ok=True)
    except OSError as e:
        die(5, "%s: cannot create the folder (%s)" % (args.out, e.strerror))
    written = []

    def save(fig, stem):
        for fmt in formats:
            path = os.path.join(args.out, stem + "." + fmt)
            meta = {"svg": {"Date": None}, "pdf": {"CreationDate": None}}.get(fmt, {})
            try:
                fig.savefig(path + ".tmp." + fmt, format=fmt, dpi=150, bbox_inches="tight",
                            metadata=meta)
                os.replace(path + ".tmp." + fmt, path)  # complete or absent
            except OSError as e:  # a full disk, a folder removed meanwhile
                if os.path.exists(path + ".tmp." + fmt):
                    os.remove(path + ".tmp." + fmt)
                die(5, "%s: cannot write (%s)" % (path, e.strerror))
            written.append(path)
        plt.close(fig)

    def column(measure):
        if args.relative and measure == "geometry":
            return args.statistic + "_rel"
        return args.statistic

    for mesh in meshes:
        stem = os.path.splitext(os.path.basename(mesh))[0]
        for measure in measures:
            data = series(rows, mesh, measure, column(measure), args.x)
            if not data:
                continue
            fig, ax = plt.subplots(figsize=(6.4, 4.4))
            draw(ax, data, measure, units.get(measure, ""), args, styles)
            ax.set_title("%s: %s" % (os.path.basename(mesh), PRETTY.get(measure, measure)), fontsize=10)
            ax.legend(fontsize=7)
            save(fig, "%s_%s" % (stem, measure))
        panels = [m for m in ("geometry", "normal") if series(rows, mesh, m, column(m), args.x)]
        if len(panels) == 2:
            fig, axes = plt.subplots(1, 2, figsize=(12, 4.6))
            for ax, m, tag in zip(axes, panels, ("(a) Geometric deviation", "(b) Normal deviation")):
                draw(ax, series(rows, mesh, m, column(m), args.x), m, units.get(m, ""), args, styles)
                ax.set_title(tag, fontsize=10)
            axes[0].legend(fontsize=7)
            fig.suptitle("%s — comparison between mesh simplification algorithms (cf. paper Fig. 8)"
                         % os.path.basename(mesh), fontsize=10)
            save(fig, "%s_fig8" % stem)
    if not written:
        die(4, "nothing to plot for measures %s" % ",".join(measures))
    for w in written:
        print(w)


if __name__ == "__main__":
    main()
