"""Each phase's work on the gate suite, counted (phase_counts.json: bench/count_phases.py as
ci/report runs it): instructions and simulated cache misses per step at one thread. The counts
ci/count-gate holds every change to, and what tells the comparison with the snapshot whether a
timing moved with its work."""
from render_common import num, section_heading, table

ORDER = 45
RECORDS = ("phase_counts.json", "tables.json", "speed_accuracy.json")
PHASES = ("rotate", "assemble", "update", "solve", "forces", "system", "checks")


def render_counts(bundle, md):
    if not section_heading(md, "Work per phase, counted", bundle, "bench/count_phases.py"):
        return
    counting = bundle.get("counting", {})
    caches = counting.get("simulated_caches") or {}
    md.append(f"- {counting.get('tool')} at {counting.get('threads')} thread on simulated caches "
              f"(D1 {caches.get('D1', '?')}; LL {caches.get('LL', '?')}), the code seeing "
              f"`{counting.get('processor_seen')}`: the same counts on any host, run after run "
              "(lib/docs/counting.md). Per step; a phase holds its parts (the update its Galerkin "
              "products, smoothers' set-up and coarsest factorization).\n\n")
    rows = []
    for record in bundle.get("records", []):
        sections = record.get("phase_counts", {}).get("sections", {})
        steps = max(record.get("steps", 1), 1)
        for phase in PHASES:
            if phase not in sections:
                continue
            c = sections[phase]
            rows.append([record["scene_file"], record.get("mesh", {}).get("tets"), phase,
                         num(c["instructions"] / steps), num(c["d1_misses"] / steps),
                         num(c["ll_misses"] / steps)])
    md.append(table(["scene", "tets", "phase", "instructions", "D1 misses", "LL misses"], rows))
    md.append("\n")


def render(records, folder, md):
    if records["tables.json"] or records["speed_accuracy.json"]:
        if records["phase_counts.json"] is not None:
            render_counts(records["phase_counts.json"], md)
