"""Benchmark of the 2D contact model (woundroll.contact.indent); not a test.

BLAS threads are pinned to one (``OPENBLAS_NUM_THREADS=OMP_NUM_THREADS=1``, set below before
numpy is imported) because the banded Cholesky at the default bandwidth (~55) gains nothing
from threads and threaded OpenBLAS slows down badly on a loaded 2-core machine;
``--blas-threads N`` sets another count (to compare).

Prints
1. the time of one contact solve at the default mesh: PET1 roll with a synthetic profile and
   a 10 mm head, and the case the pipeline runs, PET1 wound at 26.7 N by the Hakiel model
   (``load_case("pet1-26.7N")``) with the Rho-meter head (6.565 mm, 2.54 cm), 1 mm deep;
2. solve time against mesh size on the Rho-meter case (all element sizes divided by a
   factor, growth ratios raised to 1/factor) with the fitted scaling exponent t ~ n_dof^p;
2b. the step control: the default predicted mid-step modulus (about one factorisation per
   load step) against the explicit midpoint scheme (two per step) at 24 and 48 steps;
3. the stiffness assembly: the vectorised assembler (geometric element matrices once, one
   fused multiply-add and a bincount per increment) against a straightforward
   loop-over-elements assembly of the same matrix, for the default curved element (assumed
   hoop strain) and the flat one, with their agreement.

Run: ``.venv/bin/python benchmarks/bench_contact.py [--blas-threads N] [--quick]``.
"""

from __future__ import annotations

import os
import sys


def _blas_threads() -> str:
    if "--blas-threads" in sys.argv:
        return sys.argv[sys.argv.index("--blas-threads") + 1]
    return "1"


# before numpy / scipy are imported: OpenBLAS reads these once, at load
os.environ["OPENBLAS_NUM_THREADS"] = os.environ["OMP_NUM_THREADS"] = _blas_threads()

import math  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402
import scipy.sparse as sp  # noqa: E402

from woundroll.contact import ContactOptions, indent  # noqa: E402
from woundroll.contact.plane_strain.fem import plane_strain_moduli  # noqa: E402
from woundroll.contact.plane_strain.mesh import build_mesh  # noqa: E402
from woundroll.contact.plane_strain.solver import _Roll  # noqa: E402
from woundroll.materials import Core, Pfeiffer, Web  # noqa: E402

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


def rho_meter_case() -> tuple:
    """PET1 wound at 26.7 N (Hakiel), steel core, and the Rho-meter head, 1 mm deep."""
    from woundroll.case import load_case
    from woundroll.instruments import get_instrument
    from woundroll.winding.hakiel import wind

    case = load_case("pet1-26.7N")
    web, core = case.web.build(), case.core.build()
    w = wind(web, core, case.winding.final_radius(web, core), case.winding.schedule(web))
    ins = get_instrument("rho-meter")
    head = {"head_radius": ins.head_radius, "head_length": ins.head_length, "depth_max": 1e-3}
    return web, core, np.asarray(w.radius), np.asarray(w.sigma_r), head


def refined_options(factor: float, head: dict, r_out: float, h: float) -> ContactOptions:
    d = ContactOptions()
    r_eff = 1 / (1 / head["head_radius"] + 1 / r_out)
    t_size = max(h / 4, math.sqrt(2 * r_eff * head["depth_max"]) / 40)
    return ContactOptions(
        surface_size=h / factor,
        tangential_size=t_size / factor,
        radial_growth=d.radial_growth ** (1 / factor),
        tangential_growth=d.tangential_growth ** (1 / factor),
    )


def _scatter(K: sp.dok_matrix, nodes: np.ndarray, ke: np.ndarray) -> None:
    dofs = np.ravel(np.stack([2 * nodes, 2 * nodes + 1], axis=1))
    for a in range(8):
        for b in range(8):
            K[dofs[a], dofs[b]] += ke[a, b]


def loop_assembly_flat(roll: _Roll, E_r: np.ndarray) -> sp.csc_matrix:
    """The textbook assembly of the flat element (full hoop integration), one element at a
    time: 2x2 Gauss points, rotated orthotropic D, B^T D B, scatter into a dict-of-keys."""
    mesh = roll.mesh
    xy, conn, ang = mesh.node_xy(), mesh.connectivity(), mesh.node_angle()
    C11, C12, C22, G = plane_strain_moduli(WEB, E_r)
    g = 1 / math.sqrt(3)
    xi_n, eta_n = np.array([-1.0, 1, 1, -1]), np.array([-1.0, -1, 1, 1])
    K = sp.dok_matrix((2 * mesh.n_nodes, 2 * mesh.n_nodes))
    for e, nodes in enumerate(conn):
        X = xy[nodes]
        R = np.zeros((8, 8))  # nodal polar -> Cartesian
        for a in range(4):
            c, s = math.cos(ang[nodes[a]]), math.sin(ang[nodes[a]])
            R[2 * a : 2 * a + 2, 2 * a : 2 * a + 2] = [[c, -s], [s, c]]
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
            T = np.array(
                [
                    [c * c, s * s, c * s],
                    [s * s, c * c, -c * s],
                    [-2 * c * s, 2 * c * s, c * c - s * s],
                ]
            )
            D = (
                np.array([[C11[e], C12[e], 0], [C12[e], C22[e], 0], [0, 0, 0]])
                if normal
                else np.diag([0.0, 0.0, G[e]])
            )  # shear at the centre (reduced)
            Bl = T @ B @ R
            ke += w * np.linalg.det(J) * Bl.T @ D @ Bl
        _scatter(K, nodes, ke)
    free = np.flatnonzero(roll.free)
    return K.tocsc()[free][:, free]


def loop_assembly_curved(roll: _Roll, E_r: np.ndarray) -> sp.csc_matrix:
    """The same for the default curved element: the exact sector, polar strains
    eps_r = du_r/dr, eps_t = (du_t/dtheta + u_r)/r, gamma = du_r/(r dtheta) + du_t/dr - u_t/r
    at 2x2 Gauss points of (r, theta), hoop strain taken at the element's mid-angle (assumed
    hoop strain), shear at the centre."""
    mesh = roll.mesh
    conn = mesh.connectivity()
    C11, C12, C22, G = plane_strain_moduli(WEB, E_r)
    g = 0.5 / math.sqrt(3)
    K = sp.dok_matrix((2 * mesh.n_nodes, 2 * mesh.n_nodes))
    for e, nodes in enumerate(conn):
        i, j = nodes[0] % mesh.n_r, nodes[0] // mesh.n_r
        r0, r1, t0, t1 = mesh.r[i], mesh.r[i + 1], mesh.theta[j], mesh.theta[j + 1]

        def b_row(a: float, b: float, r0=r0, r1=r1, t0=t0, t1=t1) -> tuple[np.ndarray, float]:
            r = r0 + a * (r1 - r0)
            N = np.array([(1 - a) * (1 - b), a * (1 - b), a * b, (1 - a) * b])
            dNa = np.array([-(1 - b), 1 - b, b, -b]) / (r1 - r0)
            dNb = np.array([-(1 - a), -a, a, 1 - a]) / (t1 - t0)
            B = np.zeros((3, 8))
            B[0, 0::2] = dNa
            B[1, 0::2], B[1, 1::2] = N / r, dNb / r
            B[2, 0::2], B[2, 1::2] = dNb / r, dNa - N / r
            return B, r

        ke = np.zeros((8, 8))
        D = np.array([[C11[e], C12[e]], [C12[e], C22[e]]])
        for a in (0.5 - g, 0.5 + g):
            for b in (0.5 - g, 0.5 + g):
                B, r = b_row(a, b)
                Bn = np.stack([B[0], b_row(a, 0.5)[0][1]])  # hoop at the mid-angle
                ke += 0.25 * r * (r1 - r0) * (t1 - t0) * Bn.T @ D @ Bn
        Bc, rc = b_row(0.5, 0.5)
        ke += rc * (r1 - r0) * (t1 - t0) * G[e] * np.outer(Bc[2], Bc[2])
        _scatter(K, nodes, ke)
    free = np.flatnonzero(roll.free)
    return K.tocsc()[free][:, free]


def main() -> None:
    quick = "--quick" in sys.argv
    print(f"woundroll contact benchmark (BLAS threads: {os.environ['OPENBLAS_NUM_THREADS']})")
    t, res = best_of(lambda: indent(WEB, CORE, RADIUS, SIGMA_R, **HEAD))
    print(
        f"synthetic PET1 profile, head R = 10 mm, 1 mm: {res.n_elements} elements, "
        f"{res.n_dof} DOF, {len(res.delta) - 1} increments: {t:.3f} s per solve (best of 3); "
        f"F = {res.force[-1]:.1f} N, a = {res.semi_contact_width * 1e3:.3f} mm"
    )
    web, core, radius, sigma_r, head = rho_meter_case()
    t, res = best_of(lambda: indent(web, core, radius, sigma_r, **head))
    print(
        f"PET1 26.7 N (Hakiel), Rho-meter head, 1 mm: {res.n_elements} elements, "
        f"{res.n_dof} DOF: {t:.3f} s per solve (best of 3); F = {res.force[-1]:.2f} N, "
        f"a = {res.semi_contact_width * 1e3:.3f} mm"
    )
    t, res = best_of(lambda: indent(web, core, radius, sigma_r, **head, update_modulus=False))
    print(f"  the same without the modulus update (one factorisation): {t:.3f} s")

    print("\nstep control, Rho-meter case, 1 mm (issue 14: one factorisation per load step):")
    ref = None
    for label, kw in (
        ("explicit midpoint, 48 steps (reference)", {"n_steps": 48, "predictor": False}),
        ("explicit midpoint, 24 steps", {"predictor": False}),
        ("predicted mid-step, 24 steps (default)", {}),
    ):
        o = ContactOptions(**kw)
        t, res = best_of(lambda o=o: indent(web, core, radius, sigma_r, **head, options=o))
        ref = res.force[-1] if ref is None else ref
        print(
            f"  {label:42s} {t:6.3f} s  {res.factorisations:3d} factorisations  "
            f"F = {res.force[-1]:.2f} N ({100 * (res.force[-1] / ref - 1):+.2f} %)"
        )

    print("\nsolve time vs mesh size, Rho-meter case (sizes / factor, growth ** (1 / factor)):")
    rows = []
    for factor in (0.7, 1.0, 1.4) if quick else (0.7, 1.0, 1.4, 2.0):
        opts = refined_options(factor, head, radius[-1], web.thickness)
        t, res = best_of(
            lambda o=opts: indent(web, core, radius, sigma_r, **head, options=o), repeat=2
        )
        rows.append((res.n_dof, t))
        print(
            f"  factor {factor:3.1f}: {res.n_elements:6d} elements {res.n_dof:6d} DOF "
            f"(mesh {res.mesh_shape[0]} x {res.mesh_shape[1]}) {t:7.3f} s  "
            f"F = {res.force[-1]:8.2f} N"
        )
    n, tt = np.array(rows).T
    p = np.polyfit(np.log(n), np.log(tt), 1)[0]
    print(f"  fitted scaling: time ~ n_dof^{p:.2f}")

    print("\nstiffness assembly, synthetic PET1 profile, default mesh:")
    R_eff = 1 / (1 / HEAD["head_radius"] + 1 / R_OUT)
    mesh = build_mesh(
        R_CORE,
        R_OUT,
        surface_size=H,
        radial_growth=1.25,
        tangential_size=max(H / 4, math.sqrt(2 * R_eff * 1e-3) / 40),
        fine_halfwidth=math.sqrt(2 * R_eff * 1e-3),
        tangential_growth=1.1,
    )
    for label, opts, loop in (
        ("curved element, assumed hoop (default)", ContactOptions(), loop_assembly_curved),
        (
            "flat element, full hoop",
            ContactOptions(element="flat", assumed_hoop=False),
            loop_assembly_flat,
        ),
    ):
        t_setup, roll = best_of(lambda o=opts: _Roll(WEB, CORE, RADIUS, SIGMA_R, mesh, o))
        E_r = WEB.E_r(roll.sigma_pre)
        moduli = plane_strain_moduli(WEB, E_r)
        asm = roll.assembler
        t_vec, K_vec = best_of(lambda a=asm, m=moduli: a.csc(a.values(*m)), 5)
        t_band, _ = best_of(
            lambda a=asm, m=moduli: a.banded(a.values_lower(*m), lower_only=True), 5
        )
        t_loop, K_loop = best_of(lambda r=roll, f=loop, e=E_r: f(r, e), 1)
        diff = abs(K_vec - K_loop).max() / abs(K_loop).max()
        print(
            f"  {label}: {mesh.n_elements} elements; one-off geometry (element matrices, "
            f"scatter map): {t_setup * 1e3:.1f} ms"
        )
        print(
            f"    per increment, vectorised: {t_band * 1e3:.2f} ms (banded), "
            f"{t_vec * 1e3:.2f} ms (CSC)"
        )
        print(
            f"    per increment, loop over elements: {t_loop * 1e3:.0f} ms "
            f"-> vectorised is {t_loop / t_band:.0f}x faster; max |K_loop - K_vec| / max |K| "
            f"= {diff:.1e}"
        )


if __name__ == "__main__":
    main()
