#!/usr/bin/env python3
"""Writes a patch that plants a known fault, for calibrating ci/bench-gate and corofem compare.

Usage: bench/gate/plant.py slowdown PHASE PERCENT [--ref REF] > plant.patch
       bench/gate/plant.py rotation-offset RADIANS [--ref REF] > plant.patch
       bench/gate/plant.py assembly-work ITERATIONS [--ref REF] > plant.patch
       bench/gate/plant.py extra-pass [--ref REF] > plant.patch
       bench/gate/plant.py scattered-order [--ref REF] > plant.patch
then:  ci/bench-gate REF REF --patch plant.patch   (timings)
       bench/gate/count_calibration.py             (counts: it plants the last three)

slowdown: every timed PHASE of a step (solve, update, assemble, rotate, ...) busy-waits PERCENT of
its own time before the phase clock stops (lib/fem/simulation_result.hpp's PhaseClock), so that
phase, and the step by its share, are that much slower, at any thread count.
rotation-offset: the energy-newton extractor turns every element's rotation by RADIANS about z
after its Newton solve (lib/rotation/energy_rotation.cpp): an accuracy fault, every else equal.
The faults of real work, for the counted gate (ci/count-gate), each in one phase:
assembly-work: the assembly does ITERATIONS more dependent multiply-adds per element (two
instructions each, unrolled: 6 of them add about 1.1% to the assembly's 1,152 instructions an
element).
extra-pass: every multigrid update reads the fine level's matrix once more after its Galerkin
products (a sum over its values): the update's instructions and misses grow.
scattered-order: energy-newton's rotations visit their batches of elements in a strided order
(b * 7919 modulo their count) instead of the locality order: the same work and the same bits, the
vertices' positions no longer shared by the batches that follow each other. (The assembly's order
cannot be planted so: each block's first store is fixed by the locality order.)
The patch is made against REF's file (default HEAD) and applied only in bench-gate's worktree:
the production code has no switch for it.
"""
import argparse
import difflib
import subprocess
import sys

CLOCK = "lib/fem/simulation_result.hpp"
ENERGY = "lib/rotation/energy_rotation.cpp"
ASSEMBLY = "lib/fem/corotated_assembly.cpp"
MULTIGRID = "lib/multigrid/multigrid_solver.cpp"


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


def assembly_work(ref, iterations):
    text = file_at(ref, ASSEMBLY)
    old = ("  for (std::size_t n = 0; n < list.size(); ++n) {\n"
           "    const int e = list[n];\n")
    new = old + ("    {  // planted work: a chain of dependent multiply-adds the compiler must keep\n"
                 "      double planted = static_cast<double>(n);\n"
                 f"      for (int k = 0; k < {iterations}; ++k) {{\n"
                 "        planted = planted * 1.0000001 + 1e-9;\n"
                 "        asm volatile(\"\" : \"+x\"(planted));\n"
                 "      }\n"
                 "    }\n")
    return ASSEMBLY, text, replaced(text, old, new, ASSEMBLY)


EXTRA_PASS = ("  {  // planted: the fine level's matrix read once more\n"
              "    double sum = 0;\n"
              "    for (double v : hierarchy_.matrix(0).values) sum += v;\n"
              "    asm volatile(\"\" : : \"x\"(sum));\n"
              "  }\n")


def extra_pass(ref):
    """After the update's Galerkin part, before the levels' update (two spellings of the code:
    before and after the solver's events)."""
    text = file_at(ref, MULTIGRID)
    for galerkin in ("  timed(SolverPart::Galerkin, [&] { hierarchy_.take_update(a, "
                     "params_.galerkin); });\n",
                     "    hierarchy_.update_coarse(params_.galerkin);\n  });\n"):
        old = galerkin + "  update_levels();\n"
        if text.count(old) == 1:
            new = galerkin + EXTRA_PASS + "  update_levels();\n"
            return MULTIGRID, text, replaced(text, old, new, MULTIGRID)
    return MULTIGRID, text, replaced(text, "(not found)", "", MULTIGRID)


def scattered_order(ref):
    text = file_at(ref, ENERGY)
    old = ("  for (int batch = 0; batch < batches; ++batch) {\n"
           "    const int first = batch * kNewtonLanes;\n")
    new = ("  for (int batch = 0; batch < batches; ++batch) {\n"
           "    // planted: the batches in a strided order (each independent: the same bits)\n"
           "    const int stride = batches % 7919 ? 7919 : 1;\n"
           "    const int first =\n"
           "        static_cast<int>(static_cast<long long>(batch) * stride % batches) * kNewtonLanes;\n")
    return ENERGY, text, replaced(text, old, new, ENERGY)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("kind", choices=["slowdown", "rotation-offset", "assembly-work",
                                         "extra-pass", "scattered-order"])
    parser.add_argument("values", nargs="*")
    parser.add_argument("--ref", default="HEAD")
    args = parser.parse_args()
    if args.kind == "slowdown":
        if len(args.values) != 2:
            parser.error("slowdown PHASE PERCENT")
        path, before, after = slowdown(args.ref, args.values[0], float(args.values[1]))
    elif args.kind == "rotation-offset":
        if len(args.values) != 1:
            parser.error("rotation-offset RADIANS")
        path, before, after = rotation_offset(args.ref, float(args.values[0]))
    elif args.kind == "assembly-work":
        if len(args.values) != 1:
            parser.error("assembly-work ITERATIONS")
        path, before, after = assembly_work(args.ref, int(args.values[0]))
    else:
        if args.values:
            parser.error(f"{args.kind} takes no values")
        path, before, after = (extra_pass if args.kind == "extra-pass" else scattered_order)(args.ref)
    sys.stdout.writelines(difflib.unified_diff(before.splitlines(True), after.splitlines(True),
                                               f"a/{path}", f"b/{path}"))


if __name__ == "__main__":
    main()
