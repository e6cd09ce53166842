"""What every unit of the renderer shares: loading a record, numbers as the report prints them
(machine-dependent ones blanked for the golden test), Markdown tables, charts saved atomically,
the line that says what produced a record."""
import json
import math
import os
import tempfile

try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import matplotlib.patches
    import matplotlib.ticker

    HAVE_MPL = True
except ImportError:  # REPORT.md is still written; it says the charts are missing
    HAVE_MPL = False
    matplotlib = plt = None

BLANK = False  # --blank-times: set by render_report.main through set_blank


def load(folder, name):
    path = os.path.join(folder, name)
    if not os.path.exists(path):
        return None
    with open(path) as f:
        return json.load(f)


def num(value, digits=3):
    """A number with `digits` significant digits; '-' for missing."""
    if value is None or (isinstance(value, float) and not math.isfinite(value)):
        return "-"
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, int):
        return str(value)
    if value == 0:
        return "0"
    magnitude = abs(value)
    if magnitude >= 1e5 or magnitude < 1e-3:
        return f"{value:.{digits - 1}e}"
    return f"{value:.{digits}g}" if magnitude < 10 ** digits else f"{value:.0f}"


def t(value, digits=3):
    """A machine-dependent number (time, rate, ratio of times)."""
    return "t" if BLANK else num(value, digits)


def ratio(a, b):
    if a is None or b is None or b == 0:
        return None
    return a / b


def table(headers, rows):
    out = ["| " + " | ".join(headers) + " |", "|" + "---|" * len(headers)]
    out += ["| " + " | ".join(str(c) for c in row) + " |" for row in rows]
    return "\n".join(out) + "\n"


def save(fig, folder, name):
    charts = os.path.join(folder, "charts")
    os.makedirs(charts, exist_ok=True)
    path = os.path.join(charts, name)
    fd, tmp = tempfile.mkstemp(dir=charts, suffix=".png")
    os.close(fd)
    fig.savefig(tmp, dpi=90, metadata={"Software": None})
    os.chmod(tmp, 0o644)
    os.replace(tmp, path)
    # The same chart as vectors, for papers (no dates in them: a redraw of the same records gives
    # the same files).
    vector = os.path.join(charts, "vector")
    os.makedirs(vector, exist_ok=True)
    stem = os.path.splitext(name)[0]
    for suffix, metadata in ((".pdf", {"CreationDate": None, "Producer": None, "Creator": None}),
                             (".svg", {"Date": None, "Creator": None})):
        fd, tmp = tempfile.mkstemp(dir=vector, suffix=suffix)
        os.close(fd)
        fig.savefig(tmp, metadata=metadata)
        os.chmod(tmp, 0o644)
        os.replace(tmp, os.path.join(vector, stem + suffix))
    plt.close(fig)
    return "charts/" + name


def context_lines(record):
    c = record.get("context", {})
    p = record.get("parameters", {})
    date = "t" if BLANK else c.get("date", "?")
    commit = "t" if BLANK else c.get("commit", "?")
    return (f"- {record.get('producer', '?')}, mode `{p.get('mode', '?')}`, {p.get('scenes', '')}; "
            f"commit `{commit}`, {c.get('compiler', '?')} `{c.get('flags', '?')}`, "
            f"{'t' if BLANK else c.get('cpu', '?')}, {c.get('threads_used', 1)} thread, {date}\n")


def failed(row):
    return not row.get("completed", False)


def failure_text(row):
    e = row.get("error", {})
    return f"**failed** ({e.get('kind', '?')}): {e.get('message', '?')}"


def set_blank(blank):
    global BLANK
    BLANK = blank


def blanked():
    """Whether machine-dependent text (times, rates, dates, verdicts on times) prints as "t"."""
    return BLANK


def section_heading(md, title, record, runner):
    """A companion record's heading (one ci/report makes beside `corofem report`); False, after
    saying so, when this report has none."""
    md.append(f"## {title}\n\n")
    if record is None:
        md.append(f"Not run in this report (ci/report runs {runner}).\n\n")
        return False
    return True
