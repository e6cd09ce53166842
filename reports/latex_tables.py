"""Every table of a REPORT.md as a LaTeX (booktabs) file a paper can \\input: tables/NN-slug.tex,
one per Markdown table, named by the heading above it, and tables/all.tex, a document that inputs
them all (it compiles with pdflatex, as the tests check). Drawn from the Markdown text itself, so
the cells are the report's, digit for digit."""
import os
import re
import tempfile

HEADING = re.compile(r"^#{2,4} (.+)$")
RULE = re.compile(r"^\|(---\|)+$")
NUMBER = re.compile(r"^[-+]?(\d[\d,]*\.?\d*|\.\d+)([eE][-+]?\d+)?(%|x)?$")
SPECIAL = {"\\": r"\textbackslash{}", "&": r"\&", "%": r"\%", "$": r"\$", "#": r"\#",
           "_": r"\_", "{": r"\{", "}": r"\}", "~": r"\textasciitilde{}", "^": r"\textasciicircum{}",
           "<": r"\textless{}", ">": r"\textgreater{}"}


def escaped(text):
    return "".join(SPECIAL.get(ch, ch) for ch in text)


def cell_tex(cell):
    """A Markdown cell as LaTeX: **bold** and `code` kept, the rest escaped."""
    out = []
    for part in re.split(r"(\*\*[^*]+\*\*|`[^`]+`)", cell):
        if part.startswith("**") and part.endswith("**") and len(part) > 4:
            out.append(r"\textbf{" + escaped(part[2:-2]) + "}")
        elif part.startswith("`") and part.endswith("`") and len(part) > 2:
            out.append(r"\texttt{" + escaped(part[1:-1]) + "}")
        else:
            out.append(escaped(part))
    return "".join(out)


def cells(line):
    return [c.strip() for c in line.strip().strip("|").split("|")]


def markdown_tables(text):
    """(heading, header cells, rows of cells) of every Markdown table, in order."""
    heading, out = "report", []
    lines = text.splitlines()
    i = 0
    while i < len(lines):
        m = HEADING.match(lines[i])
        if m:
            heading = m.group(1)
        if lines[i].startswith("|") and i + 1 < len(lines) and RULE.match(lines[i + 1].strip()):
            header = cells(lines[i])
            rows = []
            i += 2
            while i < len(lines) and lines[i].startswith("|"):
                rows.append(cells(lines[i]))
                i += 1
            out.append((heading, header, rows))
            continue
        i += 1
    return out


def slug(text):
    return re.sub(r"[^a-z0-9]+", "-", text.lower()).strip("-")[:48] or "table"


def tabular(heading, header, rows):
    """One table: numeric columns right-aligned, the others left."""
    numeric = [all(NUMBER.match(r[k].replace(" ", "")) or r[k] in ("-", "", "t")
                   for r in rows if k < len(r)) and any(NUMBER.match(r[k]) for r in rows if k < len(r))
               for k in range(len(header))]
    spec = "".join("r" if n else "l" for n in numeric)
    body = [f"% corofem report: {heading}",
            r"\begin{tabular}{" + spec + "}", r"\toprule",
            " & ".join(cell_tex(h) for h in header) + r" \\", r"\midrule"]
    for r in rows:
        r = (r + [""] * len(header))[:len(header)]
        body.append(" & ".join(cell_tex(c) for c in r) + r" \\")
    body += [r"\bottomrule", r"\end{tabular}", ""]
    return "\n".join(body)


def write_atomically(path, text):
    fd, tmp = tempfile.mkstemp(dir=os.path.dirname(path), suffix=".tex")
    with os.fdopen(fd, "w") as f:
        f.write(text)
    os.chmod(tmp, 0o644)
    os.replace(tmp, path)


def write_tables(markdown, folder):
    """Writes folder/tables/*.tex from the Markdown; returns the files written."""
    out_dir = os.path.join(folder, "tables")
    os.makedirs(out_dir, exist_ok=True)
    for old in os.listdir(out_dir):  # a table the report no longer has leaves no stale file
        if old.endswith(".tex"):
            os.remove(os.path.join(out_dir, old))
    names = []
    for n, (heading, header, rows) in enumerate(markdown_tables(markdown), 1):
        name = f"{n:02d}-{slug(heading)}.tex"
        write_atomically(os.path.join(out_dir, name), tabular(heading, header, rows))
        names.append(name)
    document = [r"\documentclass{article}", r"\usepackage{booktabs}",
                r"\usepackage[landscape,margin=1cm]{geometry}", r"\begin{document}", r"\tiny"]
    for name in names:
        document += [r"\noindent\input{" + name[:-4] + "}", r"\par\bigskip"]
    document += [r"\end{document}", ""]
    write_atomically(os.path.join(out_dir, "all.tex"), "\n".join(document))
    return names
