#!/usr/bin/env python3
"""Plot and tables of the rigid_motion benchmarks.

The figure is rigid_motion_speed_vs_error's CSV: error after 10 s of free
rotation against the cost of getting there, in two panels (the spinning
body's relative energy error, the symmetric top's orientation error in rad).
One line per integrator, solid for double and dashed for float, one marker
per time step. The x axis is ns per body-step × steps: a method's cost per
step does not depend on the step, so against the per-step cost alone each
method would be a vertical line.

Also prints, as Markdown, the tables of docs/rigid_motion.md: body-steps per
second on the two scenes of rigid_motion's CSV, the cost per step of free
rotation, the largest step (and its cost) reaching an error of 1e-6, and the
smallest error each method reaches (float's floor).

Needs matplotlib (Debian: apt-get install python3-matplotlib, then run with
/usr/bin/python3).

Usage: plot.py rigid_motion.csv rigid_motion_speed_vs_error.csv rigid_motion.png
"""
import csv
import statistics
import sys
from collections import defaultdict

INTEGRATORS = {  # color, marker, stages
    "euler": ("tab:red", "o", 1),
    "symplectic_euler": ("tab:purple", "x", 1),
    "midpoint": ("tab:green", "o", 2),
    "rk4": ("tab:blue", "o", 4),
}
BASE = "symplectic_euler"
SCALARS = {"double": "-", "float": "--"}
ERRORS = {  # column: panel title, axis label
    "energy_error": ("spinning body: moments 1, 2, 3; ω = (0.01, 2, 0.01) rad/s",
                     "|E(10 s) − E(0)| / E(0)"),
    "orientation_error": ("symmetric top: I⊥ = 1, I₃ = 1.8; closed-form motion",
                          "orientation error at 10 s, rad"),
}
THRESHOLD = 1e-6


def read_throughput(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def read_errors(path):
    """{(integrator, scalar): [row, ...]} sorted by decreasing dt."""
    series = defaultdict(list)
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            for column in ("dt", "ns_per_body_step", *ERRORS):
                row[column] = float(row[column])
            row["steps"] = int(row["steps"])
            series[(row["integrator"], row["scalar"])].append(row)
    for rows in series.values():
        rows.sort(key=lambda r: -r["dt"])
    return series


def plot(series, out):
    import matplotlib  # here, so that the tables need no matplotlib (tools/bench_docs.py)

    matplotlib.use("Agg")  # files only: no display on a build machine
    import matplotlib.pyplot as plt  # after choosing the backend
    from matplotlib.lines import Line2D

    fig, axes = plt.subplots(1, len(ERRORS), figsize=(14, 6.2))
    for ax, (column, (title, label)) in zip(axes, ERRORS.items()):
        for integrator, (color, marker, _) in INTEGRATORS.items():
            for scalar, style in SCALARS.items():
                rows = [r for r in series.get((integrator, scalar), []) if 0 < r[column] < float("inf")]
                ax.plot([r["ns_per_body_step"] * r["steps"] for r in rows], [r[column] for r in rows],
                        style, color=color, marker=marker, markersize=4, linewidth=1.4,
                        markerfacecolor=color if scalar == "double" else "white")
        ax.axhline(THRESHOLD, color="0.6", linewidth=0.8, linestyle=":")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_title(title, fontsize=11)
        ax.set_ylabel(label)
        ax.set_xlabel("cost to reach t = 10 s: ns per body\n(= ns per body-step × steps)")
        ax.grid(True, which="major", color="0.9", linewidth=0.6)
    handles = [Line2D([], [], color=c, marker=m, linewidth=2, label=name)
               for name, (c, m, _) in INTEGRATORS.items()]
    handles += [Line2D([], [], color="0.3", linestyle="-", label="double"),
                Line2D([], [], color="0.3", linestyle="--", label="float")]
    dts = sorted({r["dt"] for rows in series.values() for r in rows}, reverse=True)
    fig.legend(handles=handles, loc="lower center", ncol=len(handles), frameon=False,
               title=f"one marker per time step, 1/{1 / dts[0]:.0f} s … 1/{1 / dts[-1]:.0f} s, halving "
                     "(left to right); without torque euler and symplectic_euler are the same method; "
                     f"dotted: {THRESHOLD:g}")
    fig.suptitle("impulse rigid bodies: error after 10 s of free rotation against cost "
                 "(1024 bodies, median of 7 runs)", fontsize=13)
    fig.tight_layout(rect=(0, 0.1, 1, 0.96))
    fig.savefig(out, dpi=110)


def markdown_lines(header, rows, labels=1, align="---:"):
    """The lines of a Markdown table; the first `labels` columns are left-aligned."""
    return (["| " + " | ".join(header) + " |",
             "|" + " --- |" * labels + f" {align} |" * (len(header) - labels)]
            + ["| " + " | ".join(row) + " |" for row in rows])


def markdown_table(header, rows, labels=1, align="---:"):
    """Prints a Markdown table; the first `labels` columns are left-aligned."""
    print("\n".join(markdown_lines(header, rows, labels, align)))


def throughput_columns(rows):
    """The (scalar, N) columns of the throughput tables, their header, and the rows by key."""
    sizes = sorted({int(r["bodies"]) for r in rows})
    columns = [(scalar, n) for scalar in ("float", "double") for n in sizes]
    header = ["integrator"] + [f"{s} N = {n:,}".replace(",", " ") for s, n in columns]
    cell = {(r["scene"], r["integrator"], r["scalar"], int(r["bodies"])): r for r in rows}
    return columns, header, cell


def throughput_table(rows, scene):
    """Lines of the table of one scene: M body-steps/s and the cost relative to BASE."""
    columns, header, cell = throughput_columns(rows)

    def throughput(integrator, scalar, n):
        r = cell.get((scene, integrator, scalar, n))
        return "–" if r is None else f"{float(r['mbody_steps_per_s']):.2f} ({float(r['cost_vs_symplectic_euler']):.2f}×)"

    return markdown_lines(header, [[i] + [throughput(i, s, n) for s, n in columns] for i in INTEGRATORS])


def coupled_over_independent_table(rows):
    """Lines of the table of the coupled scene's time per body-step over the independent one's."""
    columns, header, cell = throughput_columns(rows)

    def coupled_over_independent(integrator, scalar, n):
        r = cell.get(("coupled", integrator, scalar, n))
        return "–" if r is None else f"{float(r['cost_vs_independent']):.2f}×"

    return markdown_lines(header, [[i] + [coupled_over_independent(i, s, n) for s, n in columns] for i in INTEGRATORS])


def throughput_tables(rows):
    for scene in dict.fromkeys(r["scene"] for r in rows):
        print(f"\n**{scene}**: M body-steps/s (median of 7 runs); in brackets, the time per step "
              f"relative to {BASE} in the same repeats (median of 7 ratios)\n")
        print("\n".join(throughput_table(rows, scene)))
    print("\nTime per body-step on the coupled scene relative to the independent one, same integrator "
          "(median of 7 ratios within a repeat)\n")
    print("\n".join(coupled_over_independent_table(rows)))


def cost_table(series):
    """Lines of the table of free rotation's cost per body-step, per scalar and integrator."""
    by_dt = {(key, r["dt"]): r["ns_per_body_step"] for key, rows in series.items() for r in rows}
    cost = {key: statistics.median(r["ns_per_body_step"] for r in rows) for key, rows in series.items()}

    def per_step(integrator, scalar):
        key = (integrator, scalar)
        ratio = statistics.median(by_dt[(key, r["dt"])] / by_dt[((BASE, scalar), r["dt"])] for r in series[key])
        return f"{cost[key]:.0f} ({ratio:.2f}×)"

    return markdown_lines(["scalar", *INTEGRATORS], [[s] + [per_step(i, s) for i in INTEGRATORS] for s in SCALARS])


def error_tables(series):
    cost = {key: statistics.median(r["ns_per_body_step"] for r in rows) for key, rows in series.items()}

    def largest_step(column, integrator, scalar):
        key = (integrator, scalar)
        hits = [r for r in series[key] if r[column] <= THRESHOLD]
        if not hits:
            return f"not reached (best {min(r[column] for r in series[key]):.1e})"
        r = hits[0]  # rows run from the largest dt down
        return f"1/{1 / r['dt']:.0f} ({r['steps']}; {cost[key] * r['steps'] / 1e3:.3g})"

    def smallest_error(column, integrator, scalar):
        best = min(series[(integrator, scalar)], key=lambda r: r[column])
        return f"{best[column]:.1e} at 1/{1 / best['dt']:.0f}"

    print("\nFree rotation, cost per body-step: ns (median over the time steps of the medians of 7 runs); "
          f"in brackets, relative to {BASE} (median over the time steps of the ratio at each)\n")
    print("\n".join(cost_table(series)))
    for column in ERRORS:
        print(f"\n{column} ≤ {THRESHOLD:g}: largest time step, s (steps to 10 s; cost to 10 s in µs per body "
              "= median ns per step × steps)\n")
        markdown_table(["scalar", *INTEGRATORS],
                       [[s] + [largest_step(column, i, s) for i in INTEGRATORS] for s in SCALARS], align="---")
    print("\nSmallest error on the ladder, and the time step reaching it (float's floor; double beside it)\n")
    markdown_table(["error", "scalar", *INTEGRATORS],
                   [[c, s] + [smallest_error(c, i, s) for i in INTEGRATORS] for c in ERRORS for s in SCALARS],
                   labels=2, align="---")


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    series = read_errors(sys.argv[2])
    plot(series, sys.argv[3])
    throughput_tables(read_throughput(sys.argv[1]))
    error_tables(series)


if __name__ == "__main__":
    main()
