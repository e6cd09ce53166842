#!/usr/bin/env python3
"""Where a multigrid hierarchy is weak, by a route independent of corofem's own cycle (issue 36).

Usage: bench/multigrid_diagnosis.py [--spectrum K] [--smoothed-prolongation] DIR [DIR...]      (needs python3-scipy)

DIR is what `corofem export-matrices SCENE.json --out DIR` writes: A<h>.mtx and R<h>.mtx (at least
two levels). With natural-order nodal 3x3 block Gauss-Seidel (forward before the coarse
correction, backward after) and a direct solve on the coarsest level, it prints per DIR:
  - the asymptotic energy-norm convergence factor of the two-grid and of the full V(1,1) cycle
    (power iteration from a random error; larger than the report's rho, which is a mean residual
    reduction over 12 cycles from a step's own right-hand side);
  - the two-grid factor with 1, 2 and 4 sweeps on each side (falling fast: smoother-limited;
    slowly: the coarse space is the limit);
  - where the slowest error lives: the share of its energy on the 1% of vertices holding most of
    it, how many of those lie outside their coarse tet (a negative transfer weight), how many
    clusters they form, and its Rayleigh quotient against the block diagonal (small: a smooth
    local mode that smoothing barely reduces);
  - with --smoothed-prolongation, the same with the first transfer smoothed as smoothed
    aggregation smooths its tentative one, P' = (I - w D^-1 A) P (D the 3x3 block diagonal,
    w = 4 / (3 lambda_max(D^-1 A))), the coarse operators formed again from it, and their size:
    whether a smoothed geometric prolongation (issue 36's candidate) would pay for its denser
    coarse operators;
  - with --spectrum K, the K largest eigenvalues of the V-cycle's error propagation E = I - B A
    (Arnoldi, scipy's eigs): a few isolated ones would be what CG (or a deflation of a few
    vectors) removes in a few iterations; a cluster of many is what bounds MG-PCG's iterations.
Progress and results on stdout; nothing is written.
"""
import argparse
import sys

import numpy as np
import scipy.io
import scipy.sparse as sp
import scipy.sparse.linalg as sl
from scipy.sparse.csgraph import connected_components


def block_triangle(a, lower):
    """The blocks on and below (or above) the block diagonal: Gauss-Seidel's sweep matrix."""
    c = a.tocoo()
    keep = c.row // 3 >= c.col // 3 if lower else c.row // 3 <= c.col // 3
    return sp.csc_matrix((c.data[keep], (c.row[keep], c.col[keep])), shape=a.shape)


def block_diagonal_inverse(a):
    """The inverse of A's 3x3 block diagonal, as a sparse matrix."""
    n = a.shape[0] // 3
    return sp.block_diag([np.linalg.inv(a[3 * i:3 * i + 3, 3 * i:3 * i + 3].toarray()) for i in range(n)],
                         format="csr")


def smoothed_restriction(a, r):
    """R' = P'^T for P' = (I - w D^-1 A) P, P = R^T: R' = R (I - w A D^-1) (A, D symmetric)."""
    d_inv = block_diagonal_inverse(a)
    v = np.random.default_rng(2).standard_normal(a.shape[0])
    for _ in range(30):  # power iteration for lambda_max(D^-1 A)
        v = d_inv @ (a @ v)
        v /= np.linalg.norm(v)
    lam = float(v @ (d_inv @ (a @ v)))
    w = 4 / (3 * lam)
    return sp.csr_matrix(r - w * ((r @ a) @ d_inv)), w


class Hierarchy:
    def __init__(self, folder, smooth_first=False):
        self.a = []
        h = 0
        while True:
            try:
                self.a.append(sp.csr_matrix(scipy.io.mmread(f"{folder}/A{h}.mtx")))
            except FileNotFoundError:
                break
            h += 1
        self.r = [sp.csr_matrix(scipy.io.mmread(f"{folder}/R{h}.mtx")) for h in range(len(self.a) - 1)]
        if len(self.a) < 2:
            sys.exit(f"{folder}: needs A0.mtx, A1.mtx and R0.mtx (corofem export-matrices)")
        self.blocks_before = [a.nnz // 9 for a in self.a]
        if smooth_first:
            self.r[0], self.omega = smoothed_restriction(self.a[0], self.r[0])
            for h in range(len(self.r)):
                self.a[h + 1] = sp.csr_matrix(self.r[h] @ self.a[h] @ self.r[h].T)
        lu = lambda m: sl.splu(m, permc_spec="NATURAL", diag_pivot_thresh=0)
        self.forward = [lu(block_triangle(a, True)) for a in self.a]
        self.backward = [lu(block_triangle(a, False)) for a in self.a]
        self.direct = [sl.splu(a.tocsc()) for a in self.a]

    def cycle(self, h, b, last, sweeps):
        """x ~ A_h^-1 b by one V-cycle down to `last` (solved directly)."""
        a = self.a[h]
        if h == last:
            return self.direct[h].solve(b)
        x = self.forward[h].solve(b)
        for _ in range(sweeps - 1):
            x = x + self.forward[h].solve(b - a @ x)
        x = x + self.r[h].T @ self.cycle(h + 1, self.r[h] @ (b - a @ x), last, sweeps)
        for _ in range(sweeps):
            x = x + self.backward[h].solve(b - a @ x)
        return x

    def slowest(self, last, sweeps=1, iterations=30):
        """The asymptotic factor (geometric mean of the last 8 reductions) and the error then."""
        a = self.a[0]
        norm = lambda v: np.sqrt(v @ (a @ v))
        e = np.random.default_rng(1).standard_normal(a.shape[0])
        ratios = []
        for _ in range(iterations):
            before = norm(e)
            e = e - self.cycle(0, a @ e, last, sweeps)
            ratios.append(norm(e) / before)
            e /= norm(e)
        return float(np.exp(np.mean(np.log(ratios[-8:])))), e


def diagnose(folder, smooth_first=False):
    m = Hierarchy(folder, smooth_first)
    a, n = m.a[0], m.a[0].shape[0] // 3
    levels = len(m.a)
    two_grid, e = m.slowest(1)
    full = m.slowest(levels - 1)[0] if levels > 2 else two_grid
    print(f"{folder}: {levels} levels, {n} fine vertices")
    if smooth_first:
        print(f"  first prolongation smoothed (w = {m.omega:.3f}): coarse blocks per level " +
              " / ".join(f"{b} -> {a.nnz // 9}" for b, a in zip(m.blocks_before[1:], m.a[1:])) +
              f", transfer entries {m.r[0].nnz}")
    print(f"  two-grid factor {two_grid:.3f}, V-cycle over all levels {full:.3f}")
    print(f"  two-grid with 1 / 2 / 4 sweeps each side: {two_grid:.3f} / " +
          " / ".join(f"{m.slowest(1, s)[0]:.3f}" for s in (2, 4)))
    energy = np.abs((e * (a @ e)).reshape(n, 3).sum(axis=1))
    top = np.argsort(-energy)[: max(10, n // 100)]
    p = m.r[0].T.tocoo()
    outside = np.zeros(n, bool)
    outside[p.row[p.data < -1e-12] // 3] = True
    c = a.tocoo()
    graph = sp.csr_matrix((np.ones(len(c.row)), (c.row // 3, c.col // 3)), shape=(n, n))
    clusters, label = connected_components(graph[top][:, top], directed=False)
    shares = sorted((energy[top][label == k].sum() / energy.sum() for k in range(clusters)), reverse=True)
    blocks = sp.block_diag([a[3 * i:3 * i + 3, 3 * i:3 * i + 3].toarray() for i in range(n)], format="csr")
    print(f"  slowest error: {energy[top].sum() / energy.sum():.1%} of its energy on {len(top)} vertices "
          f"(1%), {outside[top].mean():.0%} of them outside their coarse tet ({outside.mean():.0%} of all "
          f"vertices are), in {clusters} clusters (the largest holds {shares[0]:.0%}); Rayleigh quotient "
          f"against the block diagonal {float(e @ (a @ e)) / float(e @ (blocks @ e)):.3f}")


def spectrum(folder, k):
    """The k largest eigenvalues of the full V-cycle's error propagation on the fine level."""
    m = Hierarchy(folder)
    a, last = m.a[0], len(m.a) - 1
    propagate = sl.LinearOperator(a.shape, matvec=lambda v: v - m.cycle(0, a @ v, last, 1), dtype=float)
    mu = np.sort(np.real(sl.eigs(propagate, k=k, which="LM", ncv=max(2 * k + 1, 100), tol=1e-6,
                                 return_eigenvectors=False)))[::-1]
    print(f"{folder}: the {k} largest eigenvalues of E = I - B A (the V-cycle's error propagation): "
          f"{mu[0]:.3f} ... {mu[-1]:.3f}")
    print("  how many lie above 0.3 / 0.5 / 0.6 / 0.7 / 0.8: " +
          " / ".join(str(int(np.sum(mu > t))) for t in (0.3, 0.5, 0.6, 0.7, 0.8)) +
          (f" (all {k} computed lie above {mu[-1]:.3f}: more lie beyond)" if mu[-1] > 0.3 else ""))


if __name__ == "__main__":
    parser = argparse.ArgumentParser(usage=__doc__)
    parser.add_argument("--spectrum", type=int, default=0, metavar="K")
    parser.add_argument("--smoothed-prolongation", action="store_true")
    parser.add_argument("folders", nargs="+", metavar="DIR")
    args = parser.parse_args()
    for folder in args.folders:
        if args.spectrum:
            spectrum(folder, args.spectrum)
        else:
            diagnose(folder, args.smoothed_prolongation)
