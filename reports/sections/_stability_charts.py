"""The stability study's charts: the status matrix and the final poses."""
import math

from render_common import matplotlib, num, plt, save


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
