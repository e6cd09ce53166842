#!/usr/bin/env python3
"""Fails on an #include in lib/ that runs against the layer order.

lib/'s folders are layers, lowest first (the order a step flows through them); a file may include
headers of its own folder and of the layers its layer links, directly or through another, never
others. The order and the links are read from lib/CMakeLists.txt (COROFEM_LAYERS: each layer
links the one before it; COROFEM_LINKS_<layer>: the layers it links instead), the one place they
are written. The oracles of reference/ are for verify/ and bench/; no layer includes them: the
report reaches them through a seam (report/report_oracles.hpp) that the executable's own file,
cli/main.cpp, wires.

Usage: ci/check_layers.py [LIB_DIR]   (default: lib beside this script's folder)
Exit 0: every include keeps the order; 1: each offending line printed.
"""
import os
import re
import sys

REFERENCE_HEADERS = {"cholmod_oracle.hpp", "exact_rotation.hpp", "galerkin_oracle.hpp"}
REFERENCE_USERS = {"cli/main.cpp"}  # the executable, not a layer's library
INCLUDE = re.compile(r'^\s*#\s*include\s*"([^"]+)"')


def layers_and_links(cmake_lists):
    """The layer order and, for each layer, the layers it may include (its links, closed)."""
    with open(cmake_lists, encoding="utf-8") as f:
        text = f.read()
    order = re.search(r"^set\(COROFEM_LAYERS ([^)]*)\)", text, re.M).group(1).split()
    links = {}
    for i, layer in enumerate(order):
        named = re.search(rf"^set\(COROFEM_LINKS_{layer} ([^)]*)\)", text, re.M)
        links[layer] = named.group(1).split() if named else order[i - 1:i]
    below = {}
    for layer in order:  # lowest first: each link's own closure is known
        below[layer] = set()
        for link in links[layer]:
            below[layer] |= {link} | below[link]
    return order, below


def main(argv):
    lib = argv[1] if len(argv) > 1 else os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "lib")
    order, below = layers_and_links(os.path.join(lib, "CMakeLists.txt"))
    rank = {name: i for i, name in enumerate(order)}
    bad = []
    folders = sorted(d for d in os.listdir(lib) if os.path.isdir(os.path.join(lib, d)))
    for folder in folders:
        if folder == "docs":  # the reference's pages and design notes, no code
            continue
        if folder not in rank:
            bad.append(f"lib/{folder}: a folder that is no layer (add it to COROFEM_LAYERS in lib/CMakeLists.txt)")
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
                    if layer in rank and layer != folder and layer not in below[folder]:
                        bad.append(f"{where}: {folder} does not link {layer} (it links "
                                   f"{', '.join(sorted(below[folder])) or 'nothing'}; "
                                   f"lib/CMakeLists.txt)")
    for line in bad:
        print(f"check_layers: {line}")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
