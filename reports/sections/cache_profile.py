"""The cache profiles (cache_profile.json, bench/cache_profile.sh as ci/report runs it), shown
beside the tables or the speed-accuracy section."""
from render_common import num, section_heading, table

ORDER = 40
RECORDS = ("cache_profile.json", "tables.json", "speed_accuracy.json")


def render_cache(cache, md):
    if not section_heading(md, "Cache profiles", cache, "bench/cache_profile.sh"):
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


def render(records, folder, md):
    if records["tables.json"] or records["speed_accuracy.json"]:
        render_cache(records["cache_profile.json"], md)
