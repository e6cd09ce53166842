#!/usr/bin/env python3
"""Where a multigrid hierarchy is weak, by a route independent of corofem's own cycle (issue 36).

Usage: bench/multigrid_diagnosis.py [--spectrum K] [--smoothed-prolongation] [--rigid-enrichment N]
                                    [--thin-patches K] [--thin-coarse K] [--outside-coarse]
                                    DIR [DIR...]
                                    (needs python3-scipy)

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
  - what the slowest error's vertices are: their neighbour counts against the mesh's, and (with
    X0.mtx, the fine positions) how far the largest clusters' error is from a rigid motion and from
    an affine field (least-squares misfit, 0 = exactly rigid): near-rigid motions of a feature are
    what a coarse space with that feature's rigid-body modes would remove;
  - with --rigid-enrichment N (needs X0.mtx), the two-grid factor with a second coarse correction
    before and after the first: the rigid-body modes of aggregates of at most N vertices (greedy
    balls in the matrix graph, 6 modes each), once on the vertices outside their coarse tet only,
    once on all: whether the coarse space lacks piecewise-rigid motions;
  - with --thin-patches K, the two-grid and V-cycle factors with a patch smoother beside the block
    Gauss-Seidel sweeps: exact solves on patches of at most 40 vertices covering the vertices with at
    most K neighbours and their neighbours (thin features: spikes and fins one or two elements
    thick), forward before the coarse correction and backward after, and what their dense
    factorizations cost: whether a smoother that solves thin features locally would reach the
    slowest error;
  - with --thin-coarse K, the two-grid factor at 1 and 2 sweeps with the thin features' vertices
    themselves added to the first coarse space, P = [P_mesh, I_T], T the vertices with at most K
    neighbours (then grown by one ring), the coarse problem solved exactly: the limit of a coarse
    mesh that keeps every thin feature at the fine resolution, and how large its coarse level is;
  - with --outside-coarse, the same with the vertices outside their coarse tet (the extrapolated
    ones) added instead: the best two-grid factor any transfer that changes only their rows of P
    could give (the factor only falls as the coarse space grows), and the same for as many
    vertices drawn at random and drawn from those inside their coarse tet (controls);
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


def read_positions(folder):
    """The fine vertices' positions (n x 3) from X0.mtx, or None when the folder has none."""
    try:
        return scipy.io.mmread(f"{folder}/X0.mtx").toarray()
    except FileNotFoundError:
        return None


def vertex_graph(a):
    """The vertices' adjacency (the 3x3 blocks' pattern), diagonal included."""
    n = a.shape[0] // 3
    c = a.tocoo()
    return sp.csr_matrix((np.ones(len(c.row)), (c.row // 3, c.col // 3)), shape=(n, n))


def aggregates(graph, members, size):
    """Greedy breadth-first balls of at most `size` of the `members` vertices, in index order."""
    label = -np.ones(graph.shape[0], int)
    count = 0
    for seed in np.flatnonzero(members):
        if label[seed] >= 0:
            continue
        label[seed] = count
        taken, front = 1, [seed]
        while front and taken < size:
            grown = []
            for u in front:
                for w in graph.indices[graph.indptr[u]:graph.indptr[u + 1]]:
                    if members[w] and label[w] < 0 and taken < size:
                        label[w] = count
                        taken += 1
                        grown.append(w)
            front = grown
        count += 1
    order = np.argsort(label, kind="stable")[np.sum(label < 0):]  # members by aggregate
    return np.split(order, np.cumsum(np.bincount(label[order], minlength=count))[:-1])


def motion_basis(x, kind):
    """Columns of the translations, + rotations (rigid), + the 9 linear fields (affine) about the
    points' centre, DOF 3 v + c."""
    d = x - x.mean(axis=0)
    fields = []
    for c in range(3):
        f = np.zeros_like(d)
        f[:, c] = 1
        fields.append(f)
    if kind in ("rigid", "affine"):
        for i, j in ((0, 1), (1, 2), (2, 0)):
            f = np.zeros_like(d)
            f[:, i], f[:, j] = -d[:, j], d[:, i]
            fields.append(f)
    if kind == "affine":
        for i in range(3):
            for j in range(3):
                f = np.zeros_like(d)
                f[:, i] = d[:, j]
                fields.append(f)
    return np.array([f.ravel() for f in fields]).T


def misfit(x, e, vertices, kind):
    """|e - its least-squares fit by `kind` motions| / |e| on the vertices."""
    basis = motion_basis(x[vertices], kind)
    y = e.reshape(-1, 3)[vertices].ravel()
    fit = basis @ np.linalg.lstsq(basis, y, rcond=None)[0]
    return np.linalg.norm(y - fit) / np.linalg.norm(y)


def rigid_enrichment(a, x, groups):
    """The extra coarse correction x += Q (Q^T A Q)^-1 Q^T r, Q the orthonormalized rigid-body modes
    of each group of vertices (groups under 3 vertices skipped), and Q's column count."""
    rows, cols, vals = [], [], []
    for vertices in groups:
        if len(vertices) < 3:
            continue
        q, r = np.linalg.qr(motion_basis(x[vertices], "rigid"))
        q = q[:, np.abs(np.diag(r)) > 1e-8 * abs(r[0, 0])]
        dofs = (3 * vertices[:, None] + np.arange(3)).ravel()
        for column in q.T:
            rows.append(dofs)
            cols.append(np.full(len(dofs), len(cols)))
            vals.append(column)
    if not cols:  # no group of 3 vertices or more (no vertex outside the coarse mesh)
        return (lambda v, b: v), 0
    q = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                      shape=(a.shape[0], len(cols)))
    solve = sl.splu(sp.csc_matrix(q.T @ a @ q)).solve
    return (lambda v, b: v + q @ solve(q.T @ (b - a @ v))), len(cols)


def thin_vertices(graph, neighbours, rings):
    """The vertices with at most `neighbours` neighbours, grown by `rings` rings of neighbours."""
    thin = np.diff(graph.indptr) - 1 <= neighbours
    for _ in range(rings):
        thin = thin | (graph @ thin.astype(float) > 0)
    return thin


def thin_patches(a, neighbours):
    """Forward and backward patch sweeps (exact solves) over patches of at most 40 vertices covering
    the vertices with at most `neighbours` neighbours and their neighbours, the number of patch
    vertices and the patches' dense Cholesky flops."""
    graph = vertex_graph(a)
    thin = thin_vertices(graph, neighbours, 1)
    factors = []
    for vertices in aggregates(graph, thin, 40):
        dofs = (3 * vertices[:, None] + np.arange(3)).ravel()
        factors.append((dofs, np.linalg.cholesky(a[dofs][:, dofs].toarray())))

    def sweep(order):
        def apply(v, b):
            v = v.copy()
            for dofs, chol in factors[::order]:
                y = np.linalg.solve(chol, b[dofs] - a[dofs] @ v)
                v[dofs] += np.linalg.solve(chol.T, y)
            return v
        return apply
    flops = sum(len(d) ** 3 / 3 for d, _ in factors)
    return sweep(1), sweep(-1), int(thin.sum()), flops


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
        # Optional fine-level corrections beside the sweeps: (v, b) -> v, after the forward sweep
        # and before the backward one.
        self.before_coarse = self.after_coarse = None

    def replace_first_transfer(self, r):
        """R0 := r and A1 := r A0 r^T, for two-grid factors only (the levels below stay as read)."""
        self.r[0] = r
        self.a[1] = sp.csr_matrix(r @ self.a[0] @ r.T)
        self.direct[1] = sl.splu(self.a[1].tocsc())

    def cycle(self, h, b, last, sweeps):
        """x ~ A_h^-1 b by one V-cycle down to `last` (solved directly)."""
        a = self.a[h]
        if h == last:
            return self.direct[h].solve(b)
        x = self.forward[h].solve(b)
        for _ in range(sweeps - 1):
            x = x + self.forward[h].solve(b - a @ x)
        if h == 0 and self.before_coarse:
            x = self.before_coarse(x, b)
        x = x + self.r[h].T @ self.cycle(h + 1, self.r[h] @ (b - a @ x), last, sweeps)
        if h == 0 and self.after_coarse:
            x = self.after_coarse(x, b)
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


def diagnose(folder, smooth_first=False, enrichment=0, patches=0, coarse_thin=0,
             coarse_outside=False):
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
    graph = vertex_graph(a)
    clusters, label = connected_components(graph[top][:, top], directed=False)
    cluster_energy = np.bincount(label, weights=energy[top])
    largest = np.argsort(-cluster_energy)  # clusters, most energy first
    shares = cluster_energy[largest] / energy.sum()
    degree = np.diff(graph.indptr) - 1
    blocks = sp.block_diag([a[3 * i:3 * i + 3, 3 * i:3 * i + 3].toarray() for i in range(n)], format="csr")
    print(f"  slowest error: {energy[top].sum() / energy.sum():.1%} of its energy on {len(top)} vertices "
          f"(1%), {outside[top].mean():.0%} of them outside their coarse tet ({outside.mean():.0%} of all "
          f"vertices are), in {clusters} clusters (the largest holds {shares[0]:.0%}); Rayleigh quotient "
          f"against the block diagonal {float(e @ (a @ e)) / float(e @ (blocks @ e)):.3f}")
    print(f"  its vertices have {np.median(degree[top]):.0f} neighbours (median; the mesh's "
          f"{np.median(degree):.0f}), {np.mean(degree[top] <= 6):.0%} of them at most 6 "
          f"({np.mean(degree <= 6):.0%} of all vertices)")
    x = read_positions(folder)
    if x is not None:
        print("  the largest clusters' error, misfit by a rigid / an affine motion: " + ", ".join(
            f"{len(top[label == k])} vertices {misfit(x, e, top[label == k], 'rigid'):.2f} / "
            f"{misfit(x, e, top[label == k], 'affine'):.2f}" for k in largest[:3]))
    if enrichment:
        if x is None:
            sys.exit(f"{folder}: --rigid-enrichment needs X0.mtx (corofem export-matrices writes it)")
        for name, members in (("outside their coarse tet", outside), ("all", np.ones(n, bool))):
            correct, columns = rigid_enrichment(a, x, aggregates(graph, members, enrichment))
            m.before_coarse = m.after_coarse = correct
            print(f"  rigid-body modes of aggregates of at most {enrichment} vertices ({name}, "
                  f"{columns} columns) as a second coarse correction: two-grid {m.slowest(1)[0]:.3f}")
        m.before_coarse = m.after_coarse = None
    if patches:
        m.before_coarse, m.after_coarse, covered, flops = thin_patches(a, patches)
        print(f"  patch solves on thin features (at most {patches} neighbours, grown one ring: "
              f"{covered} vertices, {covered / n:.0%}; {flops / 1e6:.0f} MFlop of factorization): "
              f"two-grid {m.slowest(1)[0]:.3f}, V-cycle over all levels {m.slowest(levels - 1)[0]:.3f}")
        m.before_coarse = m.after_coarse = None
    # Last: these replace the first transfer.
    r0 = m.r[0]
    if coarse_thin:
        for rings in (0, 1):
            thin = np.flatnonzero(thin_vertices(graph, coarse_thin, rings))
            print(f"  thin vertices (at most {coarse_thin} neighbours, grown {rings} ring(s): "
                  f"{len(thin)}, {len(thin) / n:.0%}) " + vertices_in_coarse_space(m, r0, thin))
    if coarse_outside:
        outside_vertices = np.flatnonzero(outside)
        print(f"  the vertices outside their coarse tet ({len(outside_vertices)}, "
              f"{len(outside_vertices) / n:.0%}) " + vertices_in_coarse_space(m, r0, outside_vertices))
        # Controls: whether it is these vertices or any as many.
        draw = np.random.default_rng(3)
        for name, pool in (("at random", np.arange(n)),
                           ("from those inside their coarse tet", np.flatnonzero(~outside))):
            chosen = np.sort(draw.choice(pool, min(len(outside_vertices), len(pool)), replace=False))
            print(f"  as many vertices drawn {name} " + vertices_in_coarse_space(m, r0, chosen))


def vertices_in_coarse_space(m, r0, vertices):
    """Adds the vertices' own DOFs to the first coarse space, P = [P_mesh, I_V], and says what the
    two-grid cycle does then. The two-grid factor only falls as the coarse space grows (its
    symmetrized error propagation S* (I - pi) S is monotone in pi's range), so this is a bound for
    every transfer that changes only these vertices' rows of P."""
    a = m.a[0]
    dofs = (3 * vertices[:, None] + np.arange(3)).ravel()
    injection = sp.csr_matrix((np.ones(len(dofs)), (np.arange(len(dofs)), dofs)),
                              shape=(len(dofs), a.shape[0]))
    m.replace_first_transfer(sp.vstack([r0, injection]).tocsr())
    return (f"added to the first coarse space: {r0.shape[0]} + {len(dofs)} coarse DOFs, "
            f"{m.a[1].nnz // 9} coarse blocks (the fine level's {a.nnz // 9}); two-grid "
            f"{m.slowest(1)[0]:.3f}, at 2 sweeps {m.slowest(1, 2)[0]:.3f}")


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
    parser = argparse.ArgumentParser(usage=__doc__.replace("%", "%%"))
    parser.add_argument("--spectrum", type=int, default=0, metavar="K")
    parser.add_argument("--smoothed-prolongation", action="store_true")
    parser.add_argument("--rigid-enrichment", type=int, default=0, metavar="N")
    parser.add_argument("--thin-patches", type=int, default=0, metavar="K")
    parser.add_argument("--thin-coarse", type=int, default=0, metavar="K")
    parser.add_argument("--outside-coarse", action="store_true")
    parser.add_argument("folders", nargs="+", metavar="DIR")
    args = parser.parse_args()
    for folder in args.folders:
        if args.spectrum:
            spectrum(folder, args.spectrum)
        else:
            diagnose(folder, args.smoothed_prolongation, args.rigid_enrichment, args.thin_patches,
                     args.thin_coarse, args.outside_coarse)
