"""Speed against accuracy (speed_accuracy.json): each scene's chart of time per step against
error, with its Pareto front, and its table."""
import math

from render_common import HAVE_MPL, context_lines, failed, failure_text, matplotlib, num, plt, save, t, table

ORDER = 30
RECORDS = ("speed_accuracy.json",)
REPORT_SECTION = True


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


def render(records, folder, md):
    if records["speed_accuracy.json"]:
        render_speed_accuracy(records["speed_accuracy.json"], folder, md)
