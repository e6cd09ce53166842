"""Beyond one machine (mpi_scaling.json, bench/mpi_scaling.py as ci/report runs it), shown beside
the tables or the speed-accuracy section."""
from render_common import num, ratio, section_heading, t, table

ORDER = 50
RECORDS = ("mpi_scaling.json", "tables.json", "speed_accuracy.json")


def render_mpi_scaling(scaling, md):
    if not section_heading(md, "Beyond one machine: MPI ranks", scaling, "bench/mpi_scaling.py"):
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


def render(records, folder, md):
    if records["tables.json"] or records["speed_accuracy.json"]:
        render_mpi_scaling(records["mpi_scaling.json"], md)
