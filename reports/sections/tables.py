"""Tables 1 and 2 of the paper beside ours (tables.json), with the thread, rival-solver and
verification tables and the phase chart; the multigrid tables are in _multigrid_tables.py."""
from render_common import HAVE_MPL, blanked, context_lines, failed, failure_text, num, plt, ratio, save, t, table
from sections._multigrid_tables import render_multigrid_quality, render_roofline

ORDER = 10
RECORDS = ("tables.json",)
REPORT_SECTION = True


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
    render_targets(tables, md)
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
        md.append(f"- The coarsest factor is kept while the coarsest operator moved less than "
                  "`analysis.coarsest_refactor` (3%) since it was factorized. In an update that refactors, at "
                  f"{n} threads MG-PCG factors the coarsest level (CHOLMOD, serial) and sets up the smoothers "
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


# The step's target against its roofline floor: within this factor, at one thread, and at two
# where the host placed the two cores close (their handoff under CLOSE_NS: lib/docs/threads.md,
# "Where the host puts the two cores").
FLOOR_TARGET = 1.5
CLOSE_NS, FAR_NS = 100, 150


def placement(ns):
    """Where the host put the two cores, from the handoff time the record carries."""
    if not isinstance(ns, (int, float)):
        return "not recorded"
    where = "close" if ns < CLOSE_NS else "far" if ns >= FAR_NS else "between"
    return f"{where} ({t(ns, 2)} ns)"


def render_targets(tables, md):
    """Each step and its slowest phase against the roofline floor, at one thread and at all,
    beside where the host put the cores; the paper's multiples as context."""
    md.append("### Performance targets: the step against its floor\n\n")
    threads = tables.get("threads", 1)
    where = placement((tables.get("context") or {}).get("core_to_core_ns"))
    md.append(f"- Step time over its roofline floor (the bytes and flops it must move at this "
              f"machine's measured roofs); target {FLOOR_TARGET}x at one thread, and at {threads} "
              f"threads where the host placed the cores close (handoff under {CLOSE_NS} ns; this "
              f"run: {where}). The paper's multiples are context.\n\n")
    rows = []
    for r in tables.get("table1", []):
        if failed(r) or not r.get("roofline"):
            continue
        one = r.get("one_thread") or {}
        for label, run, tps in (("1", one, one.get("tps")), (str(threads), r, r.get("tps"))):
            roof = run.get("roofline") or {}
            if not roof:
                continue
            phases = roof.get("phases", {})
            # The phase that costs most above its floor (a tiny phase's ratio says little).
            worst = max(phases.items(), default=None,
                        key=lambda kv: kv[1].get("measured_ms", 0) - kv[1].get("floor_ms", 0))
            over = roof.get("over_floor")
            judged = label == "1" or where.startswith("close")
            verdict = ("t" if blanked() else
                       ("met" if over <= FLOOR_TARGET else "not met") if judged else
                       "not judged: the cores were not placed close")
            paper = r.get("paper") or {}
            rows.append([r["model"], label, t(over, 2), verdict,
                         f"{worst[0]} {t(worst[1].get('over_floor'), 2)}" if worst else "-",
                         f"{t(ratio(tps, paper.get('tps')), 2)}x" if paper.get("tps") else "-"])
    if not rows:
        md.append("- (no row with a roofline in this run)\n\n")
        return
    md.append(table(["model", "threads", "step / floor", f"within {FLOOR_TARGET}x",
                     "most above its floor (phase / its floor)", "tps / paper's"], rows))
    md.append("\n")


def render(records, folder, md):
    if records["tables.json"]:
        render_tables(records["tables.json"], folder, md)
