#!/usr/bin/env python3
"""Checks that two report folders have the same schema where the renderer reads them.

Usage: schema_check.py EXPECTED_DIR ACTUAL_DIR
       schema_check.py --snapshot CODE_DIR SNAPSHOT_DIR

Renders both folders (copies, in a temporary folder) with render_report.py while recording every
field the renderer looks up in each JSON record. A field counts as read by its path: keys joined
by '.', list indices as '[]'. For every record file present in both folders, every path the
renderer read in either must exist in both or in neither: a field the renderer reads that one
folder has and the other lacks is schema drift. ci/test runs it with the golden fixtures
(verify/golden/report) against a smoke report the current code wrote, so the fixtures cannot
drift from the code; reports/regenerate_golden refreshes them.

With --snapshot, only one direction: every field the renderer reads in CODE_DIR (records the
current code wrote) must be in SNAPSHOT_DIR (the published snapshot, reports/), so a snapshot older
than a change to the records fails; the snapshot may hold more (its runs had the models, whose
rows have fields the procedural scenes' lack). reports/publish refreshes it.

Exit 0: no drift; 1: drift (each path printed, with the folder that lacks it); 2: bad usage.
"""
import contextlib
import io
import json
import os
import shutil
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import render_report  # noqa: E402

RECORDS = tuple(render_report.record_files(render_report.units()))



class Reads:
    """The paths looked up while rendering, per record file."""

    def __init__(self):
        self.paths = {}

    def note(self, record, path):
        self.paths.setdefault(record, set()).add(path)


class TrackedDict(dict):
    def __init__(self, data, record, path, reads):
        super().__init__((k, wrap(v, record, f"{path}.{k}", reads)) for k, v in data.items())
        self._record, self._path, self._reads = record, path, reads

    def _note(self, key):
        self._reads.note(self._record, f"{self._path}.{key}")

    def __getitem__(self, key):
        self._note(key)
        return super().__getitem__(key)

    def get(self, key, default=None):
        self._note(key)
        return super().get(key, default)

    def __contains__(self, key):
        self._note(key)
        return super().__contains__(key)


class TrackedList(list):
    pass


def wrap(value, record, path, reads):
    if isinstance(value, dict):
        return TrackedDict(value, record, path, reads)
    if isinstance(value, list):
        return TrackedList(wrap(v, record, f"{path}[]", reads) for v in value)
    return value


def all_paths(value, path=""):
    """Every path in a JSON value, list indices as '[]'."""
    out = set()
    if isinstance(value, dict):
        for k, v in value.items():
            out.add(f"{path}.{k}")
            out |= all_paths(v, f"{path}.{k}")
    elif isinstance(value, list):
        for v in value:
            out |= all_paths(v, f"{path}[]")
    return out


def render_tracked(folder, reads):
    """Renders a copy of `folder` with every record's lookups noted in `reads`."""
    plain_load = render_report.load

    def tracked_load(where, name):
        data = plain_load(where, name)
        return None if data is None else wrap(data, name, "", reads)

    with tempfile.TemporaryDirectory() as work:
        copy = os.path.join(work, "report")
        os.mkdir(copy)
        for name in RECORDS:
            if os.path.exists(os.path.join(folder, name)):
                shutil.copy(os.path.join(folder, name), copy)
        render_report.load = tracked_load
        try:
            with contextlib.redirect_stderr(io.StringIO()):
                status = render_report.main(["render_report.py", copy, "--blank-times"])
        finally:
            render_report.load = plain_load
    if status != 0:
        raise SystemExit(f"schema_check: the renderer failed on {folder}")


def main(argv):
    snapshot = len(argv) == 4 and argv[1] == "--snapshot"
    if snapshot:
        argv = argv[:1] + argv[2:]
    if len(argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    folders = argv[1:]
    reads = Reads()
    for folder in folders:
        render_tracked(folder, reads)
    drift = []
    compared = 0
    for name in RECORDS:
        paths = []
        for folder in folders:
            file = os.path.join(folder, name)
            paths.append(all_paths(json.load(open(file))) if os.path.exists(file) else None)
        if None in paths:
            continue
        compared += 1
        for path in sorted(reads.paths.get(name, ())):
            present = [path in p for p in paths]
            if snapshot and not present[0]:
                continue  # read only in the snapshot: a field of the models' rows
            if present[0] != present[1]:
                lacking = folders[present.index(False)]
                drift.append(f"{name}: {path} (missing in {lacking})")
    for line in drift:
        print(f"schema_check: {line}")
    print(f"schema_check: {compared} record file(s) compared, {sum(len(v) for v in reads.paths.values())} "
          f"field(s) the renderer reads, {len(drift)} drifted", file=sys.stderr)
    return 1 if drift else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
