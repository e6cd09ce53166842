"""The example's report section (own_methods.json, bench/own_method/own_table.cpp): Table 1's
phases for its rotation method and smoother beside the paper's method. A renderer unit: corofem's
reports/render draws it when $COROFEM_REPORT_SECTIONS names this folder."""
from render_common import context_lines, failure_text, num, t, table

ORDER = 15  # after Tables 1 and 2
RECORDS = ("own_methods.json",)
REPORT_SECTION = True


def render(records, folder, md):
    own = records["own_methods.json"]
    if not own:
        return
    methods = own.get("methods", {})
    md.append("## Own methods beside the paper's\n\n")
    md.append(context_lines(own))
    md.append(f"- Rotation `{methods.get('rotation')}`, smoother `{methods.get('smoother')}`; "
              f"medians over {own.get('measured_steps')} steps after {own.get('warmup_steps')}.\n\n")
    rows = []
    for r in own.get("rows", []):
        if not r.get("completed"):
            rows.append([r["model"], r["variant"], failure_text(r), "", "", "", "", "", ""])
            continue
        rows.append([r["model"], r["variant"]] +
                    [t(r.get(p + "_ms")) for p in ("rotate", "assemble", "update", "solve", "step")] +
                    [num(r.get("linear_iterations")), num(r.get("displacement_vs_paper"), 2)])
    md.append(table(["model", "variant", "rotate ms", "assemble ms", "update ms", "solve ms", "step ms",
                     "iterations", "displacement vs paper's"], rows))
    md.append("\n")
