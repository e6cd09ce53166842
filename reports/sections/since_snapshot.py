"""The report's section "Since the last published snapshot", drawn from since_snapshot.json:
`corofem compare reports/ NEW_REPORT` as ci/report runs it (lib/docs/comparing.md). A reader sees
what changed and whether it is signal: the timings beyond the threshold with their intervals (and,
where the phase was counted on both sides, whether its counts moved: the code's, or not: the
machine's), the counters, work counts and accuracy fields that moved."""
import math

from render_common import num, table

ORDER = 20
MAX_ROWS = 20
RECORDS = ("since_snapshot.json", "tables.json", "speed_accuracy.json")



def move_of(row):
    """How far a row moved, as a ratio (1: not at all)."""
    test = row.get("test")
    if test:
        return test["ratio"]
    base, new = row.get("base"), row.get("new")
    if isinstance(base, (int, float)) and isinstance(new, (int, float)) and base and new:
        return new / base
    return 1.0


def headline(verdict):
    """compare's headline: a regression, inconclusive (timed rows it could not test), or none."""
    if verdict.get("regression"):
        return "a regression"
    return verdict.get("headline", "no regression")


def render_since_snapshot(verdict, md):
    md.append("## Since the last published snapshot\n\n")
    if verdict is None:
        md.append("Not compared (ci/report compares a new report with reports/, the published "
                  "snapshot, when both ran the same scenes).\n\n")
        return
    if "error" in verdict:
        reason = verdict["error"].removeprefix("corofem: error: ")
        md.append(f"Not compared: {reason}. The snapshot and this report ran other scenes (the "
                  "snapshot is published from the models; a default report runs the procedural "
                  "scenes) or other thread counts.\n\n")
        return
    base = verdict.get("base_context") or {}
    counts = ", ".join(f"{n} {v}" for v, n in sorted(verdict.get("verdicts", {}).items()))
    options = verdict.get("options", {})
    behind = verdict.get("base_commits_behind")
    age = f", {behind} commits before this report's" if isinstance(behind, int) and behind else ""
    md.append(f"`corofem compare` of this report against the snapshot of commit "
              f"`{str(base.get('commit', '?'))[:9]}` ({base.get('date', '?')}{age}): "
              f"**{headline(verdict)}** ({counts}). "
              f"A timing is slower or faster only with p < {options.get('alpha')} (Mann-Whitney U) "
              f"and a ratio beyond {100 * options.get('threshold', 0):g}%; the full table is "
              f"since_snapshot/compare.md.\n\n")
    for u in verdict.get("unpaired", []):
        md.append(f"- not compared: {u}\n")
    for w in verdict.get("warnings", []):
        md.append(f"- warning: {w}\n")
    if verdict.get("warnings") or verdict.get("unpaired"):
        md.append("\n")
    moved = [r for r in verdict.get("rows", [])
             if r["verdict"] in ("slower", "faster", "increased", "decreased", "worse", "better",
                                 "changed", "missing in new", "more", "fewer")]
    if not moved:
        md.append("Nothing moved beyond noise: every timing the same within its interval or "
                  "the threshold, every counter equal, every accuracy field within tolerance.\n\n")
        return
    # The largest moves first, at most MAX_ROWS of them: the section stays a page's glance.
    moved.sort(key=lambda r: -abs(math.log(max(move_of(r), 1e-12))))
    shown, rest = moved[:MAX_ROWS], len(moved) - MAX_ROWS
    rows = []
    for r in shown:
        test = r.get("test")
        interval = f"{num(test['interval'][0])}-{num(test['interval'][1])}" if test else ""
        ratio = num(test["ratio"]) if test else num(r["ratio"]) if "ratio" in r else ""
        cause = r.get("attribution")
        rows.append([r["case"], r["threads"], r["quantity"], r["kind"], num(r.get("base")),
                     num(r.get("new")), ratio, interval, r["verdict"],
                     f"the {cause['to']}'s: {cause['because']}" if cause else ""])
    md.append(table(["case", "threads", "quantity", "kind", "snapshot", "now", "ratio",
                     "interval", "verdict", "cause"], rows))
    if rest > 0:
        md.append(f"\n{rest} more in since_snapshot/compare.md.\n")
    md.append("\n")


def render(records, folder, md):
    if records["tables.json"] or records["speed_accuracy.json"]:
        render_since_snapshot(records["since_snapshot.json"], md)
