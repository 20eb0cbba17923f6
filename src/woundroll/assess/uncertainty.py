"""Uncertainty on a prediction: bands on the stresses and the reading from the case's tolerances.

The case's ``[uncertainty]`` gives one SD of the Pfeiffer K1, K2 {2} (and their correlation,
as ``woundroll fit-stack`` reports it), of the web thickness and of the tension setting.
:func:`propagate` (``woundroll run CASE --uncertainty N``) draws N samples of them and

* **stresses**: winds every sample with the full 1D model (Hakiel, about 10 ms a roll) and
  reports percentile bands of sigma_r and sigma_theta on the nominal radius grid, of the core
  pressure, of the near-surface pressure, and the share of samples with negative hoop stress;
* **reading**: the contact solve is 0.3-1 s, too slow for every sample. A surrogate instead:
  a quadratic in each standardised parameter ``u_i = (p_i - p_i0) / SD_i`` without cross
  terms, ``R = R0 + sum a_i u_i + b_i u_i^2 / 2``, from 2 p + 1 full forward runs at
  ``u_i = 0, +-2`` (steps of 2 SD keep the forward chain's own 0.1-0.3 Rho steps small against
  the differences, docs/diagnosis.md). It is checked at run time against full forward runs at
  the first ``verify`` samples (``surrogate.max_abs_error`` in the JSON), and in the tests
  against a full Monte Carlo.

* **CMD profile** (cases with ``winding.thickness_profile``): the full profile run (about
  20 s) is too slow per sample. Per sector, the reading is propagated through the reduced
  profile model of :mod:`woundroll.inverse.causes` (axisymmetric winding with uncoupled sectors,
  about 1 s for 61 sectors, then the near-surface pressure ``P_s`` of each sector mapped to
  the reading along the case's forward curve, :mod:`woundroll.inverse.diagnosis`), with the same
  quadratic-per-parameter surrogate (steps of 2 SD): ``2 p + 1`` reduced runs. K1 and K2
  change the contact too: their steps use a forward curve of the perturbed web (one curve,
  about 5-10 s, per step); thickness (a uniform relative change of the whole CMD profile)
  and tension keep the nominal curve. The band is the surrogate's change from its nominal,
  added to the full run's profile when it is given (``propagate(..., profile=...)``).
  Checked against a brute-force Monte Carlo of the reduced model in the tests. With the full
  run given, the tension term is calibrated per sector by one more full profile run at
  +2 SD (``calibrate=1``; two runs at +-2 SD with ``calibrate=2``): the reduced model's
  tension sensitivity was up to 2.5x off per sector, the calibrated one within 20 % of the
  full model's at +-10 % (docs/diagnosis.md).

Sampling: K1, K2 bivariate normal with the given correlation; thickness and tension normal;
samples are clipped to K1 >= 0, K2 > 0, thickness > 0, tension >= 0 (a truncation that
matters only for SDs comparable to the value; stated in docs/diagnosis.md).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from woundroll.errors import InputError
from woundroll.pipeline.vocabulary import versioned
from woundroll.util.output import strict_json

if TYPE_CHECKING:
    from woundroll.case import Case
    from woundroll.materials.web import Web

FloatArray = NDArray[np.float64]
PERCENTILES = (2.5, 50.0, 97.5)
#: Step of the surrogate's central differences, in SDs.
SURROGATE_STEP = 2.0
#: Tension factors of the profile band's forward curve (down to 1/16: light lanes too).
PROFILE_CURVE_FACTORS = (0.0625, 0.25, 0.5, 1.0, 2.0, 4.0)

__all__ = [
    "UncertaintyResult",
    "draw_samples",
    "profile_bands",
    "reduced_profile",
    "propagate",
    "uncertain_parameters",
]


def uncertain_parameters(case: Case) -> dict[str, float]:
    """Name -> SD (SI) of every parameter the case's ``[uncertainty]`` makes uncertain.

    Raises
    ------
    InputError
        No ``[uncertainty]`` table, or K1/K2 SDs for a law that is not Pfeiffer's.
    """
    from woundroll.materials.radial_modulus import Pfeiffer

    u = case.uncertainty
    if u is None:
        raise InputError(
            "give the tolerances in [uncertainty] (K1, K2, K1_K2_correlation, thickness, "
            "tension; docs/case-files.md)",
            "uncertainty",
        )
    web = case.web.build()
    out: dict[str, float] = {}
    for name in ("K1", "K2"):
        sd = getattr(u, name)
        if sd:
            if not isinstance(web.radial_modulus, Pfeiffer):
                raise InputError(
                    f"{name} is a parameter of the Pfeiffer law; web.radial_modulus is "
                    f"{web.radial_modulus.to_dict()['law']}",
                    f"uncertainty.{name}",
                )
            out[name] = float(sd)
    if u.thickness_sd(web.thickness):
        out["thickness"] = u.thickness_sd(web.thickness)
    if u.tension:
        out["tension"] = float(u.tension) * case.winding.schedule(web).web_stress
    if not out:
        raise InputError("every tolerance is zero: nothing to propagate", "uncertainty")
    return out


def draw_samples(case: Case, n: int, seed: int = 0) -> dict[str, FloatArray]:
    """``n`` standardised samples ``u`` (mean 0, SD 1) per uncertain parameter; K1 and K2
    correlated as the case says."""
    params = uncertain_parameters(case)
    rng = np.random.default_rng(seed)
    z = {k: rng.standard_normal(n) for k in params}
    rho = case.uncertainty.K1_K2_correlation if case.uncertainty else 0.0
    if "K1" in z and "K2" in z and rho:
        z["K2"] = rho * z["K1"] + math.sqrt(max(1.0 - rho * rho, 0.0)) * z["K2"]
    return z


def _perturb(
    web: Web, web_stress: float, params: dict[str, float], u: dict[str, float]
) -> tuple[Web, float]:
    """The web and tension at standardised offsets ``u`` (clipped to physical values)."""
    law = web.radial_modulus
    changes: dict[str, float] = {}
    for name in ("K1", "K2"):
        if name in u and name in params:
            v = getattr(law, name) + u[name] * params[name]
            changes[name] = max(v, 0.0) if name == "K1" else max(v, 1e-3 * getattr(law, name))
    if changes:
        web = replace(web, radial_modulus=replace(law, **changes))
    if "thickness" in u and "thickness" in params:
        h = web.thickness + u["thickness"] * params["thickness"]
        web = replace(web, thickness=max(h, 0.05 * web.thickness))
    if "tension" in u and "tension" in params:
        web_stress = max(web_stress + u["tension"] * params["tension"], 0.0)
    return web, web_stress


def _band(samples: FloatArray) -> dict[str, Any]:
    s = np.asarray(samples, dtype=float)
    p = np.percentile(s, PERCENTILES, axis=0)
    return {
        "mean": s.mean(axis=0).tolist(),
        "sd": s.std(axis=0, ddof=1).tolist() if s.shape[0] > 1 else 0.0,
        "p2_5": p[0].tolist(),
        "p50": p[1].tolist(),
        "p97_5": p[2].tolist(),
    }


@dataclass(frozen=True)
class UncertaintyResult:
    """Monte Carlo bands of one case (module docstring).

    Attributes
    ----------
    n : int
    parameters : dict
        Name -> SD (SI).
    samples : dict
        Name -> standardised samples u (n,).
    radius : (m,) array [m]
        The nominal run's radii (bands are interpolated onto them).
    sigma_r, sigma_theta : (n, m) arrays [Pa]
    core_pressure, surface_pressure, min_hoop : (n,) arrays [Pa]
    nominal_sigma_r, nominal_sigma_theta : (m,) arrays [Pa]
    reading : (n,) array or None
        Surrogate readings (scale ``scale``).
    reading_nominal : float or None
    surrogate : dict
        Coefficients, full-run verification.
    """

    n: int
    parameters: dict[str, float]
    samples: dict[str, FloatArray]
    radius: FloatArray
    sigma_r: FloatArray
    sigma_theta: FloatArray
    core_pressure: FloatArray
    surface_pressure: FloatArray
    min_hoop: FloatArray
    nominal_sigma_r: FloatArray
    nominal_sigma_theta: FloatArray
    reading: FloatArray | None = None
    reading_nominal: float | None = None
    scale: str = "Rho"
    surrogate: dict[str, Any] = field(default_factory=dict)
    pressure_depth: float = 0.0
    notes: tuple[str, ...] = ()
    profile: dict[str, Any] | None = None

    @property
    def negative_hoop_share(self) -> float:
        """Share of samples with a negative (compressive) hoop stress somewhere."""
        return float(np.mean(self.min_hoop < 0.0))

    def to_dict(self) -> dict[str, Any]:
        out: dict[str, Any] = {
            "n": self.n,
            "parameters_sd": dict(self.parameters),
            "percentiles": list(PERCENTILES),
            "radius_m": self.radius.tolist(),
            "sigma_r_Pa": _band(self.sigma_r),
            "sigma_theta_Pa": _band(self.sigma_theta),
            "core_pressure_Pa": _band(self.core_pressure),
            "surface_pressure_Pa": _band(self.surface_pressure),
            "surface_pressure_depth_m": self.pressure_depth,
            "min_hoop_stress_Pa": _band(self.min_hoop),
            "negative_hoop_share": self.negative_hoop_share,
            "notes": list(self.notes),
        }
        if self.reading is not None:
            out["reading"] = {
                "scale": self.scale,
                "nominal": self.reading_nominal,
                **_band(self.reading),
            }
            out["surrogate"] = self.surrogate
        if self.profile is not None:
            out["profile"] = {k: v for k, v in self.profile.items() if not k.startswith("_")}
        return out

    def summary(self) -> list[tuple[str, str]]:
        """(label, value) rows: 95 % bands of the headline numbers."""

        def b(a: FloatArray, scale: float, unit: str) -> str:
            lo, mid, hi = np.percentile(a, PERCENTILES)
            return f"{mid * scale:.3g} ({lo * scale:.3g}-{hi * scale:.3g}) {unit}"

        rows = [
            ("samples", f"{self.n}"),
            ("core pressure (95 % band)", b(self.core_pressure, 1e-3, "kPa")),
            ("near-surface pressure (95 % band)", b(self.surface_pressure, 1e-3, "kPa")),
            ("negative hoop stress in", f"{100 * self.negative_hoop_share:.1f} % of samples"),
        ]
        if self.reading is not None:
            rows.append((f"reading [{self.scale}] (95 % band)", b(self.reading, 1.0, "")))
            err = self.surrogate.get("max_abs_error")
            if err is not None:
                rows.append(("surrogate vs full runs, max error", f"{err:.2g} {self.scale}"))
        if self.profile is not None:
            half = 0.5 * (
                np.array(self.profile["reading_high"]) - np.array(self.profile["reading_low"])
            )
            rows.append(
                (
                    f"CMD profile [{self.scale}], 95 % half-band",
                    f"{half.min():.2g}-{half.max():.2g} over {half.size} sectors",
                )
            )
        return rows

    def plot(self, path_prefix: str | Path | None = None) -> list[Any]:
        """Stresses with their 95 % bands against radius; the reading's histogram.
        Saved as ``<prefix>_stresses.png`` / ``<prefix>_reading.png``."""
        import matplotlib.pyplot as plt

        figs = []
        fig, (a1, a2) = plt.subplots(2, 1, sharex=True, figsize=(6.4, 6.0))
        r_cm = self.radius * 100
        for a, s, nom, label in (
            (a1, -self.sigma_r, -self.nominal_sigma_r, "interlayer pressure -sigma_r [kPa]"),
            (a2, self.sigma_theta, self.nominal_sigma_theta, "hoop stress sigma_theta [kPa]"),
        ):
            lo, hi = np.percentile(s, [2.5, 97.5], axis=0)
            a.fill_between(r_cm, lo / 1e3, hi / 1e3, color="C0", alpha=0.3, lw=0, label="95 %")
            a.plot(r_cm, nom / 1e3, color="C0", lw=1.5, label="nominal")
            a.set_ylabel(label, fontsize=9)
            a.grid(alpha=0.3)
        a2.axhline(0.0, color="k", lw=0.8)
        a1.legend(fontsize=8)
        a1.set_title(
            f"{self.n} samples: "
            + ", ".join(f"{k} SD {v:.3g}" for k, v in self.parameters.items()),
            fontsize=8,
        )
        a2.set_xlabel("radius [cm]")
        fig.tight_layout()
        figs.append(fig)
        if self.reading is not None:
            fig2, ax = plt.subplots(figsize=(5.6, 3.6))
            ax.hist(self.reading, bins=max(10, min(40, self.n // 5)), color="C1", alpha=0.8)
            ax.axvline(self.reading_nominal, color="k", lw=1.2, label="nominal")
            for q in np.percentile(self.reading, [2.5, 97.5]):
                ax.axvline(q, color="k", ls="--", lw=0.8)
            ax.set_xlabel(f"reading [{self.scale}] (surrogate)")
            ax.set_ylabel("samples")
            ax.legend(fontsize=8)
            fig2.tight_layout()
            figs.append(fig2)
        if self.profile is not None:
            p = self.profile
            fig3, ax = plt.subplots(figsize=(7.2, 3.8))
            zc = np.array(p["z_m"]) * 100
            ax.fill_between(zc, p["reading_low"], p["reading_high"], color="C3", alpha=0.3, lw=0)
            ax.plot(zc, p["reading_nominal"], color="C3", marker="o", ms=3, label=p["centre"])
            ax.plot([], [], color="C3", alpha=0.3, lw=6, label="95 % band")
            off = np.array(p["outside_curve"], dtype=bool)
            if off.any():
                ax.plot(
                    zc[off],
                    np.array(p["reading_nominal"])[off],
                    "x",
                    color="k",
                    ms=7,
                    label="no band (pressure outside the forward curve: slack lane)",
                )
            ax.set_xlabel("CMD position [cm]")
            ax.set_ylabel(f"reading [{self.scale}]")
            ax.set_title(f"CMD profile, {self.n} samples (reduced-model surrogate)", fontsize=9)
            ax.grid(alpha=0.3)
            ax.legend(fontsize=8)
            fig3.tight_layout()
            figs.append(fig3)
        if path_prefix is not None:
            figs[0].savefig(f"{path_prefix}_stresses.png", dpi=120)
            if self.reading is not None:
                figs[1].savefig(f"{path_prefix}_reading.png", dpi=120)
            if self.profile is not None:
                figs[-1].savefig(f"{path_prefix}_profile.png", dpi=120)
        return figs

    def write(self, out_dir: str | Path) -> list[Path]:
        """``uncertainty.json`` and the plots into ``out_dir``."""

        import matplotlib

        matplotlib.use("Agg", force=False)
        import matplotlib.pyplot as plt

        out = Path(out_dir)
        try:
            out.mkdir(parents=True, exist_ok=True)
            (out / "uncertainty.json").write_text(
                strict_json(versioned(self.to_dict())), encoding="utf-8"
            )
            for fig in self.plot(out / "uncertainty"):
                plt.close(fig)
        except OSError as exc:
            raise InputError(f"cannot write to {out}: {exc.strerror or exc}", "--out") from None
        return sorted([out / "uncertainty.json", *out.glob("uncertainty_*.png")])


def propagate(
    case: Case | str | Path,
    n: int = 200,
    *,
    seed: int = 0,
    verify: int = 2,
    progress: Callable[[str, float], None] | None = None,
    profile: Any = None,
    calibrate: int = 1,
) -> UncertaintyResult:
    """Monte Carlo of the case's tolerances through the winding model, and through a verified
    surrogate of the contact and impact steps for the reading (module docstring).

    Parameters
    ----------
    case : Case or path / bundled name
    n : int
        Samples (>= 10).
    seed : int
    verify : int
        Full forward runs at the first ``verify`` samples to check the surrogate.
    progress : callable, optional
        ``progress(stage, fraction)``; stages "winding samples", "reading surrogate",
        "profile surrogate".
    profile : ProfileResult, optional
        The case's full CMD profile run: the profile band is centred on its readings
        (otherwise on the reduced model's).
    calibrate : int
        Full profile runs that correct the band's tension term per sector (with
        ``profile``; :func:`profile_bands`): 1 (default), 2 or 0.
    """
    from woundroll.case import Case, load_case
    from woundroll.inverse.diagnosis import RollModel

    if not isinstance(case, Case):
        case = load_case(case)
    if isinstance(n, bool) or not isinstance(n, int) or n < 10:
        raise InputError(f"needs at least 10 samples, got {n!r}", "--uncertainty")
    params = uncertain_parameters(case)
    u = draw_samples(case, n, seed)
    web0 = case.web.build()
    sched0 = case.winding.schedule(web0)
    # the stresses: every sample wound
    result = _winding_samples(case, web0, sched0, params, u, n, progress)
    setup = case.tester_setup
    if setup is None or setup.roll_spring is not None:
        note = "no [tester]" if setup is None else "explicit [tester.roll_spring]"
        return replace(result, notes=(*result.notes, f"{note}: no reading band"))
    # the reading: a surrogate of the contact and impact steps, checked by full runs
    model = RollModel.from_case(case)
    reading, sur = _reading_surrogate(model, web0, sched0, params, u, n, verify, progress)
    result = replace(
        result, reading=reading, reading_nominal=sur["nominal"], scale=model.scale, surrogate=sur
    )
    if case.winding.thickness_profile is None:
        return result
    # across the roll: the profile band
    bands = profile_bands(
        case, model, u, params, full=profile, progress=progress, calibrate=calibrate
    )
    return replace(result, profile=bands)


def _winding_samples(
    case: Case,
    web0: Any,
    sched0: Any,
    params: dict[str, float],
    u: dict[str, FloatArray],
    n: int,
    progress: Callable[[str, float], None] | None,
) -> UncertaintyResult:
    """The nominal roll and every sample wound by the 1D model, on the nominal radii."""
    from woundroll.inverse.diagnosis import near_surface_pressure
    from woundroll.winding.hakiel import WindingOptions, wind

    core = case.core.build()
    r_out = case.winding.final_radius(web0, core)
    options = WindingOptions.from_dict(case.winding.options, "winding.options")
    setup = case.tester_setup
    depth = setup.instrument.head_radius if setup is not None else 0.0065
    notes = []
    if case.winding.thickness_profile is not None:
        notes.append(
            "stresses: 1D model at the nominal thickness; CMD profile: reduced model "
            "(uncoupled sectors, P_s -> reading along the forward curve)"
        )
    from woundroll.pipeline.runner import after_winding

    def wound(web: Any, sched: Any) -> Any:
        # as the reading sees the roll: after the case's entrained air and storage
        w = wind(web, core, r_out, sched, options=options)
        return after_winding(case, w, web, core, r_out, sched, options).winding

    nominal = wound(web0, sched0)
    radius = nominal.radius
    sr = np.empty((n, radius.size))
    st = np.empty((n, radius.size))
    core_p = np.empty(n)
    surf_p = np.empty(n)
    min_hoop = np.empty(n)
    for i in range(n):
        web, t = _perturb(web0, sched0.web_stress, params, {k: v[i] for k, v in u.items()})
        w = wound(web, replace(sched0, web_stress=t))
        sr[i] = np.interp(radius, w.radius, w.sigma_r)
        st[i] = np.interp(radius, w.radius, w.sigma_theta)
        core_p[i] = w.core_pressure
        surf_p[i] = near_surface_pressure(w.radius, w.sigma_r, depth)
        min_hoop[i] = float(w.sigma_theta.min())
        if progress is not None and (i % 10 == 0 or i == n - 1):
            progress("winding samples", (i + 1) / n)
    return UncertaintyResult(
        n=n,
        parameters=params,
        samples=u,
        radius=radius,
        sigma_r=sr,
        sigma_theta=st,
        core_pressure=core_p,
        surface_pressure=surf_p,
        min_hoop=min_hoop,
        nominal_sigma_r=nominal.sigma_r,
        nominal_sigma_theta=nominal.sigma_theta,
        pressure_depth=depth,
        notes=tuple(notes),
    )


def _reading_surrogate(
    model: Any,
    web0: Any,
    sched0: Any,
    params: dict[str, float],
    u: dict[str, FloatArray],
    n: int,
    verify: int,
    progress: Callable[[str, float], None] | None,
) -> tuple[FloatArray, dict[str, Any]]:
    """The reading of every sample from a quadratic surrogate per standardised parameter
    (central differences of full forward runs), checked by full runs at the first
    ``verify`` samples. Returns the readings and the surrogate's description."""
    names = list(params)
    total = 1 + 2 * len(names) + verify

    def run(offsets: dict[str, float]) -> float:
        web, t = _perturb(web0, sched0.web_stress, params, offsets)
        return model.with_web(web).evaluate(t).reading

    done = 0

    def tick() -> None:
        nonlocal done
        done += 1
        if progress is not None:
            progress("reading surrogate", done / total)

    r0 = run({})
    tick()
    h = SURROGATE_STEP
    a, b = {}, {}
    for name in names:
        rp = run({name: h})
        tick()
        rm = run({name: -h})
        tick()
        a[name] = (rp - rm) / (2 * h)
        b[name] = (rp - 2 * r0 + rm) / h**2

    def surrogate(uu: dict[str, FloatArray]) -> FloatArray:
        out = np.full(np.asarray(next(iter(uu.values()))).shape, r0)
        for name in names:
            out = out + a[name] * uu[name] + 0.5 * b[name] * uu[name] ** 2
        return out

    reading = surrogate(u)
    checks = []
    for i in range(min(verify, n)):
        full = run({k: float(v[i]) for k, v in u.items()})
        tick()
        checks.append({"sample": i, "reading_full": full, "reading_surrogate": float(reading[i])})
    return reading, {
        "kind": "quadratic per standardised parameter, no cross terms",
        "step_sd": h,
        "nominal": r0,
        "linear": a,
        "quadratic": b,
        "full_runs": 1 + 2 * len(names) + len(checks),
        "checks": checks,
        "max_abs_error": max(
            (abs(c["reading_full"] - c["reading_surrogate"]) for c in checks), default=None
        ),
    }


def reduced_profile(
    case: Case,
    model: Any,
    curve: Any,
    params: dict[str, float],
    offsets: dict[str, float],
    n_sectors: int,
    *,
    pressure: bool = False,
    coupled: bool = False,
) -> tuple[FloatArray, FloatArray]:
    """Sector centres and readings (or near-surface pressures [Pa] with ``pressure``) of the
    reduced profile model at standardised offsets: uncoupled axisymmetric winding, ``P_s``
    one head radius deep, the reading along ``curve`` (linear in ln P, held at the curve's
    ends: a sector outside the curve's pressures, slack ones, gets no band). ``coupled``: the
    shear-coupled winding instead (closer to the full profile model, about 10 s for 61
    sectors instead of 1-2 s; docs/diagnosis.md)."""
    from woundroll.inverse.diagnosis import near_surface_pressure
    from woundroll.materials.thickness_profile import ThicknessProfile
    from woundroll.winding.axisymmetric import wind_axisymmetric

    web0 = model.web
    base = case.thickness_profile
    web, t = _perturb(web0, model.schedule.web_stress, params, offsets)
    prof = ThicknessProfile(
        base.position, base.thickness * (web.thickness / web0.thickness), base.source
    )
    w = wind_axisymmetric(
        web,
        model.core,
        model.outer_radius,
        replace(model.schedule, web_stress=t),
        prof,
        n_sectors=n_sectors,
        n_groups=case.profile.groups,
        shear_coupling=coupled,
    )
    ps = np.array(
        [near_surface_pressure(*w.sector_profile(j), model.depth) for j in range(w.z.size)]
    )
    if pressure:
        return w.z, ps
    lp = np.log(np.maximum(ps, 1.0))
    return w.z, np.interp(lp, np.log(curve.surface_pressure), curve.reading)


def profile_bands(
    case: Case,
    model: Any,
    u: dict[str, FloatArray],
    params: dict[str, float],
    *,
    full: Any = None,
    curve: Any = None,
    n_sectors: int | None = None,
    progress: Callable[[str, float], None] | None = None,
    calibrate: int = 1,
) -> dict[str, Any]:
    """Bands of the CMD reading profile: the reduced model's quadratic surrogate per sector
    (module docstring) at the samples ``u``; ``full`` (a ProfileResult) centres them.

    ``calibrate`` (with ``full`` and a tension tolerance): full profile runs that correct
    the tension term per sector (:func:`_calibrate_tension`): 1 -- one run at +2 SD scales
    the reduced model's term to it; 2 -- runs at +-2 SD replace it by the full model's own
    quadratic; 0 -- none.

    Returns the JSON-ready ``uncertainty.profile`` dictionary, with the per-sample readings
    under the private key ``_samples`` (n, sectors).
    """
    from woundroll.inverse.diagnosis import forward_curve

    ns = n_sectors if n_sectors is not None else case.profile.sectors
    web0 = model.web
    h = SURROGATE_STEP
    names = list(params)
    total = 2 + 2 * len(names)
    done = 0

    def tick() -> None:
        nonlocal done
        done += 1
        if progress is not None:
            progress("profile surrogate", done / total)

    if curve is None:
        curve = forward_curve(model, factors=PROFILE_CURVE_FACTORS)
    tick()
    grid = curve.web_stress
    curves: dict[tuple[str, float], Any] = {}

    def sector_readings(offsets: dict[str, float]) -> tuple[FloatArray, FloatArray]:
        cv = curve
        material = [k for k in ("K1", "K2") if offsets.get(k)]
        if material:  # the contact sees the perturbed web: its own curve, same tensions
            key = (material[0], offsets[material[0]])
            if key not in curves:
                web, _ = _perturb(web0, model.schedule.web_stress, params, offsets)
                curves[key] = forward_curve(model.with_web(web), tensions=grid)
            cv = curves[key]
        return reduced_profile(case, model, cv, params, offsets, ns)

    z, r0 = sector_readings({})
    p_s = reduced_profile(case, model, curve, params, {}, ns, pressure=True)[1]
    outside = (p_s < curve.surface_pressure.min()) | (p_s > curve.surface_pressure.max())
    tick()
    a, b, plus = _sector_sensitivities(names, sector_readings, r0, h, tick)
    a_reduced = {k: v.copy() for k, v in a.items()}
    calibration = None
    covered = {name: ~outside for name in names}
    if calibrate and full is not None and "tension" in names:
        calibration = _calibrate_tension(
            case, model, params, full, z, plus["tension"], outside, runs=calibrate
        )
        a["tension"], b["tension"] = _apply_calibration(a["tension"], b["tension"], calibration, h)
        covered["tension"] = np.ones(z.size, dtype=bool)
    delta = _surrogate_delta(u, names, a, b, covered, z.size)
    if full is not None:
        centre = np.interp(z, full.z, full.rho)
        source = "full profile run"
    else:
        centre = r0
        source = "reduced model"
    samples = centre[None, :] + delta
    surrogate = {
        "kind": "reduced profile model, quadratic per standardised parameter",
        "step_sd": h,
        "linear": {k: v.tolist() for k, v in a.items()},
        "quadratic": {k: v.tolist() for k, v in b.items()},
        "curve_runs": len(curve.points) * (1 + len(curves)),
        "linear_reduced": {k: v.tolist() for k, v in a_reduced.items()},
        "tension_calibration": calibration,
    }
    return _bands_dict(z, centre, source, samples, r0, outside, surrogate)


def _bands_dict(
    z: FloatArray,
    centre: FloatArray,
    source: str,
    samples: FloatArray,
    r0: FloatArray,
    outside: NDArray[np.bool_],
    surrogate: dict[str, Any],
) -> dict[str, Any]:
    """The ``uncertainty.profile`` dictionary: percentiles and SD of the sampled readings
    per sector, the per-sample readings under the private key ``_samples``."""
    lo, mid, hi = np.percentile(samples, PERCENTILES, axis=0)
    return {
        "z_m": z.tolist(),
        "reading_nominal": centre.tolist(),
        "centre": source,
        "reading_low": lo.tolist(),
        "reading_p50": mid.tolist(),
        "reading_high": hi.tolist(),
        "reading_sd": samples.std(axis=0, ddof=1).tolist(),
        "reduced_nominal": r0.tolist(),
        "outside_curve": [bool(x) for x in outside],
        "outside_note": "sectors whose near-surface pressure lies outside the forward "
        "curve's (slack lanes) get no band (low = high = nominal)",
        "surrogate": surrogate,
        "_samples": samples,
    }


def _sector_sensitivities(
    names: list[str],
    sector_readings: Callable[[dict[str, float]], tuple[FloatArray, FloatArray]],
    r0: FloatArray,
    h: float,
    tick: Callable[[], None],
) -> tuple[dict[str, FloatArray], dict[str, FloatArray], dict[str, FloatArray]]:
    """Per parameter and sector: the linear and quadratic terms of the surrogate (central
    differences of step ``h`` SD) and the change at +h SD."""
    a, b, plus = {}, {}, {}
    for name in names:
        rp = sector_readings({name: h})[1]
        tick()
        rm = sector_readings({name: -h})[1]
        tick()
        a[name] = (rp - rm) / (2 * h)
        b[name] = (rp - 2 * r0 + rm) / h**2
        plus[name] = rp - r0
    return a, b, plus


def _surrogate_delta(
    u: dict[str, FloatArray],
    names: list[str],
    a: dict[str, FloatArray],
    b: dict[str, FloatArray],
    covered: dict[str, NDArray[np.bool_]],
    n_sectors: int,
) -> FloatArray:
    """The surrogate's change of each sector's reading at each sample (n, sectors)."""
    delta = np.zeros((np.asarray(next(iter(u.values()))).size, n_sectors))
    for name in names:
        uu = np.asarray(u[name])[:, None]
        term = a[name][None, :] * uu + 0.5 * b[name][None, :] * uu**2
        # slack or off-curve lanes: the reduced model says nothing (the calibrated tension
        # term does: it is the full model's own change)
        delta = delta + np.where(covered[name][None, :], term, 0.0)
    return delta


#: A sector's reduced-model change at +2 SD below this [reading units] is too small to
#: scale: the full run's own change is used as a linear term there.
CALIBRATION_FLOOR = 0.05


def _calibrate_tension(
    case: Case,
    model: Any,
    params: dict[str, float],
    full: Any,
    z: FloatArray,
    reduced_plus: FloatArray,
    outside: NDArray[np.bool_],
    *,
    runs: int = 1,
) -> dict[str, Any]:
    """One full profile run (:func:`woundroll.pipeline.run`: coupled winding, the nip
    roller's CMD load if the case has one, a contact solve per sector) at +2 SD of tension;
    per sector the ratio of its change to the reduced model's change at the same step.

    The reduced model errs per sector (docs/diagnosis.md): it winds the sectors uncoupled,
    maps ``P_s`` to the reading through a uniform roll's forward curve and, for a nip,
    adds the uniform ``mu N / h``; its tension sensitivity was up to 2.5x off at the edge.
    The calibrated term reproduces the full model's change at +2 SD exactly and keeps the
    reduced model's curvature relative to its slope (checked at -2 SD in the tests).
    """
    from woundroll.pipeline import run

    if runs not in (1, 2):
        raise InputError(f"must be 0, 1 or 2 full runs, got {runs!r}", "calibrate")

    def change(t: float) -> FloatArray:
        winding = case.winding.model_copy(update={"tension": ("pressure", t)})
        prof = run(case.model_copy(update={"winding": winding})).profile
        return np.interp(z, prof.z, prof.rho) - np.interp(z, full.z, full.rho)

    t0 = model.schedule.web_stress
    t_up = t0 + SURROGATE_STEP * params["tension"]
    full_plus = change(t_up)
    ok = (np.abs(reduced_plus) > CALIBRATION_FLOOR) & (reduced_plus * full_plus > 0) & ~outside
    ratio = np.where(ok, full_plus / np.where(ok, reduced_plus, 1.0), np.nan)
    out: dict[str, Any] = {
        "full_runs": runs,
        "web_stress_Pa": t_up,
        "full_change": full_plus.tolist(),
        "reduced_change": reduced_plus.tolist(),
        "ratio": [None if not math.isfinite(x) else float(x) for x in ratio],
        "linear_only": [bool(x) for x in ~ok],
    }
    if runs == 2:
        t_down = max(t0 - SURROGATE_STEP * params["tension"], 0.0)
        out["web_stress_minus_Pa"] = t_down
        out["full_change_minus"] = change(t_down).tolist()
    return out


def _apply_calibration(
    a: FloatArray, b: FloatArray, cal: dict[str, Any], h: float
) -> tuple[FloatArray, FloatArray]:
    """The tension term scaled per sector to the full run's change at +h SD; sectors where
    the reduced model's change is too small (or of the other sign, or off its curve) take
    the full run's change as a linear term."""
    full_plus = np.asarray(cal["full_change"], dtype=float)
    if "full_change_minus" in cal:  # the full model's own quadratic through -h, 0, +h
        full_minus = np.asarray(cal["full_change_minus"], dtype=float)
        return (full_plus - full_minus) / (2 * h), (full_plus + full_minus) / h**2
    ratio = np.array([np.nan if x is None else x for x in cal["ratio"]], dtype=float)
    ok = np.isfinite(ratio)
    a2 = np.where(ok, a * np.where(ok, ratio, 1.0), full_plus / h)
    b2 = np.where(ok, b * np.where(ok, ratio, 1.0), 0.0)
    return a2, b2
