#!/usr/bin/env python3
"""Benchmark tables in the docs: render each from its CSV, and replace it in place.

Every table in docs/ that comes from a benchmark sits between two marker lines,

    <!-- bench_all: NAME begin -->
    ...
    <!-- bench_all: NAME end -->

and tools/bench_all.sh rewrites what lies between them: one italic provenance
line (date, machine, compiler and flags, peers), a blank line, then the table
as rendered here from the benchmark's output. Where a bench script already
prints the table (bench/particles/table.py, bench/broadphase/plot.py,
bench/rigid_motion/plot.py) its functions are reused; the tables the docs
pivot differently are rendered here in the docs' shape.

Usage (python3, standard library only):
  bench_docs.py list
      every block: its name, file and the benchmark step that makes it
  bench_docs.py check [--root DIR]
      fails unless every block's markers are in its file exactly once
  bench_docs.py render NAME [--root DIR] [--prov FILE] [--input KEY=FILE]...
      prints the block's new content
  bench_docs.py replace FILE NAME [CONTENT]
      replaces block NAME of FILE with CONTENT (a file, or stdin when
      absent or "-"); fails if the markers are missing or duplicated
  bench_docs.py update --step STEP [--root DIR] --prov FILE [--date D] [--input KEY=FILE]... [--no-plots]
      renders and replaces every block of STEP, and STEP's row of the
      provenance table in docs/benchmarks.md
  bench_docs.py joints-results RAW --prov FILE [--date D]
      prints bench/joints/results.txt: a summary of RAW (the output of
      bench/joints) in comment lines, then RAW
  bench_docs.py compare [--root DIR] [--prov FILE]
      renders every block from the files under DIR and shows where it
      differs from the block's present content (provenance line aside)

--root is the tree holding docs/ and bench/ (default: this repository;
tools/bench_all.sh --quick points it at a scratch copy). --prov is the
key=value file tools/bench_all.sh writes (date, machine, compilers, peers).
"""
import argparse
import csv
import difflib
import importlib.util
import math
import os
import pathlib
import re
import statistics
import sys
import textwrap

REPO = pathlib.Path(__file__).resolve().parent.parent
MARKER = re.compile(r"^<!-- bench_all: (\S+) (begin|end) -->$")


class Failure(Exception):
    """An error to report in one line and exit 1 with."""


# ---- markers ---------------------------------------------------------------------


def markers(lines):
    """(index, name, 'begin' or 'end') of each marker line, fenced code blocks skipped (a doc may show
    a marker as an example)."""
    found, fence = [], None
    for i, line in enumerate(lines):
        stripped = line.strip()
        if fence is None and stripped.startswith(("```", "~~~")):
            fence = stripped[:3]
        elif fence is not None and stripped.startswith(fence):
            fence = None
        elif fence is None:
            match = MARKER.match(stripped)
            if match:
                found.append((i, match.group(1), match.group(2)))
    return found


def find_block(lines, name, path="(text)"):
    """(index of the begin marker, index of the end marker) of block `name`."""
    all_markers = markers(lines)
    begins = [i for i, n, kind in all_markers if n == name and kind == "begin"]
    ends = [i for i, n, kind in all_markers if n == name and kind == "end"]
    for kind, found in (("begin", begins), ("end", ends)):
        if not found:
            raise Failure(f"{path}: no '<!-- bench_all: {name} {kind} -->' line")
        if len(found) > 1:
            lines_at = ", ".join(str(i + 1) for i in found)
            raise Failure(f"{path}: '<!-- bench_all: {name} {kind} -->' appears {len(found)} times "
                          f"(lines {lines_at})")
    begin, end = begins[0], ends[0]
    if end < begin:
        raise Failure(f"{path}: block {name} ends (line {end + 1}) before it begins (line {begin + 1})")
    inner = [i for i, _, _ in all_markers if begin < i < end]
    if inner:
        raise Failure(f"{path}: block {name} holds another marker at line {inner[0] + 1}")
    return begin, end


def block_content(path, name):
    lines = pathlib.Path(path).read_text(encoding="utf-8").split("\n")
    begin, end = find_block(lines, name, path)
    return lines[begin + 1:end]


def replace_block(path, name, content):
    """Replaces the lines between block `name`'s markers in `path` with `content` (a list of lines)."""
    path = pathlib.Path(path)
    if not path.is_file():
        raise Failure(f"{path}: no such file")
    text = path.read_text(encoding="utf-8")
    lines = text.split("\n")
    begin, end = find_block(lines, name, path)
    new = lines[:begin + 1] + list(content) + lines[end:]
    temporary = path.with_name(path.name + ".bench_docs.tmp")
    temporary.write_text("\n".join(new), encoding="utf-8")
    os.replace(temporary, path)


# ---- provenance ------------------------------------------------------------------


def read_provenance(path):
    """The key=value lines tools/bench_all.sh writes."""
    prov = {}
    if path is None:
        return prov
    for line in pathlib.Path(path).read_text(encoding="utf-8").splitlines():
        if "=" in line and not line.startswith("#"):
            key, value = line.split("=", 1)
            prov[key.strip()] = value.strip()
    return prov


def machine(prov):
    """'AMD EPYC, 2 cores (AVX2, FMA, no AVX-512)'."""
    features = [label if prov.get(key) == "yes" else f"no {label}"
                for key, label in (("avx2", "AVX2"), ("fma", "FMA"), ("avx512f", "AVX-512"))]
    return f"{prov.get('machine', 'unknown machine')}, {prov.get('cores', '?')} cores ({', '.join(features)})"


PEERS = {  # step -> the peer engines its programs compare with
    "broadphase": ["bullet"],
    "narrowphase": ["libccd", "bullet"],
    "scenes": ["bullet", "ode"],
    "joints": ["bullet"],
    "contact_memory": ["bullet"],
}
PEER_NAMES = {"bullet": "Bullet", "ode": "ODE", "libccd": "libccd"}


def peers(prov, step):
    """'Bullet 3.24, no ODE (not found)' for the peers of `step`; '' if it has none."""
    parts = []
    for peer in PEERS.get(step, []):
        version = prov.get(peer, "")
        parts.append(f"{PEER_NAMES[peer]} {version}" if version else f"no {PEER_NAMES[peer]} (not found)")
    return ", ".join(parts)


def compiler(prov, step):
    if step == "compile_time":
        names = [prov[k] for k in (("gxx",) if prov.get("quick") == "1" else ("gxx", "clangxx")) if prov.get(k)]
        return " and ".join(names) + ", flags per row"
    return f"{prov.get('cxx', 'unknown compiler')} {prov.get('cxx_flags', '')}".strip()


def provenance_line(prov, step, date=None):
    date = date or prov.get("date", "unknown date")
    how = "tools/bench_all.sh --quick (a smoke run, not figures)" if prov.get("quick") == "1" \
        else "tools/bench_all.sh"
    text = f"Measured {date} by {how}: {machine(prov)}; {compiler(prov, step)}"
    if peers(prov, step):
        text += f"; {peers(prov, step)}"
    return f"*{text}.*"


# ---- number formats --------------------------------------------------------------


def grouped(integer):
    """12345 -> '12 345' (the docs group thousands with a space)."""
    return f"{integer:,}".replace(",", " ")


def sig(x, digits):
    """x to `digits` significant digits, without an exponent, thousands grouped: 10 300, 0.55, 31."""
    if x == 0 or not math.isfinite(x):
        return f"{x:g}"
    rounded = float(f"{x:.{digits}g}")
    decimals = max(0, digits - 1 - math.floor(math.log10(abs(rounded))))
    if decimals == 0:
        return grouped(int(round(rounded)))
    return f"{rounded:.{decimals}f}"


def short_exponent(x, digits):
    """x in e-notation with `digits` significant digits and no padding: 1.95e-4, 6.1e-6, 3.0e-4."""
    mantissa, exponent = f"{x:.{digits - 1}e}".split("e")
    return f"{mantissa}e{int(exponent)}"


def short_exponent_trimmed(x, digits):
    """As short_exponent, trailing zeros of the mantissa dropped: 6.10e-6 -> 6.1e-6."""
    mantissa, exponent = f"{x:.{digits - 1}e}".split("e")
    if "." in mantissa:
        mantissa = mantissa.rstrip("0").rstrip(".")
    return f"{mantissa}e{int(exponent)}"


def whole(x):
    """Rounded to an integer, grouped: 38260.6 -> '38 261'."""
    return grouped(int(round(x)))


def ratio(x):
    """271×, 5.5×."""
    return f"{x:.0f}×" if x >= 10 else f"{x:.1f}×"


SUPERSCRIPTS = "¹²³⁴⁵⁶⁷⁸⁹"


def dip(values, i, factor=5, floor=1e-14):
    """True when values[i] (errors along a ladder of halving steps) is a cancellation rather than
    accuracy: at least `factor` times below both its neighbours, the next step's error above the
    previous one's (the error rises again past it), and above `floor`, where the figures are
    double's rounding and a dip means nothing."""
    if i <= 0 or i >= len(values) - 1 or values[i] < floor:
        return False
    return (values[i - 1] >= factor * values[i] and values[i + 1] >= factor * values[i]
            and values[i + 1] > values[i - 1])


# ---- loading the bench scripts -------------------------------------------------------


def load(relative):
    """The module of a bench script, e.g. bench/broadphase/plot.py (matplotlib is imported only to plot)."""
    path = REPO / relative
    sys.dont_write_bytecode = True  # no __pycache__ left beside the bench scripts
    spec = importlib.util.spec_from_file_location("bench_" + re.sub(r"\W", "_", relative), path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def source(ctx, relative):
    path = ctx.root / relative
    if not path.is_file():
        raise Failure(f"{path}: missing (run its benchmark first)")
    return path


def read_csv(path):
    with open(path, newline="", encoding="utf-8") as f:
        return list(csv.DictReader(f))


def table(header, rows, align):
    """Markdown table lines; align is one '---' or '---:' per column."""
    return (["| " + " | ".join(header) + " |", "| " + " | ".join(align) + " |"]
            + ["| " + " | ".join(row) + " |" for row in rows])


# ---- compile time ------------------------------------------------------------------


def render_program_table(name, program):
    """A block that is the Markdown table a program printed, given as --input NAME=FILE."""
    def render(ctx):
        path = ctx.inputs.get(name)
        if path is None:
            raise Failure(f"block {name} needs --input {name}=FILE (the output of {program})")
        lines = pathlib.Path(path).read_text(encoding="utf-8").strip("\n").split("\n")
        if not any(line.startswith("|") for line in lines):
            raise Failure(f"{path}: no table in the output of {program}")
        return lines
    return render


render_compile_time = render_program_table("compile_time", "bench/compile_time/compile_time.py")
render_contact_memory = render_program_table("contact_memory", "bench/contact_memory")


# ---- particles -----------------------------------------------------------------------


def render_particles(scalar):
    def render(ctx):
        rows = read_csv(source(ctx, "docs/particles_benchmark.csv"))
        return load("bench/particles/table.py").scalar_section(rows, scalar)
    return render


# ---- speed against error -------------------------------------------------------------


def format_h(h):
    """0.0125, 0.2; below 0.01 in e-notation: 1.95e-4, 6.1e-6."""
    return short_exponent_trimmed(h, 3) if h < 0.01 else f"{h:.3g}"


def cost_ns(x):
    """3 significant digits from 100 up, 2 below: 10 300, 246, 31, 7.6."""
    return sig(x, 3 if x >= 100 else 2)


def render_speed_vs_error_cost(ctx):
    sv = load("bench/speed_vs_error/plot.py")
    series = sv.read(source(ctx, "docs/speed_vs_error.csv"))
    cost = sv.per_step_cost(series)
    header = ["problem", "scalar"] + [f"{i} ({stages} stages)" if stages > 1 else i
                                      for i, (_, stages) in sv.INTEGRATORS.items()]
    rows = []
    for problem in sv.PROBLEMS:
        for scalar in ("float", "double"):
            base = cost.get((problem, "euler", scalar))
            if base is None:
                continue
            cells = []
            for integrator in sv.INTEGRATORS:
                c = cost.get((problem, integrator, scalar))
                if c is None:
                    cells.append("–")
                else:
                    cells.append(f"{c:.2f}" if integrator == "euler" else f"{c:.2f} ({c / base:.2f}×)")
            rows.append([problem, scalar] + cells)
    return table(header, rows, ["---", "---"] + ["---:"] * len(sv.INTEGRATORS))


class Footnotes:
    """Numbered footnotes for cells: mark() returns ' ¹' and keeps the note."""

    def __init__(self):
        self.notes = []

    def mark(self, note):
        self.notes.append(note)
        return " " + SUPERSCRIPTS[min(len(self.notes), len(SUPERSCRIPTS)) - 1]

    def lines(self):
        if not self.notes:
            return []
        lines = [""]
        for i, note in enumerate(self.notes):
            lines += textwrap.wrap(f"{SUPERSCRIPTS[min(i, len(SUPERSCRIPTS) - 1)]} {note}", 78)
        return lines


def speed_vs_error_hit(rows, threshold, scalar):
    """(hit row, 'h s (steps)', footnote or None) for the largest h whose error <= threshold; None if
    none reaches it. The footnote when the hit is an isolated dip (a cancellation)."""
    errors = [r["error"] for r in rows]
    for i, r in enumerate(rows):  # rows run from the largest h down
        if r["error"] <= threshold:
            note = None
            if dip(errors, i):
                rounding = "float " if scalar == "float" else ""
                note = (f"A cancellation, not accuracy: the truncation error and the accumulated {rounding}rounding "
                        f"have opposite signs there. The neighbouring h give {short_exponent(errors[i - 1], 2)} "
                        f"and {short_exponent(errors[i + 1], 2)}.")
            return r, f"{format_h(r['dt'])} s ({grouped(r['steps'])})", note
    return None


def render_speed_vs_error_threshold(threshold):
    def render(ctx):
        sv = load("bench/speed_vs_error/plot.py")
        series = sv.read(source(ctx, "docs/speed_vs_error.csv"))
        cost = sv.per_step_cost(series)
        notes = Footnotes()

        def hit(problem, integrator, scalar):
            rows = series.get((problem, integrator, scalar), [])
            return (speed_vs_error_hit(rows, threshold, scalar) if rows else None), rows

        def cost_of(problem, integrator, scalar, found):
            return cost_ns(cost[(problem, integrator, scalar)] * found[0]["steps"])

        def mark(found):
            return notes.mark(found[2]) if found[2] else ""

        def cell(problem, integrator, scalar):
            found, rows = hit(problem, integrator, scalar)
            if not rows:
                return "–"
            if found is None:
                return f"— ({short_exponent(min(r['error'] for r in rows), 2)})"
            return f"{found[1]}: {cost_of(problem, integrator, scalar, found)}{mark(found)}"

        problems = [p for p in sv.PROBLEMS if any(k[0] == p for k in series)]
        if threshold >= 1e-3:
            # One row per problem: the h (the same in both scalars, as a rule), cost double / float.
            rows = []
            for problem in problems:
                cells = []
                for integrator in sv.INTEGRATORS:
                    (hd, _), (hf, _) = hit(problem, integrator, "double"), hit(problem, integrator, "float")
                    if hd and hf and hd[0]["dt"] == hf[0]["dt"]:
                        cells.append(f"{hd[1]}: {cost_of(problem, integrator, 'double', hd)} / "
                                     f"{cost_of(problem, integrator, 'float', hf)}{mark(hd)}{mark(hf)}")
                    else:
                        cells.append(" / ".join(cell(problem, integrator, s) for s in ("double", "float")))
                rows.append([problem] + cells)
            return table(["problem", *sv.INTEGRATORS], rows, ["---"] * (1 + len(sv.INTEGRATORS))) + notes.lines()
        rows = [[problem, scalar] + [cell(problem, i, scalar) for i in sv.INTEGRATORS]
                for problem in problems for scalar in ("double", "float")
                if any((problem, i, scalar) in series for i in sv.INTEGRATORS)]
        return table(["problem", "scalar", *sv.INTEGRATORS], rows,
                     ["---"] * (2 + len(sv.INTEGRATORS))) + notes.lines()
    return render


# ---- rigid motion --------------------------------------------------------------------


def render_rigid_motion_throughput(scene):
    def render(ctx):
        rm = load("bench/rigid_motion/plot.py")
        rows = rm.read_throughput(source(ctx, "docs/rigid_motion.csv"))
        if scene is None:
            return rm.coupled_over_independent_table(rows)
        return rm.throughput_table(rows, scene)
    return render


def render_rigid_motion_cost(ctx):
    rm = load("bench/rigid_motion/plot.py")
    return rm.cost_table(rm.read_errors(source(ctx, "docs/rigid_motion_speed_vs_error.csv")))


def rigid_motion_columns(rm, cells):
    """The integrator columns, euler and symplectic_euler merged when every one of their cells agrees
    (without torque they are the same method). cells: {(row key, integrator): text}."""
    integrators = list(rm.INTEGRATORS)
    keys = {k for k, _ in cells}
    if all(cells.get((k, "euler")) == cells.get((k, "symplectic_euler")) for k in keys):
        return [("euler, symplectic_euler", "euler")] + [(i, i) for i in integrators if i not in
                                                          ("euler", "symplectic_euler")]
    return [(i, i) for i in integrators]


def fraction_dt(dt):
    return f"1/{1 / dt:.0f}"


def render_rigid_motion_largest_step(ctx):
    rm = load("bench/rigid_motion/plot.py")
    series = rm.read_errors(source(ctx, "docs/rigid_motion_speed_vs_error.csv"))
    cost = {key: statistics.median(r["ns_per_body_step"] for r in rows) for key, rows in series.items()}
    cells = {}
    for column in rm.ERRORS:
        for scalar in rm.SCALARS:
            for integrator in rm.INTEGRATORS:
                rows = series.get((integrator, scalar))
                if not rows:
                    cells[((column, scalar), integrator)] = "–"
                    continue
                hits = [r for r in rows if r[column] <= rm.THRESHOLD]
                if not hits:
                    best = min(r[column] for r in rows)
                    cells[((column, scalar), integrator)] = f"not reached (best {short_exponent(best, 2)})"
                    continue
                r = hits[0]  # rows run from the largest dt down
                micro = cost[(integrator, scalar)] * r["steps"] / 1e3
                cells[((column, scalar), integrator)] = (f"{fraction_dt(r['dt'])} s ({grouped(r['steps'])}; "
                                                         f"{sig(micro, 3)})")
    columns = rigid_motion_columns(rm, cells)
    rows = [[column.replace("_error", ""), scalar] + [cells[((column, scalar), i)] for _, i in columns]
            for column in rm.ERRORS for scalar in rm.SCALARS]
    return table([f"error ≤ {rm.THRESHOLD:g}".replace("e-06", "e-6"), "scalar"] + [h for h, _ in columns], rows,
                 ["---"] * (2 + len(columns)))


def render_rigid_motion_smallest_error(ctx):
    rm = load("bench/rigid_motion/plot.py")
    series = rm.read_errors(source(ctx, "docs/rigid_motion_speed_vs_error.csv"))
    notes = Footnotes()
    cells, dips = {}, {}
    for column in rm.ERRORS:
        for scalar in rm.SCALARS:
            for integrator in rm.INTEGRATORS:
                rows = series.get((integrator, scalar))
                if not rows:
                    cells[((column, scalar), integrator)] = "–"
                    continue
                values = [r[column] for r in rows]
                i = min(range(len(rows)), key=lambda k: values[k])
                cells[((column, scalar), integrator)] = (f"{short_exponent(values[i], 2)} at "
                                                         f"{fraction_dt(rows[i]['dt'])}")
                if dip(values, i):
                    dips[((column, scalar), integrator)] = (
                        f"A cancellation, not accuracy: the neighbouring time steps give "
                        f"{short_exponent(values[i - 1], 2)} ({fraction_dt(rows[i - 1]['dt'])}) and "
                        f"{short_exponent(values[i + 1], 2)} ({fraction_dt(rows[i + 1]['dt'])}).")
    columns = rigid_motion_columns(rm, cells)
    rows = []
    for column in rm.ERRORS:
        for scalar in rm.SCALARS:
            row = [column.replace("_error", ""), scalar]
            for _, integrator in columns:
                key = ((column, scalar), integrator)
                row.append(cells[key] + (notes.mark(dips[key]) if key in dips else ""))
            rows.append(row)
    return table(["error", "scalar"] + [h for h, _ in columns], rows, ["---"] * (2 + len(columns))) + notes.lines()


# ---- broad phase ---------------------------------------------------------------------


BROADPHASE_NAMES = {
    "brute_force": "brute force", "sweep_and_prune": "sweep and prune", "spatial_hash": "spatial hash",
    "dynamic_bvh": "dynamic BVH", "octree": "octree", "bullet_dbvt": "Bullet dbvt",
    "bullet_axis_sweep": "Bullet axis sweep",
}


def broadphase_data(ctx):
    bp = load("bench/broadphase/plot.py")
    return (bp,) + bp.read(source(ctx, "docs/broadphase.csv"))


def render_broadphase_distribution(distribution):
    def render(ctx):
        bp, us, pairs, algorithms = broadphase_data(ctx)
        return bp.distribution_table(us, pairs, algorithms, distribution)
    return render


def render_broadphase_speedup(ctx):
    bp, us, pairs, algorithms = broadphase_data(ctx)
    lines = bp.speedup_list(us, algorithms)
    return lines if lines is not None else ["No brute-force run at N = 10 000 uniform in this run."]


def render_broadphase_vs_bullet(ctx):
    bp, us, pairs, algorithms = broadphase_data(ctx)
    lines = bp.versus_bullet_table(us, algorithms)
    if len(lines) == 2:
        if not any(a.startswith("bullet") for a in algorithms):
            return ["Bullet was not compiled in (libbullet-dev not installed): no comparison."]
        return ["No N ≥ 10 000 in this run: no comparison."]
    return lines


def render_performance_broadphase(ctx):
    bp, us, pairs, algorithms = broadphase_data(ctx)
    sizes = sorted({n for series in us.values() for n in series if n >= 10000})
    ours = [a for a in algorithms if a != "brute_force" and not a.startswith("bullet")]
    rows = []
    for d in bp.DISTRIBUTIONS:
        for n in sizes:
            if not any(n in us.get((a, d), {}) for a in algorithms):
                continue
            best = min((us[(a, d)][n] for a in ours if n in us.get((a, d), {})), default=None)
            cells = []
            for a in algorithms:
                t = us.get((a, d), {}).get(n)
                text = "–" if t is None else sig(t / 1000, 3)
                cells.append(f"**{text}**" if t is not None and t == best else text)
            rows.append([f"{d.replace('_', ' ')}, {grouped(n)}"] + cells)
    return table(["scene, N"] + [BROADPHASE_NAMES.get(a, a) for a in algorithms], rows,
                 ["---"] + ["---:"] * len(algorithms))


# ---- narrow phase --------------------------------------------------------------------


NARROWPHASE_PAIRS = ["sphere-sphere", "sphere-capsule", "sphere-box", "capsule-capsule", "capsule-box", "box-box",
                     "sphere-hull", "capsule-hull", "box-hull", "hull-hull"]
GROUND_SHAPES = ["sphere", "capsule", "box", "hull"]


def narrowphase_data(ctx):
    data = {}
    for r in read_csv(source(ctx, "docs/narrowphase_bench.csv")):
        error = r["max_abs_error_vs_reference"]
        data[(r["pair"], r["algorithm"], r["engine"])] = (float(r["ns_per_test_median"]),
                                                          float(error) if error else None)
    return data


def error_one_digit(x):
    """Worst errors: 1.8, 0.6, 7e-5, 0."""
    if x is None:
        return "–"
    if x == 0:
        return "0"
    if x >= 1:
        return f"{x:.2g}"
    if x >= 0.01:
        return f"{x:.1g}"
    return short_exponent(x, 1)


def render_performance_narrowphase(ctx):
    data = narrowphase_data(ctx)
    has_ccd = any(k[2] == "libccd" for k in data)
    has_bullet = any(k[2] == "bullet" for k in data)
    header = ["pair", "ours `collide` (f32)", "ours GJK+EPA (f32)", "ours GJK+EPA (f64)"]
    if has_ccd:
        header += ["libccd GJK+EPA", "libccd MPR"]
    if has_bullet:
        header += ["Bullet GJK+EPA"]
    if has_ccd:
        header += ["libccd ÷ ours (f64)"]
    if has_bullet:
        header += ["Bullet ÷ ours (f32)"]
    header += ["worst error: " + " / ".join(["ours f64"] + ["libccd"] * has_ccd + ["Bullet"] * has_bullet) + " (m)"]
    pairs = [p for p in NARROWPHASE_PAIRS if (p, "gjk_epa", "impulse_f64") in data]
    pairs += sorted({k[0] for k in data if k[1] == "gjk_epa" and k[2] == "impulse_f64"} - set(pairs))
    rows = []
    for pair in pairs:
        def ns(algorithm, engine):
            value = data.get((pair, algorithm, engine))
            return "–" if value is None else whole(value[0])

        def over(algorithm, engine, ours):
            theirs, mine = data.get((pair, algorithm, engine)), data.get((pair, "gjk_epa", ours))
            return "–" if theirs is None or mine is None else ratio(theirs[0] / mine[0])

        def error(engine):
            value = data.get((pair, "gjk_epa", engine))
            return "–" if value is None else error_one_digit(value[1])

        row = [pair.replace("-", "–"), ns("collide", "impulse_f32"), ns("gjk_epa", "impulse_f32"),
               ns("gjk_epa", "impulse_f64")]
        if has_ccd:
            row += [ns("gjk_epa", "libccd"), ns("mpr", "libccd")]
        if has_bullet:
            row += [ns("gjk_epa", "bullet")]
        if has_ccd:
            row += [over("gjk_epa", "libccd", "impulse_f64")]
        if has_bullet:
            row += [over("gjk_epa", "bullet", "impulse_f32")]
        row += [" / ".join([error("impulse_f64")] + [error("libccd")] * has_ccd + [error("bullet")] * has_bullet)]
        rows.append(row)
    return table(header, rows, ["---"] + ["---:"] * (len(header) - 2) + ["---"])


def error_two_digits(x):
    """Depth errors on the ground: 0.078, 6e-8."""
    if x is None:
        return "–"
    if x == 0:
        return "0"
    return f"{x:.2g}" if x >= 1e-3 else short_exponent(x, 1)


def render_performance_narrowphase_ground(ctx):
    data = narrowphase_data(ctx)
    rows = []
    for shape in GROUND_SHAPES:
        plane = data.get((f"{shape}-plane", "collide", "impulse_f32"))
        mesh = data.get((f"{shape}-mesh", "collide", "impulse_f32"))
        if plane is None and mesh is None:
            continue
        rows.append([shape, "–" if plane is None else whole(plane[0]), "–" if mesh is None else whole(mesh[0]),
                     "–" if mesh is None else error_two_digits(mesh[1])])
    return table(["shape", "on the plane", "on the mesh", "worst depth error on the mesh (m)"], rows,
                 ["---", "---:", "---:", "---:"])


# ---- rigid-body scenes ---------------------------------------------------------------


SCENE_LABELS = {
    "pile_nosleep": "`pile_nosleep` (1000 boxes)",
    "pyramid_nosleep": "`pyramid_nosleep` (210 boxes)",
    "spheres_nosleep": "`spheres_nosleep` (10 000 spheres)",
    "large_pyramid": "`large_pyramid` (5050 boxes, 200 steps)",
}
SCENE_TARGETS = {"pile_nosleep": 0.5, "pyramid_nosleep": 0.5, "spheres_nosleep": 0.5}
IMPULSE_CONFIGS = [  # column, what its config names
    ("impulse BVH", ("sequential_impulse", "dynamic_bvh")),
    ("SAP", ("sequential_impulse", "sweep_and_prune")),
    ("hash", ("sequential_impulse", "spatial_hash")),
    ("octree", ("sequential_impulse", "octree")),
    ("brute force", ("sequential_impulse", "brute_force")),
    ("soft_step", ("soft_step", "dynamic_bvh")),
]


class Scenes:
    """bench/scenes' CSV: ms per step and metrics by (column, scene), columns as in IMPULSE_CONFIGS plus
    'Bullet' and 'ODE'."""

    def __init__(self, path):
        self.ms, self.metric = {}, {}
        for r in read_csv(path):
            column = None
            if r["engine"] == "impulse":
                for name, words in IMPULSE_CONFIGS:
                    if all(w in r["config"].split() for w in words):
                        column = name
            else:
                column = {"bullet": "Bullet", "ode": "ODE"}.get(r["engine"], r["engine"])
            if column is None:
                continue
            self.ms[(column, r["scene"])] = float(r["ms_per_step_median"])
            self.metric[(column, r["scene"], r["metric"])] = float(r["value"])
        self.columns = {c for c, _ in self.ms}

    def get(self, column, scene, metric):
        return self.metric.get((column, scene, metric))


def render_performance_scenes(ctx):
    s = Scenes(source(ctx, "bench/scenes/results.csv"))
    columns = [c for c, _ in IMPULSE_CONFIGS if c in s.columns] + [c for c in ("Bullet", "ODE") if c in s.columns]
    with_ratio = "Bullet" in s.columns and "impulse BVH" in s.columns
    rows = []
    for scene, label in SCENE_LABELS.items():
        if not any((c, scene) in s.ms for c in columns):
            continue
        cells = []
        for c in columns:
            t = s.ms.get((c, scene))
            text = "–" if t is None else sig(t, 3)
            if t is not None and c in ("impulse BVH", "Bullet", "ODE"):
                text += " ms"
            cells.append(text)
        if with_ratio:
            ours, bullet = s.ms.get(("impulse BVH", scene)), s.ms.get(("Bullet", scene))
            target = SCENE_TARGETS.get(scene)
            if ours is None or bullet is None:
                cells.append("–")
            else:
                r = f"{ours / bullet:.2f}"
                cells.append(f"**{r}**" if target is not None and ours / bullet <= target else r)
            cells.append("—" if target is None else f"≤ {target:g}")
        rows.append([label] + cells)
    if not rows:
        return ["None of this table's scenes ran (pile_nosleep, pyramid_nosleep, spheres_nosleep, large_pyramid)."]
    header = ["scene (sleeping off)"] + columns + (["impulse ÷ Bullet", "target"] if with_ratio else [])
    return table(header, rows, ["---"] + ["---:"] * (len(header) - 1))


ASLEEP_LABELS = {
    "pile_asleep": "`pile_asleep` (1000 boxes)",
    "pyramid_asleep": "`pyramid_asleep` (210 boxes)",
}
ASLEEP_TARGET_US = 2.0


def render_performance_asleep(ctx):
    """The _asleep scenes: µs per step with every body asleep, and the steps each engine took to get there."""
    s = Scenes(source(ctx, "bench/scenes/results.csv"))
    columns = [c for c, _ in IMPULSE_CONFIGS if c in s.columns] + [c for c in ("Bullet", "ODE") if c in s.columns]
    rows = []
    for scene, label in ASLEEP_LABELS.items():
        if not any((c, scene) in s.ms for c in columns):
            continue
        cells = []
        for c in columns:
            t, awake = s.ms.get((c, scene)), s.get(c, scene, "bodies_awake")
            if t is None:
                cells.append("–")
                continue
            text = sig(t * 1000, 2) + (" µs" if c in ("impulse BVH", "Bullet", "ODE") else "")
            if awake:  # never all asleep within the settling limit: timed with bodies awake
                text += f" ({awake:.0f} awake)"
            cells.append(text)
        settle = [s.get(c, scene, "steps_to_sleep") for c in ("impulse BVH", "Bullet")]
        cells.append(" / ".join("–" if n is None else f"{n:.0f}" for n in settle))
        ours = s.ms.get(("impulse BVH", scene))
        cells.append("–" if ours is None else
                     (f"**{sig(ours * 1000, 2)} µs**" if ours * 1000 <= ASLEEP_TARGET_US else f"{sig(ours * 1000, 2)} µs"))
        cells.append(f"≤ {ASLEEP_TARGET_US:g} µs")
        rows.append([label] + cells)
    if not rows:
        return ["None of this table's scenes ran (pile_asleep, pyramid_asleep)."]
    header = ["scene (all asleep)"] + columns + ["steps to sleep (impulse / Bullet)", "impulse", "target"]
    return table(header, rows, ["---"] + ["---:"] * (len(header) - 1))


def length(metres):
    """A length in mm below 1 cm, else in cm: 0.69 mm, 0.007 mm, 2 cm, 97 cm, 191 cm."""
    if metres < 0.01:
        return f"{metres * 1000:.2g} mm"
    centimetres = metres * 100
    return f"{centimetres:.0f} cm" if centimetres >= 10 else f"{centimetres:.2g} cm"


def peer_header(prov, column):
    version = prov.get({"Bullet": "bullet", "ODE": "ode"}[column], "")
    version = ".".join(version.split(".")[:2])
    return f"{column} {version}".strip()


WORLD_CASES = [  # label, threshold, cell(scenes, column) -> text or None
    ("`bounce` peak", "6.58 ± 0.25 %", lambda s, c: (
        None if s.get(c, "bounce", "first_rebound_peak") is None else
        f"{s.get(c, 'bounce', 'first_rebound_peak'):.{5 if c == 'impulse BVH' else 4}g}")),
    ("`incline` μ 0.5", "0.657 ± 0.5 %", lambda s, c: (
        None if s.get(c, "incline", "acceleration") is None else
        f"{s.get(c, 'incline', 'acceleration'):.{5 if c == 'impulse BVH' else 3}g}")),
    ("`incline` μ 0.7, drift in 5 s", "< 0.05 mm", lambda s, c: (
        None if s.get(c, "incline_static", "drift") is None else length(s.get(c, "incline_static", "drift")))),
    ("10-box tower, 20 s: top drift / height lost", "< 1 cm each", lambda s, c: tower(s, c)),
    ("20-row pyramid, 20 s: largest move per axis", "< 2 cm", lambda s, c: pyramid_largest(s, c)),
    ("100 kg on 1 kg, 10 s: sinking", "< 1 cm", lambda s, c: sinking(s, c)),
    ("Newton's cradle: last ball's speed", "≥ 90 %", lambda s, c: (
        None if s.get(c, "cradle", "last_ball_speed_ratio") is None else
        f"{100 * s.get(c, 'cradle', 'last_ball_speed_ratio'):.0f} %")),
    ("pile, sleeping on: all asleep in 10 s", "yes", lambda s, c: (
        None if s.get(c, "pile", "bodies_awake") is None else
        "yes" if s.get(c, "pile", "bodies_awake") == 0 else "no")),
]


def tower(s, c):
    drift, lost = s.get(c, "tower10", "top_horizontal_drift"), s.get(c, "tower10", "top_height_lost")
    if drift is None or lost is None:
        return None
    if lost > 0.5:  # the top box came down by half a box or more: the tower fell
        return f"falls (top {lost:.2g} m lower)"
    return f"{length(drift)} / {length(lost)}"


def pyramid_largest(s, c):
    moves = {axis: s.get(c, "pyramid_nosleep", f"max_abs_d{axis}") for axis in "xyz"}
    if any(v is None for v in moves.values()):
        return None
    axis = max(moves, key=moves.get)
    return f"{length(moves[axis])} ({axis})"


def sinking(s, c):
    end, most = s.get(c, "heavy_on_light", "sinking_end"), s.get(c, "heavy_on_light", "sinking_max")
    if end is None or most is None:
        return None
    if end > 0.5:  # the heavy box ended half a box or more lower: it slid off the light one
        return "slides off"
    return length(most)


def render_world_peers(ctx):
    s = Scenes(source(ctx, "bench/scenes/results.csv"))
    columns = [c for c in ("impulse BVH", "Bullet", "ODE") if c in s.columns]
    rows = [[label, threshold] + [cell(s, c) or "–" for c in columns] for label, threshold, cell in WORLD_CASES]
    header = ["case", "threshold"] + ["impulse" if c == "impulse BVH" else peer_header(ctx.prov, c) for c in columns]
    return table(header, rows, ["---", "---"] + ["---:"] * len(columns))


SOFT_CASES = [  # label, threshold, cell(scenes, column) -> text or None
    ("`incline` μ 0.5", "0.657 ± 0.5 %", lambda s, c: (
        None if s.get(c, "incline", "acceleration") is None else f"{s.get(c, 'incline', 'acceleration'):.5g}")),
    ("`incline` μ 0.7, drift in 5 s", "< 0.05 mm", lambda s, c: (
        None if s.get(c, "incline_static", "drift") is None else length(s.get(c, "incline_static", "drift")))),
    ("10-box tower: top drift / height lost", "< 1 cm each", lambda s, c: tower(s, c)),
    ("20-row pyramid: largest move x / y / z", "< 2 cm", lambda s, c: (
        None if s.get(c, "pyramid_nosleep", "max_abs_dx") is None else
        " / ".join(f"{round(100 * s.get(c, 'pyramid_nosleep', f'max_abs_d{a}'), 2):.2g}" for a in "xyz") + " cm")),
    ("100 kg on 1 kg: sinking", "< 1 cm", lambda s, c: sinking(s, c)),
    ("`bounce` peak", "6.58 ± 0.25 %", lambda s, c: bounce_against_target(s, c)),
    ("Newton's cradle at 1 m/s: last ball", "≥ 90 %", lambda s, c: (
        None if s.get(c, "cradle", "last_ball_speed_ratio") is None else
        f"{100 * s.get(c, 'cradle', 'last_ball_speed_ratio'):.0f} %")),
]


def bounce_against_target(s, c):
    peak = s.get(c, "bounce", "first_rebound_peak")
    if peak is None:
        return None
    off = (peak / 6.58 - 1) * 100
    return f"{peak:.5g}" if abs(off) <= 0.25 else f"{peak:.4g} ({off:+.1f} %)"


def render_world_soft_step(ctx):
    s = Scenes(source(ctx, "bench/scenes/results.csv"))
    columns = [c for c in ("soft_step", "impulse BVH") if c in s.columns]
    rows = [[label, threshold] + [cell(s, c) or "–" for c in columns] for label, threshold, cell in SOFT_CASES]
    header = ["case", "threshold"] + ["sequential_impulse" if c == "impulse BVH" else c for c in columns]
    return table(header, rows, ["---", "---"] + ["---:"] * len(columns))


# ---- joints --------------------------------------------------------------------------


RAGDOLL_BODIES = 11  # bodies per ragdoll (bench/joints/ragdoll_pile.hpp)
JOINT_ENGINES = {  # engine -> (grid label, ragdoll label)
    "impulse": ("impulse, sequential_impulse (4 parts of 8 iterations)", "impulse, sequential_impulse, trees exact"),
    "soft_step": ("impulse, soft_step (4 substeps)", "impulse, soft_step, trees exact"),
    "impulse_gs": ("impulse, sequential_impulse, joint by joint", "impulse, sequential_impulse, joint by joint"),
    "soft_step_gs": ("impulse, soft_step, joint by joint", "impulse, soft_step, joint by joint"),
}


def parse_joints(text):
    """{scene: {"title": str, "rows": [(engine, run, ms, gap, lowest, moving)]}} from bench/joints' output."""
    scenes, current = {}, None
    for line in text.splitlines():
        if not line.strip() or line.startswith("#"):
            continue
        words = line.split()
        if words[0] in ("joint_grid", "ragdoll_pile"):
            current = scenes.setdefault(words[0], {"title": line, "rows": []})
        elif words[0] == "engine" or current is None:
            continue
        else:
            engine, run, ms, gap, lowest, moving = words
            current["rows"].append((engine, int(run), float(ms), float(gap), float(lowest), int(moving)))
    return scenes


def joints_by_engine(rows):
    engines = {}
    for engine, run, ms, gap, lowest, moving in rows:
        engines.setdefault(engine, {})[run] = (ms, gap, lowest, moving)
    return engines


def same_or_each(values, fmt):
    return fmt(values[0]) if len(set(values)) == 1 else ", ".join(fmt(v) for v in values)


def render_joints(scene):
    def render(ctx):
        scenes = parse_joints(source(ctx, "bench/joints/results.txt").read_text(encoding="utf-8"))
        if scene not in scenes:
            return [f"bench/joints ran no {scene} in this run."]
        title = scenes[scene]["title"]
        engines = joints_by_engine(scenes[scene]["rows"])
        runs = sorted({run for runs in engines.values() for run in runs})
        bullet = engines.get("bullet")
        grid = scene == "joint_grid"
        bodies = None
        match = re.match(r"ragdoll_pile (\d+) ragdolls", title)
        if match:
            bodies = int(match.group(1)) * RAGDOLL_BODIES
        run_label = f"runs {runs[0]}–{runs[-1]}" if len(runs) > 1 else f"run {runs[0]}"
        header = ["engine", f"ms/step ({run_label})"] + (["÷ Bullet, same run"] if bullet else []) + \
                 ["worst anchor gap at the end", "lowest body" if grid else "bodies still moving > 0.1 m/s"]
        rows = []
        order = [e for e in list(JOINT_ENGINES) + ["bullet"] if e in engines]
        for k, engine in enumerate(order):
            per_run = engines[engine]
            label = (f"Bullet {ctx.prov['bullet']} (10 iterations)" if ctx.prov.get("bullet") else
                     "Bullet (10 iterations)") if engine == "bullet" else JOINT_ENGINES[engine][0 if grid else 1]
            ms = ", ".join(sig(per_run[r][0], 3) for r in runs if r in per_run)
            row = [label, ms]
            if bullet:
                if engine == "bullet":
                    row.append("1")
                else:
                    row.append(", ".join(f"{per_run[r][0] / bullet[r][0]:.2f}" for r in runs
                                         if r in per_run and r in bullet))
            gaps = [per_run[r][1] for r in runs if r in per_run]
            if grid:
                row.append(same_or_each(gaps, lambda g: f"{g * 1000:.2g} mm" if g < 0.01 else
                                        f"{g:.2f} m" if g < 10 else f"{g:.1f} m"))
                lowest = [per_run[r][2] for r in runs if r in per_run]
                row.append(same_or_each(lowest, lambda y: f"{y:.1f} m".replace("-", "−")))
            else:
                row.append(same_or_each(gaps, lambda g: "< 0.01 mm" if g < 5e-6 else f"{g * 1000:.3g} mm"))
                moving = [per_run[r][3] for r in runs if r in per_run]
                text = same_or_each(moving, str)
                row.append(f"{text} of {bodies}" if k == 0 and bodies and len(set(moving)) == 1 else text)
            rows.append(row)
        return table(header, rows, ["---", "---"] + (["---"] if bullet else []) + ["---:", "---:"])
    return render


def joints_results(raw, prov, date):
    """bench/joints/results.txt: a summary of the runs in comment lines, then the program's output."""
    scenes = parse_joints(raw)
    runs = sorted({row[1] for s in scenes.values() for row in s["rows"]})
    lines = [f"# bench/joints, {date or prov.get('date', '')}, {machine(prov)}; {compiler(prov, 'joints')}; "
             f"{peers(prov, 'joints')}. Written by tools/bench_all.sh."]
    count = {1: "One run", 2: "Two runs", 3: "Three runs"}.get(len(runs), f"{len(runs)} runs")
    lines.append(f"# {count}, each engine timed in turn within a run; compare ratios within a run.")
    deterministic = True
    for name, s in scenes.items():
        engines = joints_by_engine(s["rows"])
        for per_run in engines.values():
            if len({(v[1], v[2], v[3]) for v in per_run.values()}) > 1:
                deterministic = False
        bullet = engines.get("bullet")
        if not bullet:
            continue

        def ratios(engine):
            values = [engines[engine][r][0] / bullet[r][0] for r in runs if r in engines[engine] and r in bullet]
            return (" ".join(f"{v:.2f}" for v in values) +
                    (f" (median {statistics.median(values):.2f})" if len(values) > 1 else ""))

        exact = [e for e in ("impulse", "soft_step") if e in engines]
        by_joint = [e for e in ("impulse_gs", "soft_step_gs") if e in engines]
        solver = {"impulse": "sequential_impulse", "soft_step": "soft_step",
                  "impulse_gs": "sequential_impulse", "soft_step_gs": "soft_step"}
        text = ", ".join(f"{solver[e]} {ratios(e)}" for e in exact)
        if by_joint:
            lines.append(f"# {name}, impulse ÷ Bullet by run: {text};")
            lines.append("#   joint trees solved joint by joint (_gs): " +
                         ", ".join(f"{solver[e]} {ratios(e)}" for e in by_joint) + ".")
        else:
            lines.append(f"# {name}, impulse ÷ Bullet by run: {text}.")
    if "bullet" not in {row[0] for s in scenes.values() for row in s["rows"]}:
        lines.append("# Bullet was not compiled in (libbullet-dev not installed): no ratios.")
    if len(runs) > 1:
        lines.append("# The gaps and positions are the same in every run (the step is deterministic)." if deterministic
                     else "# The gaps or positions differ between runs.")
    lines.append("# The grid's joints form loops, so it is solved joint by joint by both solvers; the ragdolls are "
                 "trees, solved exactly unless _gs (joint_tree.hpp).")
    return "\n".join(lines) + "\n" + raw.rstrip("\n") + "\n"


# ---- the registry --------------------------------------------------------------------


class Block:
    def __init__(self, name, doc, step, render):
        self.name, self.doc, self.step, self.render = name, doc, step, render


BLOCKS = [
    Block("compile_time", "docs/performance.md", "compile_time", render_compile_time),
    Block("contact_memory", "docs/world.md", "contact_memory", render_contact_memory),
    Block("performance_broadphase", "docs/performance.md", "broadphase", render_performance_broadphase),
    Block("performance_narrowphase", "docs/performance.md", "narrowphase", render_performance_narrowphase),
    Block("performance_narrowphase_ground", "docs/performance.md", "narrowphase",
          render_performance_narrowphase_ground),
    Block("performance_scenes", "docs/performance.md", "scenes", render_performance_scenes),
    Block("performance_asleep", "docs/performance.md", "scenes", render_performance_asleep),
    Block("broadphase_uniform", "docs/broadphase.md", "broadphase", render_broadphase_distribution("uniform")),
    Block("broadphase_clustered", "docs/broadphase.md", "broadphase", render_broadphase_distribution("clustered")),
    Block("broadphase_falling_pile", "docs/broadphase.md", "broadphase",
          render_broadphase_distribution("falling_pile")),
    Block("broadphase_speedup", "docs/broadphase.md", "broadphase", render_broadphase_speedup),
    Block("broadphase_vs_bullet", "docs/broadphase.md", "broadphase", render_broadphase_vs_bullet),
    Block("particles_float", "docs/particles_benchmark.md", "particles", render_particles("float")),
    Block("particles_double", "docs/particles_benchmark.md", "particles", render_particles("double")),
    Block("rigid_motion_independent", "docs/rigid_motion.md", "rigid_motion",
          render_rigid_motion_throughput("independent")),
    Block("rigid_motion_coupled", "docs/rigid_motion.md", "rigid_motion", render_rigid_motion_throughput("coupled")),
    Block("rigid_motion_coupled_vs_independent", "docs/rigid_motion.md", "rigid_motion",
          render_rigid_motion_throughput(None)),
    Block("rigid_motion_cost", "docs/rigid_motion.md", "rigid_motion", render_rigid_motion_cost),
    Block("rigid_motion_largest_step", "docs/rigid_motion.md", "rigid_motion", render_rigid_motion_largest_step),
    Block("rigid_motion_smallest_error", "docs/rigid_motion.md", "rigid_motion", render_rigid_motion_smallest_error),
    Block("speed_vs_error_cost", "docs/speed_vs_error.md", "speed_vs_error", render_speed_vs_error_cost),
    Block("speed_vs_error_h_1e-3", "docs/speed_vs_error.md", "speed_vs_error", render_speed_vs_error_threshold(1e-3)),
    Block("speed_vs_error_h_1e-6", "docs/speed_vs_error.md", "speed_vs_error", render_speed_vs_error_threshold(1e-6)),
    Block("joints_grid", "docs/joints.md", "joints", render_joints("joint_grid")),
    Block("joints_ragdolls", "docs/joints.md", "joints", render_joints("ragdoll_pile")),
    Block("world_peers", "docs/world.md", "scenes", render_world_peers),
    Block("world_soft_step", "docs/world.md", "scenes", render_world_soft_step),
]
PROVENANCE_BLOCK = ("provenance", "docs/benchmarks.md")

STEPS = {  # step -> its output files (beside its blocks), in the order tools/bench_all.sh runs them
    "compile_time": [],
    "particles": ["docs/particles_benchmark.csv"],
    "speed_vs_error": ["docs/speed_vs_error.csv", "docs/speed_vs_error.png"],
    "rigid_motion": ["docs/rigid_motion.csv", "docs/rigid_motion_speed_vs_error.csv", "docs/rigid_motion.png"],
    "broadphase": ["docs/broadphase.csv", "docs/broadphase.png"],
    "narrowphase": ["docs/narrowphase_bench.csv"],
    "joints": ["bench/joints/results.txt"],
    "scenes": ["bench/scenes/results.csv", "bench/scenes/peers_results.csv"],
    "contact_memory": [],
}


def blocks_of(step):
    return [b for b in BLOCKS if b.step == step]


def block_named(name):
    for b in BLOCKS:
        if b.name == name:
            return b
    raise Failure(f"no block {name} (bench_docs.py list shows them)")


class Context:
    def __init__(self, root, prov, inputs):
        self.root, self.prov, self.inputs = pathlib.Path(root), prov, inputs


def rendered(block, ctx, date=None):
    # The blank line after the table: a line right below a table would be read as one of its rows.
    return [provenance_line(ctx.prov, block.step, date), ""] + block.render(ctx) + [""]


# ---- the provenance table of docs/benchmarks.md --------------------------------------------


PROVENANCE_HEADER = ["step", "outputs", "date", "machine", "compiler and flags", "peers"]


def outputs_cell(step, no_plots):
    files = []
    for f in STEPS[step]:
        text = f"`{f}`"
        if no_plots and f.endswith(".png"):
            text += " (not redrawn: no matplotlib)"
        files.append(text)
    names = [b.name for b in blocks_of(step)]
    return "; ".join(files + [("block " if len(names) == 1 else "blocks ") + ", ".join(names)])


def update_provenance_table(ctx, step, date, no_plots):
    path = ctx.root / PROVENANCE_BLOCK[1]
    content = block_content(path, PROVENANCE_BLOCK[0])
    rows = {}
    for line in content:
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) == len(PROVENANCE_HEADER) and cells[0].startswith("`"):
            rows[cells[0].strip("`")] = cells
    rows[step] = [f"`{step}`", outputs_cell(step, no_plots), date or ctx.prov.get("date", ""),
                  machine(ctx.prov), compiler(ctx.prov, step) + (" (--quick: smoke run)" if ctx.prov.get("quick") == "1"
                                                                  else ""),
                  peers(ctx.prov, step) or "—"]
    intro = [line for line in content if line.startswith("*")][:1] or [
        "*Rewritten by tools/bench_all.sh after each step it runs; a row it has not rerun keeps what it said.*"]
    lines = intro + [""] + table(PROVENANCE_HEADER, [rows[s] for s in STEPS if s in rows], ["---"] * 6) + [""]
    replace_block(path, PROVENANCE_BLOCK[0], lines)


# ---- commands ------------------------------------------------------------------------


def parse_inputs(pairs):
    inputs = {}
    for pair in pairs or []:
        if "=" not in pair:
            raise Failure(f"--input {pair}: expected KEY=FILE")
        key, value = pair.split("=", 1)
        inputs[key] = value
    return inputs


def command_list(args):
    for b in BLOCKS:
        print(f"{b.name:38} {b.doc:30} {b.step}")
    print(f"{PROVENANCE_BLOCK[0]:38} {PROVENANCE_BLOCK[1]:30} (every step)")


def command_check(args):
    root = pathlib.Path(args.root)
    names = {}
    for name, doc in [(b.name, b.doc) for b in BLOCKS] + [PROVENANCE_BLOCK]:
        find_block((root / doc).read_text(encoding="utf-8").split("\n"), name, root / doc)
        names.setdefault(doc, set()).add(name)
    for doc in sorted((root / "docs").glob("*.md")):
        for index, name, _ in markers(doc.read_text(encoding="utf-8").split("\n")):
            if name not in names.get(f"docs/{doc.name}", set()):
                raise Failure(f"{doc}:{index + 1}: block {name} is not one bench_docs.py renders in this file")
    print(f"bench_docs: the markers of {len(BLOCKS) + 1} blocks are in place")


def command_render(args):
    ctx = Context(args.root, read_provenance(args.prov), parse_inputs(args.input))
    print("\n".join(rendered(block_named(args.name), ctx, args.date)))


def command_replace(args):
    if args.content in (None, "-"):
        text = sys.stdin.read()
    else:
        text = pathlib.Path(args.content).read_text(encoding="utf-8")
    # A blank line last: a line right below a table would be read as one of its rows.
    replace_block(args.file, args.name, text.rstrip("\n").split("\n") + [""])


def command_update(args):
    if args.step not in STEPS:
        raise Failure(f"no step {args.step} (steps: {', '.join(STEPS)})")
    ctx = Context(args.root, read_provenance(args.prov), parse_inputs(args.input))
    for block in blocks_of(args.step):
        content = rendered(block, ctx, args.date)
        replace_block(ctx.root / block.doc, block.name, content)
        print(f"bench_docs: {block.doc}: block {block.name} rewritten")
    update_provenance_table(ctx, args.step, args.date, args.no_plots)
    print(f"bench_docs: {PROVENANCE_BLOCK[1]}: provenance of {args.step} rewritten")


def command_joints_results(args):
    raw = pathlib.Path(args.raw).read_text(encoding="utf-8")
    sys.stdout.write(joints_results(raw, read_provenance(args.prov), args.date))


def command_compare(args):
    ctx = Context(args.root, read_provenance(args.prov), parse_inputs(args.input))
    differing = 0
    for block in BLOCKS:
        try:
            new = block.render(ctx)
        except Failure as error:
            print(f"== {block.name}: not rendered: {error}")
            continue
        old = block_content(ctx.root / block.doc, block.name)
        old = [line for line in old if not (line.startswith("*") and line.endswith("*"))]
        while old and not old[0].strip():
            old.pop(0)
        while old and not old[-1].strip():
            old.pop()
        if old == new:
            print(f"== {block.name}: the same")
            continue
        differing += 1
        print(f"== {block.name}: differs")
        for line in difflib.unified_diff(old, new, "in the doc", "rendered", lineterm="", n=0):
            print("   " + line)
    return 1 if differing else 0


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    sub = parser.add_subparsers(dest="command", required=True)

    def with_root(p, prov=False):
        p.add_argument("--root", default=str(REPO), help="the tree holding docs/ and bench/ (default: the repository)")
        if prov:
            p.add_argument("--prov", help="provenance file written by tools/bench_all.sh")
            p.add_argument("--date", help="date of the run (default: the provenance file's)")
            p.add_argument("--input", action="append", metavar="KEY=FILE",
                           help="an output a block needs: compile_time=FILE")
        return p

    sub.add_parser("list").set_defaults(run=command_list)
    with_root(sub.add_parser("check")).set_defaults(run=command_check)
    p = with_root(sub.add_parser("render"), prov=True)
    p.add_argument("name")
    p.set_defaults(run=command_render)
    p = sub.add_parser("replace")
    p.add_argument("file")
    p.add_argument("name")
    p.add_argument("content", nargs="?")
    p.set_defaults(run=command_replace)
    p = with_root(sub.add_parser("update"), prov=True)
    p.add_argument("--step", required=True)
    p.add_argument("--no-plots", action="store_true", help="the step's PNGs were not redrawn")
    p.set_defaults(run=command_update)
    p = sub.add_parser("joints-results")
    p.add_argument("raw")
    p.add_argument("--prov", required=True)
    p.add_argument("--date")
    p.set_defaults(run=command_joints_results)
    with_root(sub.add_parser("compare"), prov=True).set_defaults(run=command_compare)

    args = parser.parse_args(argv)
    try:
        return args.run(args) or 0
    except Failure as error:
        print(f"bench_docs: {error}", file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main())
