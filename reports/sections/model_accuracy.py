"""The model's accuracy (model_accuracy.json): every rotation method's static solve against
CalculiX NLGEOM."""
from render_common import context_lines, num, table

ORDER = 70
RECORDS = ("model_accuracy.json",)
REPORT_SECTION = True


def render_model_accuracy(ma, md):
    md.append("## Model accuracy against CalculiX\n\n")
    md.append(context_lines(ma))
    if ma.get("skipped"):
        md.append(f"\nNot run: {ma['skipped']}.\n\n")
        return
    md.append(f"\nOracle: {ma.get('oracle')}, on the same meshes, supports and load vectors; static Newton "
              f"solves (20 increments, to 1e-10). Errors: {ma.get('errors')}. The linear column compares "
              f"corofem's linear solve with CalculiX's linear one (equal to its 7 printed digits when below "
              f"1e-6), and with NLGEOM (how far small strain is).\n\n")
    cases = [c for c in ma.get("cases", []) if c.get("completed")]
    methods = list(dict.fromkeys(m["method"] for c in cases for m in c.get("methods", [])))
    rows = []
    for c in cases:
        row = [c["scene"], c["size"], c["tets"], num(c.get("displacement_max_m"), 3),
               num(c["linear"]["against_calculix_linear"]["max"], 2),
               num(c["linear"]["against_calculix_nlgeom"]["l2"], 2)]
        for method in methods:
            m = next((m for m in c["methods"] if m["method"] == method), {})
            err = (m.get("against_calculix_nlgeom") or {}).get("l2")
            cell = num(err, 2) if m.get("completed") else "failed"
            if m.get("completed") and not m.get("converged"):
                cell += " (not converged)"
            row.append(cell)
        rows.append(row)
    md.append(table(["scene", "size", "tets", "max displacement (m)", "linear vs ccx linear (max)",
                     "linear vs NLGEOM (l2)"] + [f"{m} vs NLGEOM (l2)" for m in methods], rows))
    failed = [c for c in ma.get("cases", []) if not c.get("completed")]
    for c in failed:
        md.append(f"\n- {c['scene']} {c['size']}: not run: {(c.get('error') or {}).get('message', '')[:200]}\n")
    md.append("\n")


def render(records, folder, md):
    if records["model_accuracy.json"]:
        render_model_accuracy(records["model_accuracy.json"], md)
