#!/usr/bin/env python3
"""Scaling plot and tables of bench/broadphase.

One panel per distribution: microseconds per step against N, log-log, one
line per broad phase (ours solid, Bullet's dashed, brute force dotted).
Prints, as Markdown, the tables of docs/broadphase.md: ms per step for each
distribution and N, each broad phase's speed-up over brute force at N =
10 000 uniform, and our best against Bullet's best at N >= 10 000.

Needs matplotlib (Debian: apt-get install python3-matplotlib, then run with
/usr/bin/python3).

Usage: plot.py broadphase.csv broadphase.png
"""
import csv
import sys
from collections import defaultdict

STYLE = {  # color, line style
    "brute_force": ("black", ":"),
    "sweep_and_prune": ("tab:blue", "-"),
    "spatial_hash": ("tab:green", "-"),
    "dynamic_bvh": ("tab:red", "-"),
    "octree": ("tab:purple", "-"),
    "bullet_dbvt": ("tab:orange", "--"),
    "bullet_axis_sweep": ("tab:brown", "--"),
}
DISTRIBUTIONS = ["uniform", "clustered", "falling_pile"]


def read(csv_path):
    """({(algorithm, distribution): {n: us_per_step}}, {(distribution, n, algorithm): pairs},
    the algorithms present in STYLE's order)."""
    us = defaultdict(dict)  # (algorithm, distribution) -> {n: us_per_step}
    pairs = {}
    with open(csv_path, newline="") as f:
        for row in csv.DictReader(f):
            key = (row["algorithm"], row["distribution"])
            us[key][int(row["n"])] = float(row["us_per_step"])
            pairs[(row["distribution"], int(row["n"]), row["algorithm"])] = int(row["pairs"])
    algorithms = [a for a in STYLE if any(k[0] == a for k in us)]
    return us, pairs, algorithms


def plot(us, algorithms, png_path):
    import matplotlib  # here, so that the tables need no matplotlib (tools/bench_docs.py)

    matplotlib.use("Agg")  # files only: no display on a build machine
    import matplotlib.pyplot as plt  # after choosing the backend

    fig, axes = plt.subplots(1, len(DISTRIBUTIONS), figsize=(15, 4.6), sharey=True)
    for ax, d in zip(axes, DISTRIBUTIONS):
        for a in algorithms:
            points = sorted(us.get((a, d), {}).items())
            if not points:
                continue
            color, style = STYLE[a]
            ax.loglog([n for n, _ in points], [t for _, t in points], style, color=color, marker="o", label=a)
        ax.set_title(d.replace("_", " "))
        ax.set_xlabel("moving boxes N")
        ax.grid(True, which="both", alpha=0.3)
    axes[0].set_ylabel("µs per step (move + update), median of 3")
    axes[-1].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(png_path, dpi=110)


def distribution_table(us, pairs, algorithms, d):
    """Lines of the table of distribution d: ms per step for each N and broad phase."""
    sizes = sorted({n for series in us.values() for n in series})
    present = [a for a in algorithms if (a, d) in us]
    lines = ["| N | " + " | ".join(present) + " | exact pairs |",
             "| ---: | " + " | ".join("---:" for _ in present) + " | ---: |"]
    for n in sizes:
        cells = [f"{us[(a, d)][n] / 1000:.3g}" if n in us[(a, d)] else "–" for a in present]
        exact = pairs.get((d, n, "sweep_and_prune"), "")
        lines.append(f"| {n} | " + " | ".join(cells) + f" | {exact} |")
    return lines


def speedup_list(us, algorithms):
    """Lines of the list of speed-ups over brute force at N = 10 000 uniform; None without brute force."""
    brute = us.get(("brute_force", "uniform"), {}).get(10000)
    if not brute:
        return None
    lines = []
    for a in algorithms:
        t = us.get((a, "uniform"), {}).get(10000)
        if t and a != "brute_force":
            lines.append(f"- {a}: {brute / t:.0f}×")
    return lines


def versus_bullet_table(us, algorithms):
    """Lines of the table of our best against Bullet's best at N >= 10 000."""
    sizes = sorted({n for series in us.values() for n in series})
    lines = ["| distribution | N | our best | Bullet's best | ratio |",
             "| --- | ---: | --- | --- | ---: |"]
    for d in DISTRIBUTIONS:
        for n in sizes:
            if n < 10000:
                continue
            ours = [(us[(a, d)][n], a) for a in algorithms
                    if not a.startswith("bullet") and a != "brute_force" and n in us.get((a, d), {})]
            theirs = [(us[(a, d)][n], a) for a in algorithms if a.startswith("bullet") and n in us.get((a, d), {})]
            if ours and theirs:
                o, t = min(ours), min(theirs)
                lines.append(f"| {d} | {n} | {o[1]} {o[0] / 1000:.3g} ms | {t[1]} {t[0] / 1000:.3g} ms "
                             f"| {o[0] / t[0]:.2f} |")
    return lines


def main(csv_path, png_path):
    us, pairs, algorithms = read(csv_path)
    plot(us, algorithms, png_path)

    for d in DISTRIBUTIONS:
        print(f"\n**{d.replace('_', ' ')}** (ms per step; pairs as reported at the end)\n")
        print("\n".join(distribution_table(us, pairs, algorithms, d)))

    speedups = speedup_list(us, algorithms)
    if speedups is not None:
        print("\n**speed-up over brute force, N = 10 000 uniform**\n")
        print("\n".join(speedups))

    print("\n**our best against Bullet's best, N >= 10 000** (ratio < 1: ours is faster)\n")
    print("\n".join(versus_bullet_table(us, algorithms)))


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
