#!/usr/bin/env python3
"""Plot of speed_vs_error's CSV: error at the end time against cost.

One panel per problem; one line per integrator, solid for double and dashed
for float, one marker per time step h. The x axis is the cost of reaching
t_end, ns per particle-step × steps: a method's cost per step does not depend
on h, so against the per-step cost alone each method would be a vertical
line, and which method is cheapest for a given error could not be read.

Also prints, as Markdown, the tables of docs/speed_vs_error.md: the cost per
step relative to euler, and the largest h (and its cost) that reaches an
error of 1e-3 and 1e-6.

Needs matplotlib (Debian: apt-get install python3-matplotlib, then run with
/usr/bin/python3).

Usage: plot.py speed_vs_error.csv speed_vs_error.png
"""
import csv
import statistics
import sys
from collections import defaultdict

PROBLEMS = {
    "oscillator": "harmonic oscillator  x'' = -4x",
    "projectile_drag": "projectile with linear drag  v' = g - 0.7v",
    "orbit": "circular orbit  μ = 4, r = 2",
    "orbit_estimate": "the orbit, |x|⁻³ from the 1/√ estimate",
}
INTEGRATORS = {  # color, stages
    "euler": ("tab:red", 1),
    "symplectic_euler": ("tab:purple", 1),
    "midpoint": ("tab:green", 2),
    "rk4": ("tab:blue", 4),
}
SCALARS = {"double": "-", "float": "--"}
THRESHOLDS = (1e-3, 1e-6)
T_END = 2.0


def read(path):
    """{(problem, integrator, scalar): [row, ...]} sorted by decreasing dt."""
    series = defaultdict(list)
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            row["dt"] = float(row["dt"])
            row["steps"] = int(row["steps"])
            row["error"] = float(row["error"])
            row["ns"] = float(row["ns_per_particle_step"])
            series[(row["problem"], row["integrator"], row["scalar"])].append(row)
    for rows in series.values():
        rows.sort(key=lambda r: -r["dt"])
    return series


def plot(series, out):
    import matplotlib  # here, so that the tables need no matplotlib (tools/bench_docs.py)

    matplotlib.use("Agg")  # files only: no display on a build machine
    import matplotlib.pyplot as plt  # after choosing the backend
    from matplotlib.lines import Line2D

    fig, axes = plt.subplots(1, len(PROBLEMS), figsize=(22, 6), sharey=True)
    for ax, (problem, title) in zip(axes, PROBLEMS.items()):
        for integrator, (color, _) in INTEGRATORS.items():
            for scalar, style in SCALARS.items():
                rows = [r for r in series.get((problem, integrator, scalar), [])
                        if r["error"] > 0 and r["error"] < float("inf")]
                if not rows:
                    continue
                ax.plot([r["ns"] * r["steps"] for r in rows], [r["error"] for r in rows],
                        style, color=color, marker="o" if scalar == "double" else "s",
                        markersize=3.5, linewidth=1.4,
                        markerfacecolor=color if scalar == "double" else "white")
        for threshold in THRESHOLDS:
            ax.axhline(threshold, color="0.6", linewidth=0.8, linestyle=":")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_title(title, fontsize=11)
        ax.set_xlabel("cost to reach t = 2 s: ns per particle\n(= ns per particle-step × steps)")
        ax.grid(True, which="major", color="0.9", linewidth=0.6)
    axes[0].set_ylabel("|x(2 s) − exact|")
    handles = [Line2D([], [], color=c, linewidth=2, label=name) for name, (c, _) in INTEGRATORS.items()]
    handles += [Line2D([], [], color="0.3", linestyle="-", marker="o", markersize=4, label="double"),
                Line2D([], [], color="0.3", linestyle="--", marker="s", markersize=4,
                       markerfacecolor="white", label="float")]
    dts = sorted({r["dt"] for rows in series.values() for r in rows}, reverse=True)
    fig.legend(handles=handles, loc="lower center", ncol=len(handles), frameon=False,
               title=f"one marker per time step h = {dts[0]:g} s … {dts[-1]:.3g} s, halving "
                     "(left to right); dotted: error 1e-3 and 1e-6")
    fig.suptitle("impulse integrators: error at the end time against cost "
                 "(N = 4096 particles, median of 7 runs)", fontsize=13)
    fig.tight_layout(rect=(0, 0.1, 1, 0.96))
    fig.savefig(out, dpi=110)


def per_step_cost(series):
    """Median over all h of ns per particle-step: the cost does not depend on h."""
    return {key: statistics.median(r["ns"] for r in rows) for key, rows in series.items()}


def tables(series):
    cost = per_step_cost(series)
    print("Cost per particle-step (median over all h of the medians of 7 runs), ns; "
          "in brackets: relative to euler, and per stage relative to euler\n")
    print("| problem | scalar | " + " | ".join(INTEGRATORS) + " |")
    print("| --- | --- |" + " ---: |" * len(INTEGRATORS))
    for problem in PROBLEMS:
        for scalar in SCALARS:
            base = cost.get((problem, "euler", scalar))
            cells = []
            for integrator, (_, stages) in INTEGRATORS.items():
                c = cost.get((problem, integrator, scalar))
                cells.append("" if c is None else
                             f"{c:.2f} ({c / base:.2f}×, {c / base / stages:.2f}×)")
            print(f"| {problem} | {scalar} | " + " | ".join(cells) + " |")

    for threshold in THRESHOLDS:
        print(f"\nLargest h reaching error ≤ {threshold:g}: h in s (steps to 2 s; "
              "cost to 2 s in ns per particle = median ns per step × steps)\n")
        print("| problem | scalar | " + " | ".join(INTEGRATORS) + " |")
        print("| --- | --- |" + " --- |" * len(INTEGRATORS))
        for problem in PROBLEMS:
            for scalar in SCALARS:
                cells = []
                for integrator in INTEGRATORS:
                    key = (problem, integrator, scalar)
                    hits = [r for r in series.get(key, []) if r["error"] <= threshold]
                    if not hits:
                        best = min(series.get(key, []), key=lambda r: r["error"], default=None)
                        cells.append("not reached" if best is None else
                                     f"not reached (best {best['error']:.1e})")
                        continue
                    r = hits[0]  # rows run from the largest h down
                    cells.append(f"{r['dt']:.3g} ({r['steps']}; {cost[key] * r['steps']:.3g})")
                print(f"| {problem} | {scalar} | " + " | ".join(cells) + " |")


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    series = read(sys.argv[1])
    plot(series, sys.argv[2])
    tables(series)


if __name__ == "__main__":
    main()
