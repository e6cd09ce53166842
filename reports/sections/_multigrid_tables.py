"""Table 1's multigrid tables: the roofline, the hierarchy and its quality, size independence."""
from render_common import HAVE_MPL, failed, failure_text, num, plt, save, t, table


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
