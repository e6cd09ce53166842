#!/usr/bin/env python3
"""The two-grid factor of corofem's smoothers on the ideal hierarchy, built without corofem (issue 36).

Usage: bench/nested_two_grid.py [--cells N [N ...]] [--poisson NU] [--sweeps S [S ...]]
                                [--mass-ratio M [M ...]] [--chebyshev DEGREE [DEGREE ...]]
                                [--lower L] [--drop-face-vertices] [--pcg TOL] [--json FILE]
                                (needs python3-scipy)

Issue 36 asks for a default cycle with rho <= 0.3. The best a V-cycle can do is its two-grid cycle
(the coarse level solved exactly), and the best hierarchy for P1 transfers is a nested one: then
P^T K_h P is the coarse mesh's own stiffness and nothing is extrapolated. This script builds that
case from scratch, sharing no code with corofem: the unit cube in N^3 Kuhn cells (six tets around
each cell's main diagonal, vertex (i, j, k) numbered i + (N+1)(j + (N+1)k), as corofem's
make_box_mesh), the cube in (N/2)^3 cells as the coarse level (Kuhn cells refine into Kuhn cells:
nested; checked by P^T K_h P = K_H), linear elasticity with E = 1 and Poisson ratio NU, the face
x = 0 clamped (as corofem's multigrid gates clamp it), P1 interpolation as the prolongation and its
transpose as the restriction. The coarse vertices on the clamped face stay in the coarse space
(their hat functions taken at the free fine vertices), as corofem's transfer keeps them;
--drop-face-vertices removes them instead (the coarse space of a clamped coarse mesh).

Smoothers, before the coarse correction and, transposed, after it:
  - S sweeps of nodal 3x3 block Gauss-Seidel in vertex order (corofem's sequential ordering, and
    its hybrid one on meshes of a single domain), the backward sweep the exact reverse;
  - with --chebyshev DEGREE, corofem's Chebyshev smoother: DEGREE steps of the Chebyshev iteration
    for M^-1 A on [--lower, 1], M the l1 block-Jacobi diagonal (linalg/chebyshev_smoother.hpp).
--mass-ratio M adds M x mean(diag K) to the diagonal: a lumped mass term, as in a time step's
(1 + dt alpha) M + dt^2 K. In the report's model scenes (dt = 0.01, E = 1e5, density 1000) the
mass is 0.0068 of the stiffness's diagonal on the dragon, 0.0091 on the horse and 0.051 on the
bunny (their first step's A0 exported at density 1000 and 2000, 2026-12-05).

Prints, for every combination, the two-grid error propagation's energy-norm spectral radius (power
iteration from a random error, 300 steps): the smallest rho any cycle with that smoother and
these transfers can have; with --pcg TOL, how many CG iterations that cycle takes as the
preconditioner to a relative residual TOL from zero under a uniform body force (the fewest MG-PCG
can take on this body). Cross-check with corofem: BM_NestedTwoGrid/<N>/<mass per mille> runs
corofem's own two-grid cycle on the same boxes, smoothers and masses (at 16^3 every factor within
0.003 of this script's and every CG iteration count equal, 2026-12-05), and
MultigridSolver.TwoGridEqualsDenseOperator prints the spectral radius of corofem's two-grid
operator on the nested 4^3 box (0.5589; this script with --cells 4: 0.559).
"""
import argparse
import itertools
import json
import os
import platform
import subprocess
import sys

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as sl

# The six monotone lattice paths from a cell's corner 000 to 111: the Kuhn split.
PATHS = list(itertools.permutations(range(3)))
GRADIENTS = np.array([[-1, 1, 0, 0], [-1, 0, 1, 0], [-1, 0, 0, 1]], float)


def vertex_index(n):
    return lambda i, j, k: i + (n + 1) * (j + (n + 1) * k)


def kuhn_cube(n):
    """Vertices (x fastest) and tets of the unit cube in n^3 Kuhn cells."""
    index = vertex_index(n)
    g = np.arange(n + 1) / n
    z, y, x = np.meshgrid(g, g, g, indexing="ij")
    points = np.column_stack([x.ravel(), y.ravel(), z.ravel()])
    tets = []
    for k in range(n):
        for j in range(n):
            for i in range(n):
                for path in PATHS:
                    corner = [i, j, k]
                    tet = [index(*corner)]
                    for axis in path:
                        corner[axis] += 1
                        tet.append(index(*corner))
                    tets.append(tet)
    return points, np.array(tets)


def elasticity(nu):
    lam, mu = nu / ((1 + nu) * (1 - 2 * nu)), 1 / (2 * (1 + nu))
    d = np.zeros((6, 6))
    d[:3, :3] = lam
    d[range(3), range(3)] += 2 * mu
    d[range(3, 6), range(3, 6)] = mu
    return d


def stiffness(points, tets, d):
    """Linear-tet elasticity stiffness, DOF 3 * vertex + component."""
    rows, cols, values = [], [], []
    for tet in tets:
        jac = (points[tet[1:]] - points[tet[0]]).T
        volume = abs(np.linalg.det(jac)) / 6
        grad = np.linalg.inv(jac).T @ GRADIENTS  # 3 x 4: the hat functions' gradients
        b = np.zeros((6, 12))
        for a in range(4):
            gx, gy, gz = grad[:, a]
            b[0, 3 * a], b[1, 3 * a + 1], b[2, 3 * a + 2] = gx, gy, gz
            b[3, 3 * a], b[3, 3 * a + 1] = gy, gx
            b[4, 3 * a + 1], b[4, 3 * a + 2] = gz, gy
            b[5, 3 * a], b[5, 3 * a + 2] = gz, gx
        dofs = (3 * np.repeat(tet, 3) + np.tile(range(3), 4))
        rows.append(np.repeat(dofs, 12))
        cols.append(np.tile(dofs, 12))
        values.append((volume * b.T @ d @ b).ravel())
    size = 3 * len(points)
    return sp.csr_matrix((np.concatenate(values), (np.concatenate(rows), np.concatenate(cols))),
                         shape=(size, size))


def prolongation(n):
    """P1 interpolation of the (n/2)^3 Kuhn cube's hat functions at the n^3 cube's vertices."""
    m = n // 2
    index = vertex_index(m)
    fine, _ = kuhn_cube(n)
    rows, cols, values = [], [], []
    for f, x in enumerate(fine):
        y = x * m
        cell = np.minimum(np.floor(y + 1e-12).astype(int), m - 1)
        local = y - cell
        # The Kuhn tet holding the point: its path follows the local coordinates, largest first.
        order = np.argsort(-local, kind="stable")
        corner = list(cell)
        weights = [1 - local[order[0]]]
        vertices = [index(*corner)]
        for s in range(3):
            corner[order[s]] += 1
            vertices.append(index(*corner))
            weights.append(local[order[s]] - (local[order[s + 1]] if s < 2 else 0))
        for v, w in zip(vertices, weights):
            if abs(w) > 1e-14:
                for c in range(3):
                    rows.append(3 * f + c)
                    cols.append(3 * v + c)
                    values.append(w)
    return sp.csr_matrix((values, (rows, cols)), shape=(3 * len(fine), 3 * (m + 1) ** 3))


def block_lower(a):
    """The nodal block lower triangle D + L of A (blocks with row vertex >= column vertex)."""
    c = a.tocoo()
    keep = c.row // 3 >= c.col // 3
    return sp.csr_matrix((c.data[keep], (c.row[keep], c.col[keep])), shape=a.shape)


def l1_block_diagonal(a):
    """M = blockdiag(A_ii + diag(row sums of |A| outside the block)): corofem's Chebyshev M."""
    c = a.tocoo()
    inside = c.row // 3 == c.col // 3
    outside = np.zeros(a.shape[0])
    np.add.at(outside, c.row[~inside], np.abs(c.data[~inside]))
    m = sp.csr_matrix((c.data[inside], (c.row[inside], c.col[inside])), shape=a.shape)
    return (m + sp.diags(outside)).tocsc()


def gauss_seidel(a, sweeps):
    """Pre- and post-smoother as maps (x, b) -> x + N (b - A x), repeated `sweeps` times."""
    forward, backward = sl.splu(block_lower(a).tocsc()), sl.splu(block_lower(a).T.tocsc())

    def pre(x, b):
        for _ in range(sweeps):
            x = x + forward.solve(b - a @ x)
        return x

    def post(x, b):
        for _ in range(sweeps):
            x = x + backward.solve(b - a @ x)
        return x
    return pre, post


def chebyshev(a, degree, lower):
    """The Chebyshev iteration for M^-1 A on [lower, 1]: the same polynomial before and after
    (M^-1 A is self-adjoint in the M inner product)."""
    m = sl.splu(l1_block_diagonal(a))
    theta, delta = (1 + lower) / 2, (1 - lower) / 2
    sigma = theta / delta

    def smooth(x, b):
        rho = 1 / sigma
        d = m.solve(b - a @ x) / theta
        for step in range(degree):
            x = x + d
            if step + 1 == degree:
                break
            rho_next = 1 / (2 * sigma - rho)
            d = rho_next * rho * d + 2 * rho_next / delta * m.solve(b - a @ x)
            rho = rho_next
        return x
    return smooth, smooth


def two_grid_cycle(a, p, pre, post):
    """One two-grid cycle for A x = b from x: (x, b) -> x'."""
    coarse = sl.splu((p.T @ a @ p).tocsc())

    def cycle(x, b):
        x = pre(x, b)
        x = x + p @ coarse.solve(p.T @ (b - a @ x))
        return post(x, b)
    return cycle


def two_grid_factor(a, cycle, steps=300, seed=0):
    """The energy-norm spectral radius of the cycle's error propagation (power iteration on
    A e = 0)."""
    e = np.random.default_rng(seed).standard_normal(a.shape[0])
    zero = np.zeros_like(e)
    rho = 0.0
    for _ in range(steps):
        energy = e @ (a @ e)
        e = cycle(e, zero)
        rho = np.sqrt((e @ (a @ e)) / energy)
        e /= np.sqrt(e @ (a @ e))
    return rho


def pcg_iterations(a, cycle, b, tolerance, most=500):
    """CG on A x = b from x = 0, preconditioned by one cycle from z = 0 (symmetric: the
    post-smoother is the pre-smoother's adjoint), to |r| <= tolerance |b|."""
    x, r = np.zeros_like(b), b.copy()
    z = cycle(np.zeros_like(b), r)
    d, rz = z.copy(), r @ z
    for iteration in range(1, most + 1):
        q = a @ d
        alpha = rz / (d @ q)
        x += alpha * d
        r -= alpha * q
        if np.linalg.norm(r) <= tolerance * np.linalg.norm(b):
            return iteration
        z = cycle(np.zeros_like(b), r)
        rz, rz_old = r @ z, rz
        d = z + rz / rz_old * d
    return None


def context():
    """What produced a record: the checkout's commit, the machine, the libraries."""
    here = os.path.dirname(os.path.abspath(__file__))
    try:
        commit = subprocess.run(["git", "-C", here, "describe", "--always", "--dirty"],
                                capture_output=True, text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        commit = "unknown"
    import scipy
    return {"commit": commit, "machine": platform.node(), "processor": platform.machine(),
            "cpus": os.cpu_count(), "python": platform.python_version(),
            "numpy": np.__version__, "scipy": scipy.__version__}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--cells", type=int, nargs="+", default=[4, 8, 16])
    parser.add_argument("--poisson", type=float, default=0.3)
    parser.add_argument("--sweeps", type=int, nargs="+", default=[1, 2, 3])
    parser.add_argument("--mass-ratio", type=float, nargs="+", default=[0.0])
    parser.add_argument("--chebyshev", type=int, nargs="*", default=[])
    parser.add_argument("--lower", type=float, default=0.1)
    parser.add_argument("--drop-face-vertices", action="store_true")
    parser.add_argument("--pcg", type=float, default=0.0,
                        help="also count CG iterations to this relative residual, preconditioned "
                             "by the two-grid cycle, under a uniform body force")
    parser.add_argument("--json", help="also write the rows to this file (via a temporary file)")
    args = parser.parse_args()
    if any(n < 2 or n % 2 for n in args.cells):
        sys.exit("nested_two_grid.py: --cells takes even numbers of at least 2")
    rows = []
    d = elasticity(args.poisson)
    for n in args.cells:
        fine_points, fine_tets = kuhn_cube(n)
        coarse_points, coarse_tets = kuhn_cube(n // 2)
        k = stiffness(fine_points, fine_tets, d)
        p_all = prolongation(n)
        k_coarse = stiffness(coarse_points, coarse_tets, d)
        nested_error = abs(p_all.T @ k @ p_all - k_coarse).max() / abs(k_coarse).max()
        free = np.repeat(fine_points[:, 0] > 1e-12, 3)
        p = p_all[free]
        if args.drop_face_vertices:
            p = p[:, np.repeat(coarse_points[:, 0] > 1e-12, 3)]
        else:  # the coarse vertices that still support a free fine vertex
            p = p[:, np.asarray(abs(p).sum(axis=0)).ravel() > 0]
        p = p.tocsr()
        for mass in args.mass_ratio:
            a = k[free][:, free].tocsr()
            if mass > 0:
                a = (a + mass * a.diagonal().mean() * sp.identity(a.shape[0])).tocsr()
            smoothers = [(f"Gauss-Seidel V({s},{s})", gauss_seidel(a, s)) for s in args.sweeps]
            smoothers += [(f"Chebyshev-{g} on [{args.lower}, 1]", chebyshev(a, g, args.lower))
                          for g in args.chebyshev]
            # A uniform body force along -z (gravity): the right-hand side of a sagging body.
            load = np.tile([0.0, 0.0, -1.0], a.shape[0] // 3)
            for name, (pre, post) in smoothers:
                cycle = two_grid_cycle(a, p, pre, post)
                rho = two_grid_factor(a, cycle)
                iterations = pcg_iterations(a, cycle, load, args.pcg) if args.pcg else None
                row = {"cells": n, "poisson": args.poisson, "mass_ratio": mass, "smoother": name,
                       "fine_dofs": a.shape[0], "coarse_dofs": p.shape[1],
                       "nested_error": nested_error, "two_grid_rho": rho,
                       "pcg_tolerance": args.pcg, "pcg_iterations": iterations}
                rows.append(row)
                print(f"{n:3d}^3 cells, nu {args.poisson}, mass {mass:g}: {name}: two-grid rho "
                      f"{rho:.3f} ({a.shape[0]} fine DOFs, {p.shape[1]} coarse; max |P^T K P - K_H| / "
                      f"max |K_H| {nested_error:.1e})" +
                      (f"; two-grid PCG to {args.pcg:g}: {iterations} iterations" if args.pcg
                       else ""), flush=True)
    if args.json:
        record = {"produced_by": "bench/nested_two_grid.py", "context": context(),
                  "arguments": vars(args), "rows": rows}
        temporary = args.json + ".tmp"
        with open(temporary, "w") as out:
            json.dump(record, out, indent=1)
        os.replace(temporary, args.json)


if __name__ == "__main__":
    main()
