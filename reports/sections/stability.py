"""Stability where methods fail (stability.json; its charts from stability_frames.json): the
verdicts with their causes, the runs, the status matrix and the poses."""
from render_common import HAVE_MPL, context_lines, num, plt, save, table
from sections._stability_charts import draw_poses, draw_status_matrix, run_setting

ORDER = 60
RECORDS = ("stability.json", "stability_frames.json")
REPORT_SECTION = True


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


def render(records, folder, md):
    if records["stability.json"]:
        render_stability(records["stability.json"], records["stability_frames.json"], folder, md)
