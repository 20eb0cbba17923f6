"""Benchmark of the CMD hardness profile (Table 3 case); a script, not a test.

Prints
1. the axisymmetric winding model alone (61 sectors, 1,337 layers) against the number of
   layer groups, with the core pressure of the thickest and thinnest sectors (convergence),
2. the uniform-thickness check against the 1D Hakiel model (largest deviation of sigma_r,
   fraction of the core pressure),
3. the whole Rho profile (winding + 61 contact solutions + energy model) at 2.3 and 3.45 MPa
   with 1 and 2 workers, and the nip case (foundation from the contact model at every 4th
   sector),
4. the profile statistics of each case.

With ``--plots DIR`` the CMD figures (thickness and Rho on twin axes, sigma_r(r, z) map) are
written there. Run: ``.venv/bin/python benchmarks/bench_profile.py [--quick] [--plots out]``.
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np

from woundroll.materials import Core, Pfeiffer, Web
from woundroll.profile import bundled_profile
from woundroll.profile.hardness import NipSpec, predict_profile
from woundroll.profile.nip import NipRoller
from woundroll.winding.axisymmetric import wind_axisymmetric
from woundroll.winding.tension import TensionSchedule

# Table 3 of the reference paper
WEB = Web(
    thickness=76e-6,
    width=0.61,
    E_theta=4999e6,
    E_z=4999e6,
    radial_modulus=Pfeiffer(0.0, 246.5),
    nu_theta_r=0.01,
    nu_z_r=0.01,
    nu_theta_z=0.3,
)
CORE = Core.tube(0.1016, 0.095, 69e9, 0.33)
R_OUT = 0.2032


def timed(fn):
    t0 = time.perf_counter()
    out = fn()
    return time.perf_counter() - t0, out


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true", help="skip the 1-worker and nip runs")
    ap.add_argument("--plots", type=Path, default=None)
    ap.add_argument("--winding", action="store_true", help="sections 1-2 only (winding alone)")
    args = ap.parse_args()
    prof = bundled_profile()

    print("1. axisymmetric winding alone, Table 3, 61 sectors, bundled synthetic profile")
    print(
        f"{'groups':>7} {'time [s]':>9} {'P_core thickest [kPa]':>22} {'P_core thinnest':>16}"
        f" {'sigma_r outer 1 mm, sector 20 [kPa]':>36} {'slack':>6}"
    )
    runs = {}
    for G in (100, 200, 400):
        t, w = timed(
            lambda G=G: wind_axisymmetric(
                WEB, CORE, R_OUT, TensionSchedule(web_stress=2.3e6), prof, n_groups=G
            )
        )
        runs[G] = w
        jt, jn = int(np.argmax(w.thickness)), int(np.argmin(w.thickness))
        r = w.radius[:, 20]
        near = np.interp(R_OUT - 1e-3, r, w.sigma_r[:, 20])
        print(
            f"{G:7d} {t:9.2f} {-w.sigma_r_core[jt] / 1e3:22.1f} {-w.sigma_r_core[jn] / 1e3:16.1f}"
            f" {-near / 1e3:36.2f} {int(w.slack.sum()):6d}"
        )
    for G in (100, 200):
        a, b = runs[G], runs[2 * G]
        d = 0.0
        for j in range(a.z.size):
            sel = a.radius[:, j] >= a.build_radius[j] - 5e-3
            sb = np.interp(a.radius[sel, j], b.radius[:, j], b.sigma_r[:, j])
            d = max(d, float(np.max(np.abs(a.sigma_r[sel, j] - sb))))
        ref = max(
            float(np.max(np.abs(b.sigma_r[b.radius[:, j] >= b.build_radius[j] - 5e-3, j])))
            for j in range(b.z.size)
        )
        print(
            f"   {G} -> {2 * G} groups: outer 5 mm sigma_r changes by"
            f" {100 * d / ref:.2f} % of its peak"
        )
    if not args.quick:
        t, w = timed(
            lambda: wind_axisymmetric(
                WEB, CORE, R_OUT, TensionSchedule(web_stress=2.3e6), prof, window=None
            )
        )
        b = runs[200]
        diff = np.max(np.abs(b.sigma_r - w.sigma_r)) / np.max(np.abs(w.sigma_r))
        print(
            f"   200 groups, whole stack solved every increment (window=None): {t:.2f} s;"
            f" lazy deep part differs by {100 * diff:.2f} % of max |sigma_r|"
        )
        t, w = timed(
            lambda: wind_axisymmetric(
                WEB, CORE, R_OUT, TensionSchedule(web_stress=2.3e6), prof, shear_coupling=False
            )
        )
        print(f"   independent plane-stress sectors (shear_coupling=False), 200 groups: {t:.2f} s")

    print("\n2. uniform thickness vs the 1D Hakiel model (layer by layer)")
    try:
        from woundroll.winding.hakiel import wind
    except ImportError:
        print("   woundroll.winding.hakiel not available")
    else:
        from dataclasses import replace

        plane = replace(WEB, nu_z_r=0.0, nu_theta_z=0.0)
        for label, web in (("Table 3", WEB), ("nu_z_r = nu_theta_z = 0", plane)):
            for T in (2.3e6, 3.45e6):
                ten = TensionSchedule(web_stress=T)
                t1, ref = timed(lambda ten=ten, web=web: wind(web, CORE, R_OUT, ten))
                for ns in (1, 5, 15):
                    t2, a = timed(
                        lambda ten=ten, ns=ns, web=web: wind_axisymmetric(
                            web, CORE, R_OUT, ten, n_sectors=ns
                        )
                    )
                    j = ns // 2
                    r = a.radius[:, j]
                    s1 = np.interp(r, ref.radius, ref.sigma_r)
                    dev = np.abs(a.sigma_r[:, j] - s1)
                    o = r > R_OUT - 0.005
                    print(
                        f"   {label:24s} T_w {T / 1e6:4.2f} MPa, {ns:2d} sectors (mid):"
                        " max |d sigma_r|"
                        f" = {100 * dev.max() / ref.core_pressure:5.2f} % of P_core"
                        f" ({ref.core_pressure / 1e3:.1f} kPa), outer 5 mm pointwise"
                        f" {100 * np.max(dev[o] / np.abs(s1[o])):5.2f} %, sigma_z core"
                        f" {a.sigma_z[0, j] / 1e3:7.1f} kPa; 1D {t1:.2f} s, axisym {t2:.2f} s"
                    )
    if args.winding:
        return

    print("\n3. whole Rho profile (winding + 61 contact solutions + energy model)")
    cases = [("2.3 MPa", 2.3e6, 2, None), ("3.45 MPa", 3.45e6, 2, None)]
    if not args.quick:
        cases.insert(1, ("2.3 MPa, 1 worker", 2.3e6, 1, None))
        # nip: Table 3's "P_nip 2.3 MPa" read as the nip-induced tension mu N / h
        # (docs/profile.md): mu N = 2.3 MPa x 76 um = 174.8 N/m; mu = 0.3 assumed
        roller = NipRoller.tube(200e9, 0.05, 0.04, line_load=2.3e6 * 76e-6 / 0.3, friction=0.3)
        cases.append(("2.3 MPa + nip", 2.3e6, 2, NipSpec(roller)))
    for name, T, workers, nip in cases:
        t, res = timed(
            lambda T=T, workers=workers, nip=nip: predict_profile(
                WEB,
                CORE,
                TensionSchedule(web_stress=T),
                prof,
                outer_radius=R_OUT,
                workers=workers,
                nip=nip,
            )
        )
        st = res.rho_stats
        parts = ", ".join(f"{k} {v:.1f}" for k, v in res.timings.items())
        print(f"   {name:20s} total {t:6.1f} s ({parts})")
        print(
            f"   {'':20s} Rho mean {st.mean:6.1f}, SD {st.sd:6.1f}, CoV {100 * st.cov:5.1f} %"
            f" ({st.band}), min {st.min:6.1f}, max {st.max:6.1f}; corr(Rho, h) "
            f"{np.corrcoef(res.rho, res.thickness)[0, 1]:.2f}"
        )
        if args.plots is not None:
            args.plots.mkdir(parents=True, exist_ok=True)
            tag = name.replace(" ", "_").replace(",", "").replace("+", "nip")
            res.plot(args.plots / f"profile_{tag}")


if __name__ == "__main__":
    main()
