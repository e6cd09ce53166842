#!/usr/bin/env python3
"""Fails on an #include in lib/ that runs against the layer order.

lib/'s folders are layers, lowest first (the order a step flows through them); a file may include
headers of its own folder and of the folders below it, never above. The oracles of reference/ are
for verify/ and bench/; no layer includes them: the report reaches them through a seam
(report/report_oracles.hpp) that the executable's own file, cli/main.cpp, wires. lib/CMakeLists.txt
builds one library per folder that links only the folders below it, in this same order.

Usage: ci/check_layers.py [LIB_DIR]   (default: lib beside this script's folder)
Exit 0: every include keeps the order; 1: each offending line printed.
"""
import os
import re
import sys

LAYERS = ["core", "sparse", "mesh", "element", "rotation", "fem", "linalg", "multigrid", "solver",
          "integrate", "io", "scene", "report", "tune", "compare", "cli"]
REFERENCE_HEADERS = {"cholmod_oracle.hpp", "exact_rotation.hpp", "galerkin_oracle.hpp"}
REFERENCE_USERS = {"cli/main.cpp"}  # the executable, not a layer's library
INCLUDE = re.compile(r'^\s*#\s*include\s*"([^"]+)"')


def main(argv):
    lib = argv[1] if len(argv) > 1 else os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "lib")
    rank = {name: i for i, name in enumerate(LAYERS)}
    bad = []
    folders = sorted(d for d in os.listdir(lib) if os.path.isdir(os.path.join(lib, d)))
    for folder in folders:
        if folder == "docs":  # the reference's pages and design notes, no code
            continue
        if folder not in rank:
            bad.append(f"lib/{folder}: a folder that is no layer (add it to ci/check_layers.py and lib/CMakeLists.txt)")
            continue
        for name in sorted(os.listdir(os.path.join(lib, folder))):
            if not name.endswith((".hpp", ".cpp", ".h")):
                continue
            path = os.path.join(lib, folder, name)
            with open(path, encoding="utf-8") as f:
                for number, line in enumerate(f, 1):
                    match = INCLUDE.match(line)
                    if not match:
                        continue
                    target = match.group(1)
                    where = f"lib/{folder}/{name}:{number}: #include \"{target}\""
                    if "/" not in target:
                        if target in REFERENCE_HEADERS and f"{folder}/{name}" not in REFERENCE_USERS:
                            bad.append(f"{where}: an oracle of reference/ on the production path")
                        continue
                    layer = target.split("/")[0]
                    if layer in rank and rank[layer] > rank[folder]:
                        bad.append(f"{where}: {layer} is above {folder} (order: {' < '.join(LAYERS)})")
    for line in bad:
        print(f"check_layers: {line}")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
