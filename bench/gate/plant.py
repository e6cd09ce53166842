#!/usr/bin/env python3
"""Writes a patch that plants a known fault, for calibrating ci/bench-gate and corofem compare.

Usage: bench/gate/plant.py slowdown PHASE PERCENT [--ref REF] > plant.patch
       bench/gate/plant.py rotation-offset RADIANS [--ref REF] > plant.patch
then:  ci/bench-gate REF REF --patch plant.patch

slowdown: every timed PHASE of a step (solve, update, assemble, rotate, ...) busy-waits PERCENT of
its own time before the phase clock stops (lib/fem/simulation_result.hpp's PhaseClock), so that
phase, and the step by its share, are that much slower, at any thread count.
rotation-offset: the energy-newton extractor turns every element's rotation by RADIANS about z
after its Newton solve (lib/rotation/energy_rotation.cpp): an accuracy fault, every else equal.
The patch is made against REF's file (default HEAD) and applied only in bench-gate's worktree:
the production code has no switch for it.
"""
import argparse
import difflib
import subprocess
import sys

CLOCK = "lib/fem/simulation_result.hpp"
ENERGY = "lib/rotation/energy_rotation.cpp"


def file_at(ref, path):
    return subprocess.run(["git", "show", f"{ref}:{path}"], check=True, capture_output=True,
                          text=True).stdout


def replaced(text, old, new, path):
    if text.count(old) != 1:
        sys.exit(f"plant.py: {path} at this ref does not have the expected code once; "
                 f"the plant needs updating")
    return text.replace(old, new)


def slowdown(ref, phase, percent):
    text = file_at(ref, CLOCK)
    old = ("      ~Add() {\n"
           "        totals[phase] +=\n")
    new = ("      ~Add() {\n"
           f"        if (phase == \"{phase}\") {{  // planted: {percent}% slower\n"
           "          const auto now = std::chrono::steady_clock::now();\n"
           f"          const auto until = now + (now - start) * {percent} / 100;\n"
           "          while (std::chrono::steady_clock::now() < until) {\n"
           "          }\n"
           "        }\n"
           "        totals[phase] +=\n")
    return CLOCK, text, replaced(text, old, new, CLOCK)


def rotation_offset(ref, radians):
    text = file_at(ref, ENERGY)
    old = ("  stats_.fallbacks = fallbacks;\n"
           "  stats_.inverted = inverted;\n"
           "}\n\n"
           "EnergyExactExtractor::EnergyExactExtractor")
    new = ("  {  // planted: every rotation turned about z\n"
           f"    const double c = std::cos({radians!r}), s = std::sin({radians!r});\n"
           "    Mat3 turn;\n"
           "    turn << c, -s, 0, s, c, 0, 0, 0, 1;\n"
           "    for (Mat3& r : rotations) r = Mat3(r * turn);\n"
           "  }\n" + old)
    return ENERGY, text, replaced(text, old, new, ENERGY)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("kind", choices=["slowdown", "rotation-offset"])
    parser.add_argument("values", nargs="+")
    parser.add_argument("--ref", default="HEAD")
    args = parser.parse_args()
    if args.kind == "slowdown":
        if len(args.values) != 2:
            parser.error("slowdown PHASE PERCENT")
        path, before, after = slowdown(args.ref, args.values[0], float(args.values[1]))
    else:
        if len(args.values) != 1:
            parser.error("rotation-offset RADIANS")
        path, before, after = rotation_offset(args.ref, float(args.values[0]))
    sys.stdout.writelines(difflib.unified_diff(before.splitlines(True), after.splitlines(True),
                                               f"a/{path}", f"b/{path}"))


if __name__ == "__main__":
    main()
