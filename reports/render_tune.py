#!/usr/bin/env python3
"""Draws corofem tune's chart, DIR/pareto.png, from DIR/tune.json alone.

Usage: render_tune.py DIR

Every measured setting as cost (ms per step) against error (the reference's own error included),
the Pareto front joined, the target as a line, the answer and the scene as given marked.
"""
import json
import os
import sys

try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:
    print("render_tune: no matplotlib; tune.json is complete, no chart drawn", file=sys.stderr)
    sys.exit(0)


def main(folder):
    with open(os.path.join(folder, "tune.json")) as f:
        tune = json.load(f)
    points = [c for c in tune["candidates"] if c.get("completed") and c["stage"] != "re-run"]
    floor = min([p["error_with_reference"] for p in points if p["error_with_reference"] > 0] or [1e-16])
    def err(p):
        return max(p["error_with_reference"], floor / 10)

    fig, ax = plt.subplots(figsize=(7, 4.5))
    for stage, marker in (("screening", "o"), ("combination", "s"), ("reference", "*")):
        sel = [p for p in points if p["stage"] == stage]
        ax.scatter([p["cost_ms"] for p in sel], [err(p) for p in sel], marker=marker, s=28,
                   alpha=0.6, label=stage)
    front = sorted((p for p in points if p.get("pareto")), key=lambda p: p["cost_ms"])
    ax.plot([p["cost_ms"] for p in front], [err(p) for p in front], "k-", lw=1, label="Pareto front")
    ax.axhline(tune["target"], color="tab:red", ls="--", lw=1, label="target")
    answer = tune["answer"].get("rerun") or tune["answer"].get("search")
    if answer and answer.get("completed"):
        ax.scatter([answer["cost_ms"]], [err(answer)], s=140, facecolors="none",
                   edgecolors="tab:red", lw=2, label="answer (re-run)")
    given = tune.get("given")
    if given and given.get("completed"):
        ax.scatter([given["cost_ms"]], [err(given)], marker="D", s=50, color="tab:green",
                   label="scene as given")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("cost: " + tune["cost_definition"].split(",")[0] + " (ms)")
    ax.set_ylabel(tune["quantity"]["kind"] + " error (with the reference's own)")
    ax.set_title(os.path.basename(tune["scene_file"]) + ": status " + tune["answer"]["status"])
    ax.legend(fontsize=7)
    fig.tight_layout()
    out = os.path.join(folder, "pareto.png")
    tmp = out + ".tmp.png"
    fig.savefig(tmp, dpi=110)
    os.replace(tmp, out)


if __name__ == "__main__":
    if len(sys.argv) != 2:
        print(__doc__, file=sys.stderr)
        sys.exit(2)
    main(sys.argv[1])
