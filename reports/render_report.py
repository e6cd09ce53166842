#!/usr/bin/env python3
"""Draws REPORT.md and charts/*.png of a corofem report folder from its JSON records alone.

Usage: render_report.py DIR [--blank-times]

Reads tables.json, speed_accuracy.json, stability.json, cache_profile.json and mpi_scaling.json
(each optional).
--blank-times prints every time, rate and date as "t" (the golden test of the report's format
compares text that does not depend on the machine's speed).
"""
import json
import math
import os
import sys
import tempfile

from render_since_snapshot import render_since_snapshot

try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import matplotlib.patches
    import matplotlib.ticker

    HAVE_MPL = True
except ImportError:  # REPORT.md is still written; it says the charts are missing
    HAVE_MPL = False

BLANK = False
TIME_KEYS = ("_ms", "tps", "elapsed_s", "speedup")


def load(folder, name):
    path = os.path.join(folder, name)
    if not os.path.exists(path):
        return None
    with open(path) as f:
        return json.load(f)


def num(value, digits=3):
    """A number with `digits` significant digits; '-' for missing."""
    if value is None or (isinstance(value, float) and not math.isfinite(value)):
        return "-"
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, int):
        return str(value)
    if value == 0:
        return "0"
    magnitude = abs(value)
    if magnitude >= 1e5 or magnitude < 1e-3:
        return f"{value:.{digits - 1}e}"
    return f"{value:.{digits}g}" if magnitude < 10 ** digits else f"{value:.0f}"


def t(value, digits=3):
    """A machine-dependent number (time, rate, ratio of times)."""
    return "t" if BLANK else num(value, digits)


def ratio(a, b):
    if a is None or b is None or b == 0:
        return None
    return a / b


def table(headers, rows):
    out = ["| " + " | ".join(headers) + " |", "|" + "---|" * len(headers)]
    out += ["| " + " | ".join(str(c) for c in row) + " |" for row in rows]
    return "\n".join(out) + "\n"


def save(fig, folder, name):
    charts = os.path.join(folder, "charts")
    os.makedirs(charts, exist_ok=True)
    path = os.path.join(charts, name)
    fd, tmp = tempfile.mkstemp(dir=charts, suffix=".png")
    os.close(fd)
    fig.savefig(tmp, dpi=90, metadata={"Software": None})
    plt.close(fig)
    os.chmod(tmp, 0o644)
    os.replace(tmp, path)
    return "charts/" + name


def context_lines(record):
    c = record.get("context", {})
    p = record.get("parameters", {})
    date = "t" if BLANK else c.get("date", "?")
    commit = "t" if BLANK else c.get("commit", "?")
    return (f"- {record.get('producer', '?')}, mode `{p.get('mode', '?')}`, {p.get('scenes', '')}; "
            f"commit `{commit}`, {c.get('compiler', '?')} `{c.get('flags', '?')}`, "
            f"{'t' if BLANK else c.get('cpu', '?')}, {c.get('threads_used', 1)} thread, {date}\n")


def failed(row):
    return not row.get("completed", False)


def failure_text(row):
    e = row.get("error", {})
    return f"**failed** ({e.get('kind', '?')}): {e.get('message', '?')}"


# ----------------------------------------------------------------------------------------------
def render_tables(tables, folder, md):
    s = tables.get("settings", {})
    md.append("## Tables 1 and 2: our timings beside the paper's\n\n")
    md.append(context_lines(tables))
    md.append(f"- Dynamic runs, implicit Euler dt = {s.get('dt')} s; each time is the median over "
              f"{s.get('measured_steps')} steps after {s.get('warmup_steps')} warm-up steps. "
              f"Accuracy: {s.get('accuracy')}. Energy-newton rotations, {s.get('galerkin', 'stream')} Galerkin update.\n")
    md.append("- The paper's rows (Core 2 Duo 6600, 2.4 GHz) are matched by size: 11k tets to the "
              "bunny, 34k to the horse, 67k to the dragon. Ratio = paper time / our time "
              "(above 1: we are faster).\n\n")
    rows, fails = [], []
    for r in tables.get("table1", []):
        if failed(r):
            fails.append(f"- {r['model']}: {failure_text(r)}\n")
            continue
        p = r.get("paper") or {}
        def cell(key):
            ours = r.get(key)
            if not p.get(key):
                return t(ours)
            return f"{t(ours)} ({num(p[key])}; {t(ratio(p[key], ours), 2)}x)"
        acc = r.get("solve_accuracy", {})
        rows.append([r["model"], r["tets"], r["vertices"], r["levels"], cell("rotate_ms"),
                     cell("assemble_ms"), cell("update_ms"), cell("update_naive_ms"), cell("solve_ms"),
                     f"{t(r['tps'])} ({num(p.get('tps'))}; {t(ratio(r['tps'], p.get('tps')), 2)}x)" if p else t(r["tps"]),
                     f"{num(acc.get('relative_residual_max'), 2)} / {num(acc.get('error_vs_cholmod_max'), 2)}",
                     t(r.get("cholmod_step_ms")), t(r.get("speedup_vs_cholmod"), 2)])
    md.append("### Table 1 (ms per step; in brackets the paper's value and paper/ours)\n\n")
    md.append(table(["model", "tets", "vertices", "levels", "rotate", "assemble", "update",
                     "update naive", "solve", "tps (paper; ours/paper)",
                     "residual / error vs CHOLMOD", "CHOLMOD step", "CHOLMOD / ours"], rows))
    md.extend(fails)
    md.append("\n")
    render_thread_table(tables, md)
    # Targets of the performance issue: 5x the paper's tps on one thread, 10x on all cores.
    md.append("### Performance targets\n\n")
    lines = []
    threads = tables.get("threads", 1)
    for r in tables.get("table1", []):
        if failed(r) or not r.get("paper"):
            continue
        one = (r.get("one_thread") or {}).get("tps", r["tps"])
        for label, tps, factor in (("one thread", one, 5), (f"{threads} threads", r["tps"], 10)):
            target = factor * r["paper"]["tps"]
            lines.append(f"- {r['model']}, {label}: {t(tps)} tps against the target {factor}x paper = "
                         f"{num(target)} tps: {'t' if BLANK else ('met' if tps >= target else 'not met')}\n")
        if r.get("paper_model") == "dragon":
            sp = r.get("speedup_vs_cholmod")
            lines.append(f"- {r['model']}: step {t(sp, 2)}x faster than the CHOLMOD-refactorization step "
                         f"(target 3x): {'t' if BLANK else ('met' if sp and sp >= 3 else 'not met')}\n")
    md.extend(lines or ["- (no row of the paper's sizes in this run)\n"])
    md.append("\n")
    # Table 2.
    rows = []
    t1 = {r["model"]: r for r in tables.get("table1", []) if not failed(r)}
    for r in tables.get("table2", []):
        if failed(r):
            rows.append([r["model"], failure_text(r), "", "", "", ""])
            continue
        energy = t1.get(r["model"], {}).get("tps")
        rows.append([r["model"], t(r["tps"]), num(r.get("paper_tps")), t(ratio(r["tps"], r.get("paper_tps")), 2),
                     t(energy), t(ratio(r["tps"], energy), 2)])
    md.append("### Table 2: polar decomposition with spatial smoothing\n\n")
    md.append(table(["model", "tps", "paper tps", "ours/paper", "energy-newton tps",
                     "polar+smoothing / energy-newton (paper about 2)"], rows))
    md.append("\n")
    rows = []
    for r in tables.get("small_strain", []):
        if failed(r):
            rows.append([r["model"], failure_text(r), "", "", ""])
            continue
        rows.append([r["model"], t(r["tps"]), t(r["corotated_tps"]), f"{100 * r['volume_change']:+.3f}%",
                     f"{100 * r['corotated_volume_change']:+.3f}%"])
    md.append("### Small strain against corotated (the paper's Figure 1)\n\n")
    md.append(table(["model", "small-strain tps", "corotated tps", "volume change, small strain",
                     "volume change, corotated"], rows))
    md.append("\n")
    rows = []
    # Models given with their coarse levels also run as a bare surface would (issue 36).
    bare = any("bare_surface_mgpcg_step_ms" in r for r in tables.get("jacobi_pcg", []))
    for r in tables.get("jacobi_pcg", []):
        stiffness = f"x{num(r.get('young_scale', 1))}"
        if failed(r):
            rows.append([r["model"], stiffness, failure_text(r)] + [""] * (7 if bare else 4))
            continue
        row = [r["model"], stiffness, t(r["step_ms"]), num(r["iterations"]), t(r.get("mgpcg_step_ms")),
               num(r.get("mgpcg_iterations")), t(ratio(r["step_ms"], r.get("mgpcg_step_ms")))]
        if bare:
            row += [t(r.get("bare_surface_mgpcg_step_ms")), num(r.get("bare_surface_mgpcg_iterations")),
                    t(ratio(r["step_ms"], r.get("bare_surface_mgpcg_step_ms")))]
        rows.append(row)
    md.append("### Jacobi-PCG at the same accuracy\n\n")
    md.append("- On each scene and on the same scene with every Young's modulus 100x. At the paper's soft "
              "materials and dt, M + dt^2 K is dominated by the mass matrix and well conditioned: CG with the "
              "block diagonal needs few iterations and its cheap steps tie the V-cycle's. Stiffer, the "
              "condition number grows with E, Jacobi-PCG's iterations with its square root, MG-PCG's barely.\n\n")
    header = ["model", "Young's modulus", "Jacobi-PCG step ms", "CG iterations", "MG-PCG step ms",
              "MG-PCG iterations", "Jacobi / MG-PCG"]
    if bare:
        md.append("- Bare surface: MG-PCG on the same scene with the coarse levels derived from the fine "
                  "surface alone (as a user's STL without levels runs), not the models' L1 and L2.\n\n")
        header += ["bare surface: MG-PCG step ms", "iterations", "Jacobi / MG-PCG"]
    md.append(table(header, rows))
    md.append("\n")
    render_multigrid_quality(tables, md)
    render_rival_solvers(tables, md)
    render_roofline(tables, folder, md)
    # Phase chart.
    ok = [r for r in tables.get("table1", []) if not failed(r)]
    if HAVE_MPL and ok:
        # Shares of the step on a linear axis (a log axis hid the small phases and bent the shares),
        # each bar's total ms written above it.
        phases = ["rotate_ms", "assemble_ms", "update_ms", "solve_ms"]
        fig, ax = plt.subplots(figsize=(8, 3.5))
        labels, columns = [], []
        for r in ok:
            labels += [r["model"], f"paper {r['paper_model']}" if r.get("paper") else ""]
            columns += [r, r.get("paper") or {}]
        totals = [sum(c.get(p) or 0 for p in phases) for c in columns]
        bottoms = [0.0] * len(columns)
        for phase in phases:
            shares = [100 * (c.get(phase) or 0) / total if total > 0 else 0
                      for c, total in zip(columns, totals)]
            ax.bar(range(len(columns)), shares, bottom=bottoms, label=phase[:-3])
            bottoms = [b + v for b, v in zip(bottoms, shares)]
        for i, total in enumerate(totals):
            if total > 0:
                ax.text(i, 101, f"{total:.3g} ms", ha="center", va="bottom", fontsize=6)
        ax.set_xticks(range(len(labels)))
        ax.set_xticklabels(labels, rotation=30, ha="right", fontsize=7)
        ax.set_ylabel("share of the step's phases (%)")
        ax.set_ylim(0, 112)
        ax.legend(fontsize=7, loc="lower right")
        ax.set_title("Step phases: ours beside the paper's, as shares of the step (total above)")
        fig.tight_layout()
        md.append(f"![phases]({save(fig, folder, 'table1_phases.png')})\n\n")
    # Verification summary.
    md.append("## Verification summary (oracle checks in the table runs)\n\n")
    rows = []
    for v in tables.get("verification", []):
        for c in v["checks"]:
            rows.append([v["model"], c["oracle"], c["quantity"], c["count"], num(c["largest"], 2)])
    md.append(table(["model", "oracle", "quantity", "compared", "largest"], rows))
    md.append("\nThe full gate suite (`ci/test`) checks more: see verify/.\n\n")


THREAD_PHASES = ["rotate", "assemble", "forces", "update", "solve", "checks", "system", "step"]


def render_thread_table(tables, md):
    """Table 1 on one thread and on all cores, phase by phase, with the paper's value."""
    rows = [r for r in tables.get("table1", []) if not failed(r) and r.get("one_thread") and r.get("phases_ms")]
    if not rows:
        return
    n = tables.get("threads", 1)
    md.append(f"### Table 1 on one thread and on {n} threads (ms per step; in brackets paper/ours)\n\n")
    md.append("- Every kernel writes each output from one thread and sums in a fixed order: both runs give "
              "the same bits (verify/threads_test.cpp). The smoother is l1 hybrid Gauss-Seidel in both, its "
              "domains set by each level's size, not by the threads (README, Multigrid).\n")
    if any(r.get("coarsest_factorization_in") == "solve" for r in rows):
        md.append(f"- At {n} threads MG-PCG factors the coarsest level (CHOLMOD, serial) and sets up the smoothers "
                  "at the start of the solve, on one thread beside the initial residual and the first V-cycle's "
                  "descent on the other (`MultigridSolver::defers_update`): there the update is the Galerkin "
                  "products alone and the solve carries the rest; the one-thread column keeps them in the update.\n")
    md.append("\n")
    out = []
    for r in rows:
        p = r.get("paper") or {}
        one, all_ = r["one_thread"], r["phases_ms"]
        for phase in THREAD_PHASES + ["tps"]:
            paper = p.get(f"{phase}_ms") if phase != "tps" else p.get("tps")
            def cell(v):
                if paper is None or v is None:
                    return t(v)
                return f"{t(v)} ({t(v / paper if phase == 'tps' else paper / v, 2)}x)"
            speedup = ratio(all_.get(phase), one.get(phase)) if phase == "tps" else ratio(one.get(phase), all_.get(phase))
            out.append([r["model"], phase, num(paper), cell(one.get(phase)), cell(all_.get(phase)), t(speedup, 2)])
    md.append(table(["model", "phase", "paper", "one thread", f"{n} threads", f"{n} threads / one"], out))
    md.append("\n")


def render_rival_solvers(tables, md):
    """The algebraic multigrid users would pick instead, at the same tolerance, beside MG-PCG."""
    rows = []
    for r in tables.get("rival_solvers", []):
        solver = r.get("solver", "") + (" (setup reused)" if r.get("setup_reuse") else "")
        if failed(r):
            rows.append([r["model"], solver, failure_text(r), "", "", "", "", ""])
            continue
        rows.append([r["model"], solver, t(r["step_ms"]), t(r["update_ms"]), t(r["solve_ms"]),
                     num(r["iterations"]), t(r.get("mgpcg_step_ms")), t(r.get("step_over_mgpcg"), 2)])
    if not rows:
        return
    md.append("### The solvers users would pick instead (PETSc GAMG, hypre BoomerAMG, PETSc PCMG) at the same accuracy\n\n")
    md.append("- CG preconditioned by PETSc's smoothed aggregation (rigid-body near null space), hypre's "
              "BoomerAMG (systems AMG, strong threshold 0.5) or PETSc's geometric multigrid PCMG on our own "
              "hierarchy (our interpolation, PETSc's MatPtAP coarse operators, Chebyshev-Jacobi smoothing, LU "
              "coarsest), to the same relative residual; their setup runs every step (the matrix changes) and "
              "is timed as the update, as ours is. \"Setup reused\": GAMG keeps its first interpolation and "
              "recomputes the coarse operators; BoomerAMG keeps its whole first hierarchy.\n\n")
    md.append(table(["model", "solver", "step ms", "update (setup) ms", "solve ms", "CG iterations",
                     "MG-PCG step ms", "step / MG-PCG step"], rows))
    md.append("\n")
    rows = []
    for r in tables.get("table1", []):
        g = None if failed(r) else r.get("galerkin_vs_matptap")
        if g:
            rows.append([r["model"], g.get("galerkin", ""), t(g.get("galerkin_one_thread_ms")), t(g.get("galerkin_ms")),
                         t(g.get("matptap_ms")), t(g.get("matptap_over_galerkin_one_thread"), 2)])
    if rows:
        md.append("The Galerkin update alone against PETSc's MatPtAP in its numeric-reuse mode (every coarse level "
                  "from the run's last fine matrix, A's values copied in each time; median of 5 after the symbolic "
                  "phase; PETSc on one thread), ours (the run's method) as a mean per update of the run:\n\n")
        md.append(table(["model", "ours", "ours ms (one thread)", f"ours ms ({tables.get('threads', 1)} threads)",
                         "MatPtAP ms", "MatPtAP / ours (one thread)"], rows))
        md.append("\n")


ROOFLINE_PHASES = ["checks", "rotate", "assemble", "forces", "system", "update", "solve"]


def render_roofline(tables, folder, md):
    """Each phase's measured time against its floor: compulsory bytes / STREAM bandwidth."""
    rows = [r for r in tables.get("table1", []) if not failed(r) and r.get("roofline")]
    if not rows:
        return
    md.append("### Roofline: each phase of the step against its floor\n\n")
    md.append(f"- Floor = the larger of the bytes a phase must move per step (every array it touches, once; "
              f"counted from the data structures, see lib/report/step_roofline.hpp) over the STREAM triad "
              f"bandwidth and its flops over the dense-product rate, both measured in this run "
              f"({t(tables.get('stream_triad_GBps'))} GB/s, {t(tables.get('dense_gflops'))} Gflop/s). "
              f"Over floor = measured / floor (1 = at the machine's limit). Where the working set fits in the "
              f"caches a phase can run below its floor.\n\n")
    out = []
    for r in rows:
        rl = r["roofline"]
        for phase in ROOFLINE_PHASES:
            p = rl["phases"].get(phase)
            if not p:
                continue
            out.append([r["model"], phase, num(p["bytes"] / 1e6, 3), num(p["flops"] / 1e6, 3),
                        num(p["flops_per_byte"], 2), p.get("bound", "memory"), t(p["floor_ms"]),
                        t(p.get("measured_ms")), t(p.get("over_floor"), 2)])
            if phase == "update":  # its parts, timed inside the multigrid solver (means per update)
                for part, q in (rl.get("update_parts") or {}).items():
                    out.append([r["model"], f"&nbsp;&nbsp;update: {part}", num(q["bytes"] / 1e6, 3),
                                num(q["flops"] / 1e6, 3), num(q["flops_per_byte"], 2), q.get("bound", "memory"),
                                t(q["floor_ms"]), t(q.get("measured_ms")), t(q.get("over_floor"), 2)])
        out.append([r["model"], "**step**", num(sum(p["bytes"] for p in rl["phases"].values()) / 1e6, 3),
                    num(sum(p["flops"] for p in rl["phases"].values()) / 1e6, 3), "", "", t(rl["floor_ms"]),
                    t(rl.get("step_ms")), t(rl.get("over_floor"), 2)])
        out.append([r["model"], "outside every phase", "", "", "", "", "", t(rl.get("untimed_ms")), ""])
    md.append(table(["model", "phase", "MB per step", "Mflop per step", "flop/byte", "bound", "floor ms",
                     "measured ms", "over floor"], out))
    md.append("\n")
    if not HAVE_MPL:
        return
    fig, axes = plt.subplots(1, len(rows), figsize=(max(6.5, 3.4 * len(rows) + 0.6), 3.6), squeeze=False)
    for ax, r in zip(axes[0], rows):
        phases = [p for p in ROOFLINE_PHASES if p in r["roofline"]["phases"]]
        data = r["roofline"]["phases"]
        y = list(range(len(phases)))
        one = ((r.get("one_thread") or {}).get("roofline") or {}).get("phases")
        threads = tables.get("threads", 1)
        if one and threads > 1:  # three bars: floor, one thread, all threads
            ax.barh([v - 0.27 for v in y], [max(data[p]["floor_ms"], 1e-6) for p in phases], height=0.27,
                    color="#bbbbbb", label=f"floor at {threads} threads")
            ax.barh(y, [max(one.get(p, {}).get("measured_ms") or 0, 1e-6) for p in phases], height=0.27,
                    color="#dd8452", label="measured, one thread")
            ax.barh([v + 0.27 for v in y], [max(data[p].get("measured_ms") or 0, 1e-6) for p in phases],
                    height=0.27, color="#4c72b0", label=f"measured, {threads} threads")
        else:
            ax.barh([v + 0.2 for v in y], [max(data[p].get("measured_ms") or 0, 1e-6) for p in phases], height=0.4,
                    color="#4c72b0", label="measured")
            ax.barh([v - 0.2 for v in y], [max(data[p]["floor_ms"], 1e-6) for p in phases], height=0.4,
                    color="#bbbbbb", label="floor: max(bytes / STREAM, flops / dense rate)")
        ax.set_yticks(y)
        ax.set_yticklabels(phases, fontsize=8)
        ax.invert_yaxis()
        ax.set_xscale("log")
        ax.set_xlabel("ms per step", fontsize=8)
        ax.tick_params(axis="x", labelsize=8)
        ax.set_title(f"{r['model']}: {t(r['roofline'].get('over_floor'), 2)}x over floor", fontsize=9)
    handles, labels = axes[0][0].get_legend_handles_labels()
    fig.legend(handles, labels, fontsize=8, loc="lower center", ncol=min(3, len(labels)), frameon=False)
    threads = tables.get("threads", tables.get("context", {}).get("threads_used", 1))
    fig.suptitle(f"Step phases against their floor (STREAM {t(tables.get('stream_triad_GBps'))} GB/s, dense "
                 f"{t(tables.get('dense_gflops'))} Gflop/s, at {threads} thread{'s' if threads != 1 else ''})",
                 fontsize=10)
    fig.tight_layout(rect=(0, 0.07, 1, 1))
    md.append(f"![roofline]({save(fig, folder, 'table1_roofline.png')})\n\n")


def render_size_independence(tables, md):
    """The quadruped's re-meshed rows across its sizes (11k to 270k in the full report), as the
    record sums them up: the textbook property the paper claims is that rho and the iterations do
    not grow with the mesh. Once with the coarse meshes at twice the size per level (the default),
    once at a fixed vertex ratio per level (`analysis.coarsening`)."""
    for key in ("size_independence", "size_independence_fixed_ratio"):
        si = tables.get(key)
        if not si:
            continue
        sizes = si["sizes"]
        rho = [r["rho"] for r in sizes]
        its = [r["mgpcg_iterations"] for r in sizes]
        targets = si["targets"]
        levels = (f"{num(si['coarsening'])}x fewer vertices per level" if si.get("coarsening")
                  else "coarse meshes at twice the size per level")
        md.append(f"Size independence, the {si['model']} at {', '.join(r['model'].split('-', 1)[1] for r in sizes)} "
                  f"tets, {levels}: rho {num(min(rho), 2)} to {num(max(rho), 2)} (spread {num(si['rho_spread'], 2)}; "
                  f"target at most {num(targets['rho_spread'])}), MG-PCG iterations {num(min(its))} to {num(max(its))} "
                  f"(spread {num(si['iterations_spread'])}; target at most {num(targets['iterations_spread'])}).\n\n")


def hierarchy_label(r):
    """A multigrid row's hierarchy as both of its tables name it: the builder, whether its coarse
    levels came from the bare surface, and its coarsening if one was asked for."""
    label = r["hierarchy"] + (", bare surface" if r.get("coarse_meshes") == "derived from the bare surface" else "")
    if r.get("coarsening"):
        label += f", {num(r['coarsening'])}x per level"
    return label


def render_multigrid_quality(tables, md):
    rows = []
    for r in tables.get("multigrid", []):
        if failed(r):
            rows.append([r["model"], failure_text(r)] + [""] * 10)
            continue
        rows.append([r["model"], hierarchy_label(r), r["levels"], " / ".join(str(v) for v in r["level_vertices"]),
                     num(r["operator_complexity"], 3), num(r["rho"], 2), num(r["vcycles"]),
                     num(r["mgpcg_iterations"]), t(r["setup_ms"]), t(r["update_ms"]), t(r["solve_ms"]),
                     t(r["step_ms"])])
    if not rows:
        return
    md.append("### Multigrid quality: the paper's re-meshed hierarchy against the covering lattice\n\n")
    md.append("- rho: median over the steps of the stationary V(1,1) cycle's mean residual reduction per "
              "cycle; V-cycles and MG-PCG iterations: median per step to the table's tolerance. Setup: "
              "coarse meshing (gmsh) and transfers, once per run; update, solve and step: ms per step of "
              "the MG-PCG run. Operator complexity: blocks of all levels / blocks of the fine matrix.\n\n")
    md.append(table(["model", "hierarchy", "levels", "vertices per level", "operator complexity", "rho",
                     "V-cycles", "MG-PCG iterations", "setup ms", "update ms", "solve ms", "step ms"], rows))
    md.append("\n")
    render_size_independence(tables, md)
    parts = ["fine_smooth", "fine_residual", "fine_transfer", "coarse_levels", "coarsest"]
    rows = []
    for r in tables.get("multigrid", []):
        if failed(r) or not r.get("solve_parts_ms"):
            continue
        sp, up = r["solve_parts_ms"], r.get("update_parts_ms") or {}
        outer = sum(sp.get(p, 0.0) for p in parts)
        rows.append([r["model"], hierarchy_label(r)] + [t(sp.get(p)) for p in parts] +
                    [t(r["solve_ms"] - outer) if r.get("solve_ms") is not None else "-"] +
                    [t(up.get(p)) for p in ("galerkin", "smoothers", "coarsest")])
    if rows:
        deferred = any(r.get("coarsest_factorization_in") == "solve" for r in tables.get("multigrid", []))
        md.append("Where MG-PCG's time goes (ms per step; solve parts are means over the run's solves, the "
                  "outer iteration is CG's own product and vector updates: the median solve less the parts" +
                  ("; the solve also holds the coarsest factorization, run beside its first descent, so the "
                   "remainder includes what of it the descent did not hide" if deferred else "") + "):\n\n")
        md.append(table(["model", "hierarchy", "fine smoothing", "fine residual", "fine transfers",
                         "coarser levels", "coarsest solves", "outer CG", "update: Galerkin",
                         "update: smoothers", "update: coarsest factorization"], rows))
        md.append("\n")


# ----------------------------------------------------------------------------------------------
def short_label(p):
    """A setting's label without the sweep's own key and the hierarchy (shown by the marker)."""
    if p["sweep"] == "resolution":
        return p["label"]
    words = p["label"].split()
    key = [w.split("=", 1)[1] for w in words if w.startswith(("solver=", "rotation="))]
    rest = [w for w in words if not w.startswith(("solver=", "rotation=", "hierarchy="))]
    return " ".join(key + rest)


def draw_speed_accuracy(sa, scene, folder):
    """One panel per sweep: every completed point, the Pareto front dashed with only its points
    labelled, the target error as a line and the cheapest setting meeting it ringed."""
    sweeps = ["solver", "rotation", "resolution"]
    fig, axes = plt.subplots(1, len(sweeps), figsize=(13, 5.2))
    for ax, sweep in zip(axes, sweeps):
        sel = [p for p in scene["points"] if p["sweep"] == sweep and not failed(p)
               and p.get("rel_error") and not p.get("is_reference")]
        groups = [("re-meshed hierarchy", "o", [p for p in sel if "hierarchy=lattice" not in p["label"]]),
                  ("lattice hierarchy", "D", [p for p in sel if "hierarchy=lattice" in p["label"]])]
        if sweep != "solver":
            groups = [(sweep, "o" if sweep == "rotation" else "^", sel)]
        for name, marker, group in groups:
            if group:
                ax.scatter([p["time_per_step_ms"] for p in group], [p["rel_error"] for p in group],
                           marker=marker, s=30, label=name,
                           facecolors="none" if marker == "D" else None,
                           edgecolors="C1" if marker == "D" else None)
        front = sorted([p for p in sel if p.get("pareto")], key=lambda p: p["time_per_step_ms"])
        if len(front) > 1:
            ax.plot([p["time_per_step_ms"] for p in front], [p["rel_error"] for p in front],
                    linestyle="--", linewidth=1, color="0.4", label="Pareto front")
        for p in front:
            ax.annotate(short_label(p), (p["time_per_step_ms"], p["rel_error"]), fontsize=8,
                        xytext=(4, 3), textcoords="offset points")
        target = sa.get("targets", {}).get(sweep)
        if target:
            ax.axhline(target, color="C3", linestyle=":", linewidth=1.2, label=f"target {num(target)}")
        best = (scene.get("cheapest_meeting_target") or {}).get(sweep)
        if best:
            ax.scatter([best["time_per_step_ms"]], [best["rel_error"]], s=160, facecolors="none",
                       edgecolors="C3", linewidths=1.5, label="cheapest meeting the target")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("time per step (ms)", fontsize=9)
        ax.set_ylabel(f"{sweep} error (relative)", fontsize=9)
        ax.tick_params(labelsize=8)
        # Ticks at 1, 2, 5 per decade on short ranges, per decade on long ones; no minor labels.
        for axis, (lo, hi) in ((ax.xaxis, ax.get_xlim()), (ax.yaxis, ax.get_ylim())):
            subs = (1.0, 2.0, 5.0) if lo > 0 and math.log10(hi / lo) < 2.5 else (1.0,)
            axis.set_major_locator(matplotlib.ticker.LogLocator(base=10, subs=subs))
            axis.set_major_formatter(matplotlib.ticker.FuncFormatter(lambda v, _: f"{v:g}"))
            axis.set_minor_formatter(matplotlib.ticker.NullFormatter())
        ax.set_title(f"{sweep} sweep", fontsize=10)
        if sel:
            ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=2)
    fig.suptitle(f"{scene['scene']}: speed against accuracy", fontsize=11)
    fig.tight_layout()
    return save(fig, folder, "speed_accuracy_" + scene["scene"] + ".png")


def render_speed_accuracy(sa, folder, md):
    md.append("## Speed against accuracy\n\n")
    md.append(context_lines(sa))
    for key, text in sa.get("error_definitions", {}).items():
        md.append(f"- {key} error: {text}; target {num(sa['targets'][key])}\n")
    md.append("\n")
    for scene in sa.get("scenes", []):
        md.append(f"### {scene['scene']}\n\n")
        if failed(scene):
            md.append(failure_text(scene) + "\n\n")
            continue
        pts = scene["points"]
        if HAVE_MPL:
            md.append(f"![{scene['scene']}]({draw_speed_accuracy(sa, scene, folder)})\n\n")
        rows = []
        for p in pts:
            if failed(p):
                rows.append([p["sweep"], p["label"], failure_text(p), "", "", ""])
                continue
            rows.append([p["sweep"], p["label"], p.get("tets", "-"), t(p["time_per_step_ms"]),
                         "reference" if p.get("is_reference") else num(p.get("rel_error"), 2),
                         "yes" if p.get("pareto") else ""])
        md.append(table(["sweep", "setting", "tets", "ms per step", "relative error", "Pareto"], rows))
        md.append("\nCheapest setting meeting each target (model no more than the scene needs):\n\n")
        for sweep, best in scene.get("cheapest_meeting_target", {}).items():
            if best is None:
                md.append(f"- {sweep}: none of the settings met {num(sa['targets'][sweep])}\n")
            else:
                md.append(f"- {sweep}: `{best['label']}`, {t(best['time_per_step_ms'])} ms per step, "
                          f"error {num(best['rel_error'], 2)}\n")
        md.append("\n")


# ----------------------------------------------------------------------------------------------
def render_cache(cache, md):
    md.append("## Cache profiles\n\n")
    if cache is None:
        md.append("Not run in this report (ci/report runs bench/cache_profile.sh).\n\n")
        return
    md.append(f"- {cache.get('producer')}: {cache.get('tool_note')}; model `{cache.get('model')}`, "
              f"{cache.get('updates')} repetitions, {cache.get('fine_blocks')} blocks of K.\n\n")
    rows = []
    for r in cache.get("results", []):
        rows.append([r["method"], r.get("unit", "Galerkin update"), num(r["d1_misses_per_update"]),
                     num(r["ll_misses_per_update"]), num(r["d1_misses_per_k_block"]),
                     num(r["ll_misses_per_k_block"]), num(r["instructions_per_update"])])
    md.append(table(["method", "per", "D1 misses", "LL misses", "D1 per K block", "LL per K block",
                     "instructions"], rows))
    md.append("\n")


# ----------------------------------------------------------------------------------------------
def render_mpi_scaling(scaling, md):
    md.append("## Beyond one machine: MPI ranks\n\n")
    if scaling is None:
        md.append("Not run in this report (ci/report runs bench/mpi_scaling.py).\n\n")
        return
    p = scaling.get("parameters", {})
    ranks = p.get("ranks", [1, 2])
    md.append(f"- {scaling.get('producer')}: `mpirun -np R corofem run` on cantilever bars (dynamic, "
              f"tolerance {num(p.get('tolerance'))}), {p.get('steps')} steps, median of {p.get('repeats')} "
              f"runs; ms per step, setup excluded. {scaling.get('note', '')}.\n")
    element = scaling.get("element_phases")
    if element:  # records since the mesh is distributed
        md.append(f"- `element` is {', '.join(element)} (each rank its part of the mesh), `solver` "
                  f"{', '.join(scaling.get('solver_phases', []))} (PETSc across the ranks); memory is the "
                  "largest rank's peak RSS, visits its held tets over the mesh's.\n\n")
    else:  # older records: the element work was replicated
        md.append("- `distributed` is the update plus the solve, the phases the ranks share; the rest of "
                  "the step is replicated on every rank.\n\n")

    def find(solver, study, count):
        for r in scaling.get("runs", []):
            workers = r["threads"] if solver == "mgpcg" else r["ranks"]
            if r["solver"] == solver and workers == count and (r["study"] == study or count == ranks[0]):
                return r
        return None

    solvers = []
    for r in scaling.get("runs", []):
        if r["solver"] not in solvers:
            solvers.append(r["solver"])
    label = {s: (f"{s} (threads)" if s == "mgpcg" else f"{s} (ranks)") for s in solvers}
    part = "element" if element else "distributed"
    for study, title, measure in (("strong", "Strong scaling (one bar)", "speedup"),
                                  ("weak", "Weak scaling (elements in proportion to the ranks)", "efficiency")):
        md.append(f"{title}:\n\n")
        rows = []
        for s in solvers:
            base = find(s, study, ranks[0])
            for count in ranks[1:]:
                r = find(s, study, count)
                if base is None or r is None:
                    continue
                b, m = base["ms_per_step"], r["ms_per_step"]
                over = " (oversubscribed)" if r.get("oversubscribed") else ""
                row = [label[s], f"{base['tets']} / {r['tets']}", f"{ranks[0]} / {count}{over}",
                       f"{t(b['step'])} / {t(m['step'])}", t(ratio(b["step"], m["step"]), 2),
                       f"{t(b.get(part))} / {t(m.get(part))}", t(ratio(b.get(part), m.get(part)), 2)]
                if element:
                    row += [f"{t(b.get('solver'))} / {t(m.get('solver'))}",
                            f"{t(base['peak_rss_kb_per_rank'] / 1024)} / {t(r['peak_rss_kb_per_rank'] / 1024)}",
                            t(ratio(r["peak_rss_kb_per_rank"], base["peak_rss_kb_per_rank"]), 2),
                            num(r.get("element_visits_fraction"), 3)]
                row.append(f"{num(base['linear_iterations_per_step'], 3)} / {num(r['linear_iterations_per_step'], 3)}")
                rows.append(row)
        header = ["solver", "tets", "ranks or threads", "step ms", f"step {measure}", f"{part} ms",
                  f"{part} {measure}"]
        if element:
            header += ["solver ms", "MB per rank", "memory ratio", "visits per rank"]
        md.append(table(header + ["iterations per step"], rows))
        md.append("\n")


# ----------------------------------------------------------------------------------------------
STATUS_COLOURS = {"stable": "#8fd18f", "motion": "#9cc3e6", "flutter": "#f2c14e", "stuck": "#b48ede",
                  "diverged": "#e76f6f"}


def status_cause(r):
    """One short line on why a run is not stable (empty when it is)."""
    cause = f"; cause: {r['cause']}" if r.get("cause") else ""
    if r["status"] in ("flutter", "motion"):
        return f"RMS {num(r.get('flutter_rms_rad'), 2)} rad/step{cause}"
    if r["status"] == "diverged":
        return f"step {r.get('diverged_step')}: {(r.get('divergence') or {}).get('kind', 'diverged')}{cause}"
    if r["status"] == "stuck":
        return f"{r.get('inverted_final')} inverted at the end{cause}"
    return f"{r['inverted_final']} inverted" if r.get("inverted_final") else ""


def run_setting(r):
    """The integrator and step of a run ("linear-implicit, dt 0.01"); old records had only the first."""
    return f"{r.get('integrator', 'linear-implicit')}, dt {r.get('dt', '')}"


def draw_status_matrix(runs, scenes, methods, folder):
    """(Scene, integrator, step) x method grid coloured by status, each cell with its cause when not
    stable."""
    rows = list(dict.fromkeys((r["scene"], run_setting(r)) for r in runs))
    fig, ax = plt.subplots(figsize=(1.6 * len(methods) + 3.2, 0.62 * len(rows) + 1.2))
    for i, (scene, setting) in enumerate(rows):
        for j, method in enumerate(methods):
            r = next((r for r in runs if r["scene"] == scene and run_setting(r) == setting and r["method"] == method),
                     None)
            status = r["status"] if r else "not run"
            ax.add_patch(matplotlib.patches.Rectangle((j, i), 1, 1, facecolor=STATUS_COLOURS.get(status, "white"),
                                                      edgecolor="white", linewidth=2))
            cause = status_cause(r).replace("; ", "\n") if r else "(nothing to attribute)"
            ax.text(j + 0.5, i + 0.5, status + ("\n" + cause if cause else ""), ha="center", va="center",
                    fontsize=8)
    ax.set_xlim(0, len(methods))
    ax.set_ylim(len(rows), 0)
    ax.set_xticks([j + 0.5 for j in range(len(methods))])
    ax.set_xticklabels(methods, fontsize=8, rotation=20, ha="right")
    ax.set_yticks([i + 0.5 for i in range(len(rows))])
    ax.set_yticklabels([f"{scene}\n{setting}" for scene, setting in rows], fontsize=8)
    ax.tick_params(length=0)
    for side in ax.spines.values():
        side.set_visible(False)
    ax.set_title("Stability: status by scene, integrator and step (rows) and rotation method (columns)",
                 fontsize=10)
    fig.tight_layout()
    return save(fig, folder, "stability_status.png")


POSE_LOG_RANGE = (-6, 0)  # log10 rad per step: still (1e-6) to a full radian


def shaded_colours(vertices, triangles, values):
    """Face colours: the colour map at the face's largest vertex value, darkened by the angle of
    its outward normal to a light from the viewer's upper left (Lambert, with an ambient floor)."""
    cmap = matplotlib.colormaps["viridis"]
    light = [-0.4, -0.5, 0.77]
    colours = []
    for a, b, c in triangles:
        pa, pb, pc = vertices[a], vertices[b], vertices[c]
        u = [pb[k] - pa[k] for k in range(3)]
        v = [pc[k] - pa[k] for k in range(3)]
        n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
        length = math.sqrt(sum(x * x for x in n)) or 1.0
        lambert = max(0.0, sum(n[k] * light[k] for k in range(3)) / length)
        value = max(values[a], values[b], values[c], 10.0 ** POSE_LOG_RANGE[0])
        scaled = (math.log10(value) - POSE_LOG_RANGE[0]) / (POSE_LOG_RANGE[1] - POSE_LOG_RANGE[0])
        r, g, b_, _ = cmap(min(1.0, max(0.0, scaled)))
        shade = 0.35 + 0.65 * lambert
        colours.append((r * shade, g * shade, b_ * shade, 1.0))
    return colours


def draw_poses(st, frames, integrator, folder):
    """One row per scene, one column per method: the run's boundary at the end as shaded triangles
    coloured by the largest rotation change per step while held, the rest shape faint beside it,
    and the run's status on the panel."""
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    poses = [p for p in frames.get("poses", []) if p.get("integrator", "linear-implicit") == integrator]
    surfaces = frames.get("surfaces", {})
    scenes = [s for s in dict.fromkeys(p["scene"] for p in poses) if s in surfaces]
    methods = list(dict.fromkeys(r["method"] for r in st.get("runs", [])))
    if not scenes:
        return None
    width = 2.0 * len(methods) + 1.0
    height = 2.0 * len(scenes) + 0.7
    fig = plt.figure(figsize=(width, height))
    grid = fig.add_gridspec(len(scenes), len(methods) + 1, width_ratios=[1] * len(methods) + [0.08],
                            left=0.25 / width, right=1 - 0.9 / width, top=1 - 0.5 / height, bottom=0.1 / height, wspace=0.02, hspace=0.12)
    for i, scene in enumerate(scenes):
        rest, triangles = surfaces[scene]["rest_points"], surfaces[scene]["triangles"]
        for j, method in enumerate(methods):
            pose = next((p for p in poses if p["scene"] == scene and p["method"] == method), None)
            ax = fig.add_subplot(grid[i, j], projection="3d")
            ax.set_axis_off()
            if j == 0:
                fig.text(0.12 / width, 1 - (0.5 + 2.0 * (i + 0.5)) / height, scene, rotation=90, va="center",
                         ha="center", fontsize=8)
            if i == 0:
                ax.set_title(method, fontsize=8, pad=0)
            if pose is None:
                run = next((r for r in st.get("runs", []) if r["scene"] == scene and r["method"] == method
                            and r.get("integrator", "linear-implicit") == integrator
                            and r.get("dt", first_dt(st)) == first_dt(st)), None)
                why = f"{run['status']} at step {run.get('diverged_step')}" if run and run.get("diverged_step") \
                    else (run["status"] if run else "not run")
                ax.text2D(0.5, 0.5, why + "\nno final pose", transform=ax.transAxes, ha="center", va="center",
                          fontsize=8, bbox=dict(facecolor=STATUS_COLOURS.get(run["status"] if run else "", "white"),
                                                edgecolor="none", pad=2))
                continue
            points = pose["points"]
            # The rest shape beside the pose, shifted across the narrower horizontal extent.
            extent = [max(p[k] for p in points + rest) - min(p[k] for p in points + rest) for k in range(3)]
            side = 0 if extent[0] < extent[1] else 1
            shift = (max(p[side] for p in points) - min(p[side] for p in rest)) + 0.15 * extent[side] + 1e-9
            rest_shifted = [[p[k] + (shift if k == side else 0.0) for k in range(3)] for p in rest]
            ax.add_collection3d(Poly3DCollection([[rest_shifted[k] for k in t] for t in triangles],
                                                 facecolors=(0.6, 0.6, 0.6, 0.15), edgecolors="none"))
            ax.add_collection3d(Poly3DCollection([[points[k] for k in t] for t in triangles],
                                                 facecolors=shaded_colours(points, triangles,
                                                                           pose["rotation_change_max_rad"]),
                                                 edgecolors="none"))
            every = points + rest_shifted
            low = [min(p[k] for p in every) for k in range(3)]
            high = [max(p[k] for p in every) for k in range(3)]
            span = [max(high[k] - low[k], 1e-3 * max(high[m] - low[m] for m in range(3))) for k in range(3)]
            ax.set_xlim(low[0], low[0] + span[0])
            ax.set_ylim(low[1], low[1] + span[1])
            ax.set_zlim(low[2], low[2] + span[2])
            try:  # true proportions, zoomed to fill the panel (matplotlib >= 3.3; zoom >= 3.6)
                ax.set_box_aspect(span, zoom=1.2)
            except TypeError:
                ax.set_box_aspect(span)
            ax.view_init(elev=20, azim=-60)
            status = pose.get("status", "")
            ax.text2D(0.02, 0.97, status, transform=ax.transAxes, ha="left", va="top", fontsize=8,
                      color="black", bbox=dict(facecolor=STATUS_COLOURS.get(status, "white"), edgecolor="none",
                                               pad=1.5))
    bar = fig.add_subplot(grid[:, -1])
    mappable = matplotlib.cm.ScalarMappable(norm=matplotlib.colors.Normalize(*POSE_LOG_RANGE), cmap="viridis")
    colourbar = fig.colorbar(mappable, cax=bar)
    colourbar.set_label("largest rotation change per step\nwhile held (log10 rad)", fontsize=8)
    colourbar.ax.tick_params(labelsize=8)
    fig.suptitle(f"Final poses under {integrator} Euler, dt {first_dt(st)} s (grey: the rest shape)", fontsize=10)
    return save(fig, folder, f"stability_poses_{integrator}.png")


def first_dt(st):
    return next(iter(st.get("scenes", {}).values()), {}).get("analysis", {}).get("dt", "")



def render_verdicts(st, md):
    """The verdict on the paper's claim, method by method, with its cause."""
    verdicts = st.get("verdicts")
    if not verdicts:
        return
    md.append("\n**Verdict on the paper's claim (stable corotation), method by method.** A run that is not "
              "stable is caused by the *integrator* when the same method is stable under the other integrator "
              "(linearly implicit Euler, or fully implicit Euler by Newton with the consistent tangent) at "
              "that step or at the smaller step. Where none is, the same method under Newton at dt/4 (the "
              "refined reference) decides: the *method* when it diverges or stays inverted there too, the "
              "*scene* when it shows the same motion (at least half the rate in rad/s: physical motion, status "
              "*motion*, unless another method settles the scene), the *integrator* when the flutter converges "
              "away or Newton cannot solve the small steps; where no method settles a scene under either integrator at any "
              "step, its failures are the *scene*'s unless confirmed as a method's (a blow-up, a body left inverted). "
              "Newton is robust: a line search on the incremental potential where the force has one "
              "(polar, polar-fixed), steps cut to dt/2 where it does not converge. "
              "Asymmetry: median over elements of |J - J^T| / |J| of the element force Jacobian at the end "
              "(0: a conservative force). Energy error: the largest energy created over the hold, relative to "
              "the hold's energy (E + damping - work of the loads; backward Euler with a conservative force "
              "keeps it at 0).\n\n")
    runs = st.get("runs", [])
    rows = []
    for method, v in verdicts.items():
        mine = [r for r in runs if r["method"] == method]
        asym = [r["asymmetry"] for r in mine if isinstance(r.get("asymmetry"), (int, float))]
        energy = [r["energy_error"] for r in mine if isinstance(r.get("energy_error"), (int, float))]
        failures = "; ".join(f"{f['scene']} ({f['integrator']}, dt {f['dt']}): {f['status']}, cause "
                             f"{f.get('cause') or 'undetermined'}" for f in v.get("not_stable", []))
        rows.append([method, v.get("verdict", ""), f"{len(v.get('not_stable', []))} of {v.get('runs')}",
                     num(max(asym), 2) if asym else "", num(max(energy), 2) if energy else "", failures])
    md.append(table(["method", "verdict", "not stable", "largest asymmetry", "largest energy error",
                     "runs not stable and their cause"], rows))
    md.append("\n")


def render_stability(st, frames, folder, md):
    """`frames` (stability_frames.json: each run's per-step series, in the order of the runs, and
    the final poses) draws the charts; without it (the published snapshot keeps only the records of
    at most 200 kB) the tables alone."""
    md.append("## Stability where methods fail\n\n")
    md.append(context_lines(st))
    render_verdicts(st, md)
    th = st.get("thresholds", {})
    first = next(iter(st.get("scenes", {}).values()), {}).get("analysis", {})
    damping = first.get("rayleigh", {})
    md.append(f"- Load for {st.get('ramp_steps')} steps, hold for {st.get('hold_steps')} (dt {first.get('dt')} s, "
              f"Rayleigh damping alpha {damping.get('alpha', 0)}/s, beta {damping.get('beta', 0)} s, "
              f"{first.get('solver')} solves, `{st.get('size')}` meshes). Flutter is "
              f"measured over the {th.get('window')}.\n")
    md.append(f"- Status: {th.get('statuses')}. Thresholds: largest change {th.get('flutter_max_rad')} rad "
              f"per step, RMS {th.get('flutter_rms_rad')} rad per step. Why these: with the loads constant, "
              f"a settling body's elements turn by well under 1e-3 rad per step (see the energy-exact "
              f"runs, the exact minimizer); a change 100x larger, every step, is a rotation field that "
              f"jumps, not a body that moves.\n\n")
    runs = st.get("runs", [])
    scenes = list(dict.fromkeys(r["scene"] for r in runs))
    methods = list(dict.fromkeys(r["method"] for r in runs))
    rows = []
    for r in runs:
        why = r.get("cause_detail") or (r.get("divergence") or {}).get("message", "")
        rows.append([r["scene"], r["method"], run_setting(r),
                     f"**{r['status']}**" if r["status"] != "stable" else r["status"],
                     num(r.get("flutter_rms_rad"), 2), num(r.get("flutter_max_rad"), 2), r.get("inverted_max"),
                     r.get("inverted_final"), num(r.get("kinetic_energy_final"), 2),
                     num(r.get("residual_final"), 2), num(r.get("asymmetry"), 2), num(r.get("energy_error"), 2),
                     r.get("diverged_step") or "", r.get("cause") or "", why[:160]])
    md.append(table(["scene", "method", "integrator, dt (s)", "status", "flutter RMS (rad)", "flutter max (rad)",
                     "inverted max", "inverted at end", "kinetic energy at end (J)", "equilibrium residual",
                     "asymmetry", "energy error", "diverged at step", "cause", "why"], rows))
    md.append("\n")
    # Status matrix.
    md.append("Status by scene and method (and elements still inverted at the end: a body that "
              "stays inside out is a failure the flutter measure does not see):\n\n")
    rows = []
    for s, setting in dict.fromkeys((r["scene"], run_setting(r)) for r in runs):
        row = [s, setting]
        for m in methods:
            r = next((r for r in runs if r["scene"] == s and run_setting(r) == setting and r["method"] == m), None)
            cell = r["status"] if r else ""
            if r and r.get("inverted_final"):
                cell += f", ends with {r['inverted_final']} inverted"
            row.append(cell)
        rows.append(row)
    md.append(table(["scene", "integrator, dt (s)"] + methods, rows))
    md.append("\n")
    if not HAVE_MPL:
        return
    md.append(f"![status]({draw_status_matrix(runs, scenes, methods, folder)})\n\n")
    if not frames:
        md.append("(The per-step series and final poses are in stability_frames.json, absent here: no flutter "
                  "or pose charts.)\n\n")
        return
    series_of = frames.get("series", [])
    for s in scenes:
        fig, ax = plt.subplots(figsize=(7, 3.6))
        base = next((run_setting(r) for r in runs if r["scene"] == s), "")
        for i, r in enumerate(runs):
            if r["scene"] != s or run_setting(r) != base or i >= len(series_of) or not series_of[i]:
                continue
            series = series_of[i]["rotation_change_max_rad"]
            ax.plot(range(1, len(series) + 1), [max(v, 1e-12) for v in series], label=r["method"], linewidth=0.9)
        ax.axvline(st.get("ramp_steps", 0), color="gray", linestyle=":", linewidth=0.8)
        ax.axhline(th.get("flutter_max_rad", 0.1), color="red", linestyle="--", linewidth=0.8)
        ax.set_yscale("log")
        ax.set_xlabel("step (dotted: end of loading; dashed: flutter threshold)")
        ax.set_ylabel("largest rotation change per step (rad)")
        ax.set_title(f"{s}: flutter per step ({base})", fontsize=9)
        ax.legend(fontsize=6, ncol=2)
        fig.tight_layout()
        md.append(f"![{s} flutter]({save(fig, folder, 'stability_flutter_' + s + '.png')})\n\n")
    for integrator in dict.fromkeys(p.get("integrator", "linear-implicit") for p in frames.get("poses", [])):
        chart = draw_poses(st, frames, integrator, folder)
        if chart:
            md.append(f"![poses under {integrator}]({chart})\n\n")


# ----------------------------------------------------------------------------------------------
def render_model_accuracy(ma, md):
    md.append("## Model accuracy against CalculiX\n\n")
    md.append(context_lines(ma))
    if ma.get("skipped"):
        md.append(f"\nNot run: {ma['skipped']}.\n\n")
        return
    md.append(f"\nOracle: {ma.get('oracle')}, on the same meshes, supports and load vectors; static Newton "
              f"solves (20 increments, to 1e-10). Errors: {ma.get('errors')}. The linear column compares "
              f"corofem's linear solve with CalculiX's linear one (equal to its 7 printed digits when below "
              f"1e-6), and with NLGEOM (how far small strain is).\n\n")
    cases = [c for c in ma.get("cases", []) if c.get("completed")]
    methods = list(dict.fromkeys(m["method"] for c in cases for m in c.get("methods", [])))
    rows = []
    for c in cases:
        row = [c["scene"], c["size"], c["tets"], num(c.get("displacement_max_m"), 3),
               num(c["linear"]["against_calculix_linear"]["max"], 2),
               num(c["linear"]["against_calculix_nlgeom"]["l2"], 2)]
        for method in methods:
            m = next((m for m in c["methods"] if m["method"] == method), {})
            err = (m.get("against_calculix_nlgeom") or {}).get("l2")
            cell = num(err, 2) if m.get("completed") else "failed"
            if m.get("completed") and not m.get("converged"):
                cell += " (not converged)"
            row.append(cell)
        rows.append(row)
    md.append(table(["scene", "size", "tets", "max displacement (m)", "linear vs ccx linear (max)",
                     "linear vs NLGEOM (l2)"] + [f"{m} vs NLGEOM (l2)" for m in methods], rows))
    failed = [c for c in ma.get("cases", []) if not c.get("completed")]
    for c in failed:
        md.append(f"\n- {c['scene']} {c['size']}: not run: {(c.get('error') or {}).get('message', '')[:200]}\n")
    md.append("\n")


def main(argv):
    global BLANK
    args = [a for a in argv[1:] if a != "--blank-times"]
    BLANK = "--blank-times" in argv
    if len(args) != 1:
        print(__doc__, file=sys.stderr)
        return 2
    folder = args[0]
    tables = load(folder, "tables.json")
    sa = load(folder, "speed_accuracy.json")
    st = load(folder, "stability.json")
    frames = load(folder, "stability_frames.json")
    cache = load(folder, "cache_profile.json")
    scaling = load(folder, "mpi_scaling.json")
    ma = load(folder, "model_accuracy.json")
    since = load(folder, "since_snapshot.json")
    if not (tables or sa or st or ma):
        print(f"render: no tables.json, speed_accuracy.json or stability.json in {folder}", file=sys.stderr)
        return 2
    md = ["# corofem report\n\n",
          "Drawn by reports/render_report.py from the JSON records in this folder alone; every "
          "number below is in them, with the commit, flags and machine that produced it.\n\n"]
    if not HAVE_MPL:
        md.append("(matplotlib was not available: no charts drawn.)\n\n")
    if tables:
        render_tables(tables, folder, md)
    if tables or sa:
        render_since_snapshot(since, md, table, num)
    if sa:
        render_speed_accuracy(sa, folder, md)
    if tables or sa:
        render_cache(cache, md)
        render_mpi_scaling(scaling, md)
    if st:
        render_stability(st, frames, folder, md)
    if ma:
        render_model_accuracy(ma, md)
    text = "".join(md)
    fd, tmp = tempfile.mkstemp(dir=folder, suffix=".md")
    with os.fdopen(fd, "w") as f:
        f.write(text)
    os.chmod(tmp, 0o644)
    os.replace(tmp, os.path.join(folder, "REPORT.md"))
    print(f"render: wrote {os.path.join(folder, 'REPORT.md')}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
