"""Benchmark of the 2D contact model (woundroll.contact.indent); not a test.

Prints
1. the time of one contact solve at the default mesh (PET1 roll, 10 mm head, 1 mm depth),
2. solve time against mesh size (all element sizes divided by a factor, growth ratios
   raised to 1/factor) with the fitted scaling exponent t ~ n_dof^p,
3. the stiffness assembly: the vectorised assembler (geometric element matrices once, one
   fused multiply-add and a bincount per increment) against a straightforward
   loop-over-elements assembly of the same matrix (2x2 Gauss points, rotated orthotropic D,
   B^T D B, scatter into a dict-of-keys sparse matrix), with their agreement.

Run: ``.venv/bin/python benchmarks/bench_contact.py``.
"""

from __future__ import annotations

import math
import time

import numpy as np
import scipy.sparse as sp

from woundroll.contact import ContactOptions, indent
from woundroll.contact.fem import plane_strain_moduli
from woundroll.contact.mesh import build_mesh
from woundroll.contact.solver import _Roll
from woundroll.materials import Core, Pfeiffer, Web

R_CORE, R_OUT, H = 0.0445, 0.1334, 1e-4
WEB = Web(thickness=H, width=0.1524, E_theta=5681e6, radial_modulus=Pfeiffer(4.62e3, 123.88))
CORE = Core(outer_radius=R_CORE)
RADIUS = np.linspace(R_CORE, R_OUT, 400)
SIGMA_R = -(30e3 + 1e6 * (R_OUT - RADIUS) / (R_OUT - R_CORE))
HEAD = {"head_radius": 0.01, "head_length": 0.02, "depth_max": 1e-3}


def best_of(fn, repeat: int = 3) -> tuple[float, object]:
    best, out = math.inf, None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out


def refined_options(factor: float) -> ContactOptions:
    d = ContactOptions()
    R_eff = 1 / (1 / HEAD["head_radius"] + 1 / R_OUT)
    t_size = max(H / 4, math.sqrt(2 * R_eff * HEAD["depth_max"]) / 40)
    return ContactOptions(surface_size=H / factor, tangential_size=t_size / factor,
                          radial_growth=d.radial_growth ** (1 / factor),
                          tangential_growth=d.tangential_growth ** (1 / factor))


def loop_assembly(roll: _Roll, E_r: np.ndarray) -> sp.csc_matrix:
    """The textbook assembly: one element at a time (the reference for the speed-up)."""
    mesh = roll.mesh
    xy, conn, ang = mesh.node_xy(), mesh.connectivity(), mesh.node_angle()
    C11, C12, C22, G = plane_strain_moduli(WEB, E_r)
    g = 1 / math.sqrt(3)
    xi_n, eta_n = np.array([-1.0, 1, 1, -1]), np.array([-1.0, -1, 1, 1])
    K = sp.dok_matrix((2 * mesh.n_nodes, 2 * mesh.n_nodes))
    for e, nodes in enumerate(conn):
        X = xy[nodes]
        R = np.zeros((8, 8))           # nodal polar -> Cartesian
        for a in range(4):
            c, s = math.cos(ang[nodes[a]]), math.sin(ang[nodes[a]])
            R[2 * a:2 * a + 2, 2 * a:2 * a + 2] = [[c, -s], [s, c]]
        ke = np.zeros((8, 8))
        points = [(xi, eta, 1.0, True) for xi in (-g, g) for eta in (-g, g)] + [(0, 0, 4.0, False)]
        for xi, eta, w, normal in points:
            dN = np.array([0.25 * xi_n * (1 + eta * eta_n), 0.25 * eta_n * (1 + xi * xi_n)])
            J = dN @ X
            dNx = np.linalg.solve(J, dN)
            p = (0.25 * (1 + xi * xi_n) * (1 + eta * eta_n)) @ X
            phi = math.atan2(p[1], p[0])
            c, s = math.cos(phi), math.sin(phi)
            B = np.zeros((3, 8))
            B[0, 0::2], B[1, 1::2] = dNx[0], dNx[1]
            B[2, 0::2], B[2, 1::2] = dNx[1], dNx[0]
            T = np.array([[c * c, s * s, c * s], [s * s, c * c, -c * s],
                          [-2 * c * s, 2 * c * s, c * c - s * s]])
            D = (np.array([[C11[e], C12[e], 0], [C12[e], C22[e], 0], [0, 0, 0]]) if normal
                 else np.diag([0.0, 0.0, G[e]]))       # shear at the centre (reduced)
            Bl = T @ B @ R
            ke += w * np.linalg.det(J) * Bl.T @ D @ Bl
        dofs = np.ravel(np.stack([2 * nodes, 2 * nodes + 1], axis=1))
        for a in range(8):
            for b in range(8):
                K[dofs[a], dofs[b]] += ke[a, b]
    free = np.flatnonzero(roll.free)
    return K.tocsc()[free][:, free]


def main() -> None:
    print("woundroll contact benchmark (PET1 roll, head R = 10 mm, depth 1 mm)")
    t, res = best_of(lambda: indent(WEB, CORE, RADIUS, SIGMA_R, **HEAD))
    print(f"default mesh: {res.n_elements} elements, {res.n_dof} DOF, {len(res.delta) - 1} "
          f"increments: {t:.3f} s per solve (best of 3); F(1 mm) = {res.force[-1]:.1f} N, "
          f"a = {res.semi_contact_width * 1e3:.3f} mm")

    print("\nsolve time vs mesh size (sizes / factor, growth ** (1 / factor)):")
    rows = []
    for factor in (0.7, 1.0, 1.4, 2.0):
        t, res = best_of(lambda f=factor: indent(WEB, CORE, RADIUS, SIGMA_R, **HEAD,
                                                   options=refined_options(f)), repeat=2)
        rows.append((res.n_dof, t))
        print(f"  factor {factor:3.1f}: {res.n_elements:6d} elements {res.n_dof:6d} DOF "
              f"{t:7.3f} s  F = {res.force[-1]:8.1f} N")
    n, tt = np.array(rows).T
    p = np.polyfit(np.log(n), np.log(tt), 1)[0]
    print(f"  fitted scaling: time ~ n_dof^{p:.2f}")

    print("\nstiffness assembly, default mesh:")
    R_eff = 1 / (1 / HEAD["head_radius"] + 1 / R_OUT)
    mesh = build_mesh(R_CORE, R_OUT, surface_size=H, radial_growth=1.25,
                      tangential_size=max(H / 4, math.sqrt(2 * R_eff * 1e-3) / 40),
                      fine_halfwidth=math.sqrt(2 * R_eff * 1e-3), tangential_growth=1.1)
    t_setup, roll = best_of(lambda: _Roll(WEB, CORE, RADIUS, SIGMA_R, mesh, ContactOptions()))
    E_r = WEB.E_r(roll.sigma_pre)
    moduli = plane_strain_moduli(WEB, E_r)
    t_vec, K_vec = best_of(lambda: roll.assembler.csc(roll.assembler.values(*moduli)), 5)
    t_band, _ = best_of(lambda: roll.assembler.banded(roll.assembler.values_lower(*moduli),
                                                      lower_only=True), 5)
    t_loop, K_loop = best_of(lambda: loop_assembly(roll, E_r), 1)
    diff = abs(K_vec - K_loop).max() / abs(K_loop).max()
    print(f"  {mesh.n_elements} elements; one-off geometry (element matrices, scatter map): "
          f"{t_setup * 1e3:.1f} ms")
    print(f"  per increment, vectorised: {t_band * 1e3:.2f} ms (banded), "
          f"{t_vec * 1e3:.2f} ms (CSC)")
    print(f"  per increment, loop over elements: {t_loop * 1e3:.0f} ms "
          f"-> vectorised is {t_loop / t_band:.0f}x faster; max |K_loop - K_vec| / max |K| = "
          f"{diff:.1e}")


if __name__ == "__main__":
    main()
