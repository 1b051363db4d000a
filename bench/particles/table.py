#!/usr/bin/env python3
"""Markdown tables from bench/particles' CSV: throughput of the SoA kernel
beside the array-of-structs loop and the copy roof, per N, integrator and scalar.

Usage: python3 bench/particles/table.py docs/particles_benchmark.csv
"""
import csv
import sys


def scalar_section(rows, scalar):
    """The lines for one scalar: the table (SoA M/s, fraction of the roof, AoS M/s, SoA ÷ AoS per
    integrator and N), then the cost of each integrator relative to euler."""
    sizes = sorted({int(r["n"]) for r in rows})
    lines = ["| integrator | " + " | ".join(f"N = {n:,}".replace(",", " ") for n in sizes) + " |",
             "| --- |" + " ---: |" * len(sizes)]
    for integrator in ("euler", "symplectic_euler", "midpoint", "rk4"):
        cells = []
        for n in sizes:
            pick = {r["width"] == "aos": r for r in rows
                    if r["integrator"] == integrator and r["scalar"] == scalar and int(r["n"]) == n}
            soa, aos = pick.get(False), pick.get(True)
            if not soa or not aos:
                cells.append("–")
                continue
            s, a = float(soa["msteps_per_s"]), float(aos["msteps_per_s"])
            cells.append(f"{s:.0f} ({float(soa['bandwidth_fraction']):.2f}) / {a:.0f}; {s / a:.1f}×")
        lines.append(f"| {integrator} | " + " | ".join(cells) + " |")
    lines.append("")
    euler = {int(r["n"]): float(r["msteps_per_s"]) for r in rows
             if r["integrator"] == "euler" and r["scalar"] == scalar and r["width"] != "aos"}
    for integrator in ("symplectic_euler", "midpoint", "rk4"):
        ratios = [euler[int(r["n"])] / float(r["msteps_per_s"]) for r in rows
                  if r["integrator"] == integrator and r["scalar"] == scalar and r["width"] != "aos"]
        lines.append(f"- {integrator} costs {min(ratios):.2f}–{max(ratios):.2f}× euler ({scalar}, SoA)")
    return lines


def main(path):
    rows = list(csv.DictReader(open(path)))
    for scalar in ("float", "double"):
        print(f"\n**{scalar}**: M particle-steps/s, SoA kernel (fraction of the copy roof) / AoS loop; SoA ÷ AoS\n")
        print("\n".join(scalar_section(rows, scalar)))


if __name__ == "__main__":
    main(sys.argv[1])
