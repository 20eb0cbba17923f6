"""Profile -> causes: which winder or web condition explains a measured CMD hardness profile.

Given readings across the roll (:class:`~woundroll.io.readings.Readings`), fit the inputs of the
axisymmetric model that explain them:

* a smooth **thickness variation** (gauge bands): ``h(z) = h_0(z) (1 + sum_k c_k B_k(z))``
  with ``K`` Gaussian bumps ``B_k`` evenly spaced over the width (width ``W / K`` at half
  height), their mean removed (a mean caliper change is not visible in hardness at a given
  tension); ``h_0`` is the case's own thickness profile (the starting guess) or uniform;
* the **tension level** ``T0 = s T_case`` (``ln s`` fitted);
* the **nip's CMD deflection** (cases with a nip and nip friction): the nip load
  ``N(z) = N0 (1 + d q(z))``, ``q = (2 (z - z_0)/W - 1)^2 - 1/3`` (zero mean; ``d > 0``:
  more load at the edges, a roller bending away in the middle). The **nip level** acts
  like the tension level (both add a uniform ``mu N / h`` or ``T`` to the wound-on tension)
  and cannot be told apart from it by hardness: it is not fitted, and a note says so.

Reduced model (verified against the full one, docs/diagnosis.md): the axisymmetric winding
with **uncoupled sectors** (``shear_coupling=False``: each sector a 1D roll, the tension
shared by the relaxation-radius allocation) -- about 1 s for 31 sectors instead of 20-50 s --
and the reading of each sector from its near-surface pressure ``P_s`` (one head radius deep)
through the case's forward curve (:mod:`woundroll.inverse.diagnosis`), checked by the full contact
model at three sectors.

Fit: regularised Gauss-Newton (a Bayesian reading): residuals weighted by the readings'
standard errors; priors ``c_k ~ N(0, prior_band^2)`` (default 1 % caliper), ``ln s ~ N(0, 1)``,
``d ~ N(0, 1)``. Jacobian by forward differences, then up to three frozen-Jacobian steps;
when the tension level moved by more than ``RELINEARISE`` the Jacobian is recomputed at the
fit and the steps repeated. The posterior covariance ``(J^T W J + P^-1)^-1`` at the fit,
scaled by the residuals' reduced chi-square ``chi2 / (n - tr H)`` when it exceeds 1 (the
Birge ratio: model error and causes outside the basis), gives each parameter's SD (its
coverage over noise draws against the full profile model: docs/diagnosis.md); a
parameter whose posterior SD is more than 0.7 of its prior SD is **not identifiable** from
these readings, and two whose posterior correlation exceeds 0.9 in magnitude cannot be
told apart: both are reported rather than guessed.

Causes are ranked by their share of the explained CMD variation: each cause's contribution
``J_g dtheta_g`` to the reading profile, its CMD mean removed, squared norm over the sum.
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

if TYPE_CHECKING:
    from woundroll.case import Case
    from woundroll.inverse.diagnosis import ForwardCurve, RollModel
    from woundroll.io.readings import Readings

FloatArray = NDArray[np.float64]
INCH = 0.0254
#: Tension-level change (in ln s) beyond which the Jacobian is recomputed at the fit.
RELINEARISE = 0.05

__all__ = ["CauseFit", "ProfileModel", "fit_causes"]


@dataclass(frozen=True)
class ProfileModel:
    """The reduced CMD model: uncoupled axisymmetric sectors + the ``P_s`` -> reading map."""

    roll: RollModel
    curve: ForwardCurve
    base_position: FloatArray
    base_thickness: FloatArray
    n_bands: int
    n_sectors: int = 31
    nip_deflection: bool = False

    @property
    def width(self) -> float:
        return float(self.base_position[-1] - self.base_position[0])

    def basis(self, z: FloatArray) -> FloatArray:
        """(K, len(z)) Gaussian bumps, centred at (k + 1/2) W / K, FWHM W / K."""
        z0, W, K = float(self.base_position[0]), self.width, self.n_bands
        centres = z0 + (np.arange(K) + 0.5) * W / K
        sig = (W / K) / 2.3548
        return np.exp(-0.5 * ((np.asarray(z)[None, :] - centres[:, None]) / sig) ** 2)

    @property
    def band_centres(self) -> FloatArray:
        return float(self.base_position[0]) + (np.arange(self.n_bands) + 0.5) * (
            self.width / self.n_bands
        )

    def n_params(self) -> int:
        return 1 + int(self.nip_deflection) + self.n_bands

    def split(self, theta: FloatArray) -> tuple[float, float, FloatArray]:
        ln_s = float(theta[0])
        d = float(theta[1]) if self.nip_deflection else 0.0
        return ln_s, d, np.asarray(theta[1 + int(self.nip_deflection) :])

    def thickness(self, c: FloatArray, z: FloatArray | None = None) -> FloatArray:
        """Thickness [m] at ``z`` (default the base grid) for band amplitudes ``c``."""
        z = self.base_position if z is None else np.asarray(z)
        B = self.basis(self.base_position)
        rel = c @ B
        rel = rel - np.trapezoid(rel, self.base_position) / self.width  # zero mean
        h = self.base_thickness * (1.0 + rel)
        return np.interp(z, self.base_position, h)

    def sector_pressure(self, theta: FloatArray) -> tuple[FloatArray, FloatArray, Any]:
        """Sector centres [m], near-surface pressure [Pa] per sector, and the winding."""
        from woundroll.materials.thickness_profile import ThicknessProfile
        from woundroll.winding.axisymmetric import wind_axisymmetric

        ln_s, d, c = self.split(theta)
        h = self.thickness(c)
        if np.any(h <= 0):
            raise InputError("fitted thickness not positive: bands too deep", "readings")
        prof = ThicknessProfile(self.base_position, h, "fit")
        r = self.roll
        sched = replace(r.schedule, web_stress=r.schedule.web_stress * math.exp(ln_s))
        nip = None
        if self.nip_deflection and d != 0.0:
            z0, W, N0 = float(self.base_position[0]), self.width, r.schedule.nip_load

            def nip(g: int, outer: FloatArray, sig: FloatArray) -> FloatArray:  # noqa: ARG001
                zc = np.linspace(z0, z0 + W, outer.size + 1)
                zc = 0.5 * (zc[1:] + zc[:-1])
                q = (2 * (zc - z0) / W - 1) ** 2 - 1 / 3
                return np.maximum(N0 * (1 + d * q), 0.0)

        res = wind_axisymmetric(
            r.web,
            r.core,
            r.outer_radius,
            sched,
            prof,
            n_sectors=self.n_sectors,
            shear_coupling=False,
            nip=nip,
        )
        ps = np.empty(res.sigma_r.shape[1])
        for j in range(ps.size):
            rr = res.radius[:, j] if res.radius.ndim == 2 else res.radius
            ps[j] = -np.interp(rr[-1] - r.depth, rr, res.sigma_r[:, j])
        return res.z, ps, res

    def reading_of_pressure(self, ps: FloatArray) -> FloatArray:
        """Reading for a near-surface pressure, along the forward curve (monotone; linear in
        ln P beyond its ends)."""
        p, rd = self.curve.surface_pressure, self.curve.reading
        lp = np.log(np.maximum(ps, 1.0))
        return _lin_extrap(lp, np.log(p), rd)

    def readings(self, theta: FloatArray, positions: FloatArray) -> FloatArray:
        z, ps, _ = self.sector_pressure(theta)
        return np.interp(positions, z, self.reading_of_pressure(ps))


def _lin_extrap(x: FloatArray, xp: FloatArray, fp: FloatArray) -> FloatArray:
    y = np.interp(x, xp, fp)
    lo, hi = x < xp[0], x > xp[-1]
    y[lo] = fp[0] + (x[lo] - xp[0]) * (fp[1] - fp[0]) / (xp[1] - xp[0])
    y[hi] = fp[-1] + (x[hi] - xp[-1]) * (fp[-1] - fp[-2]) / (xp[-1] - xp[-2])
    return y


@dataclass(frozen=True)
class CauseFit:
    """The fitted causes of a CMD hardness profile (module docstring)."""

    model: ProfileModel
    readings: Readings
    theta: FloatArray
    sd: FloatArray
    prior_sd: FloatArray
    correlation: FloatArray
    fitted: FloatArray
    initial: FloatArray
    causes: list[dict[str, Any]]
    identifiable: list[bool]
    notes: tuple[str, ...] = ()
    verification: dict[str, Any] = field(default_factory=dict)
    forward_runs: int = 0
    sd_scale: float = 1.0
    residual_chi2: float = math.nan
    residual_dof: float = math.nan

    @property
    def names(self) -> list[str]:
        m = self.model
        n = ["tension level ln(T0/T_case)"]
        if m.nip_deflection:
            n.append("nip deflection d")
        n += [f"band at {c / INCH:.1f} in" for c in m.band_centres]
        return n

    @property
    def residual_rms(self) -> float:
        return float(np.sqrt(np.mean((self.fitted - self.readings.mean) ** 2)))

    def thickness_profile(self, n: int = 121) -> tuple[FloatArray, FloatArray, FloatArray]:
        """z [m], fitted thickness [m] and its SD [m] (linear propagation of the band SDs)."""
        m = self.model
        z = np.linspace(m.base_position[0], m.base_position[-1], n)
        _, _, c = m.split(self.theta)
        h = m.thickness(c, z)
        k0 = 1 + int(m.nip_deflection)
        B = m.basis(z)
        B = B - B.mean(axis=1, keepdims=True)
        cov = self._cov()[k0:, k0:]
        var = np.einsum("kz,kl,lz->z", B, cov, B)
        return z, h, np.interp(z, m.base_position, m.base_thickness) * np.sqrt(np.maximum(var, 0))

    def _cov(self) -> FloatArray:
        return self.correlation * np.outer(self.sd, self.sd)

    def to_dict(self) -> dict[str, Any]:
        z, h, hsd = self.thickness_profile()
        return {
            "profile": {
                "z_m": z.tolist(),
                "thickness_m": h.tolist(),
                "thickness_low_m": (h - 1.96 * hsd).tolist(),
                "thickness_high_m": (h + 1.96 * hsd).tolist(),
                "position_m": self.readings.position.tolist(),
                "reading_measured": self.readings.mean.tolist(),
                "reading_fit": self.fitted.tolist(),
                "reading_initial": self.initial.tolist(),
                "residual_rms": self.residual_rms,
            },
            "parameters": [
                {
                    "name": n,
                    "value": float(v),
                    "sd": float(s),
                    "prior_sd": float(p),
                    "identifiable": bool(i),
                }
                for n, v, s, p, i in zip(
                    self.names, self.theta, self.sd, self.prior_sd, self.identifiable, strict=True
                )
            ],
            "correlation": self.correlation.tolist(),
            "causes": self.causes,
            "verification": self.verification,
            "forward_runs": self.forward_runs,
            "posterior_sd_scale": self.sd_scale,
            "residual_chi2": self.residual_chi2,
            "residual_dof": self.residual_dof,
            "notes": list(self.notes),
        }

    def plot(self, path: str | Path | None = None) -> Any:
        """Measured, initial and fitted readings; the fitted thickness with its band."""
        import matplotlib.pyplot as plt

        r = self.readings
        fig, (a1, a2) = plt.subplots(2, 1, sharex=True, figsize=(6.4, 6.0))
        x = r.position / INCH
        a1.errorbar(x, r.mean, yerr=r.scatter, fmt="o", color="k", ms=4, label="measured")
        a1.plot(x, self.initial, "--", color="C7", label="case as given")
        a1.plot(x, self.fitted, "-", color="C0", label="fitted causes")
        a1.set_ylabel(f"reading [{r.scale}]")
        a1.legend(fontsize=8)
        a1.grid(alpha=0.3)
        z, h, hsd = self.thickness_profile()
        a2.fill_between(z / INCH, (h - 1.96 * hsd) * 1e6, (h + 1.96 * hsd) * 1e6, alpha=0.3)
        a2.plot(z / INCH, h * 1e6, color="C0")
        a2.set_ylabel("fitted thickness [um]")
        a2.set_xlabel("CMD position [in]")
        a2.grid(alpha=0.3)
        if self.causes:
            a1.set_title(self.causes[0]["sentence"], fontsize=8)
        fig.tight_layout()
        if path is not None:
            fig.savefig(path, dpi=120)
        return fig


def fit_causes(
    case: Case | str | Path,
    readings: Readings | str | Path | None = None,
    *,
    n_bands: int | None = None,
    prior_band: float = 0.01,
    n_sectors: int = 31,
    steps: int = 3,
    verify: bool = True,
    progress: Callable[[str, float], None] | None = None,
    calibrate_sd: bool = True,
    cache: dict[str, Any] | None = None,
    full_level: int = 0,
) -> CauseFit:
    """Fit thickness bands, tension level and nip deflection to a CMD hardness profile.

    ``calibrate_sd``: scale the posterior covariance by the residuals' reduced chi-square
    when it exceeds 1 (module docstring, "Posterior SDs"). ``cache``: a dict shared by
    repeated fits of the same roll at the same positions (noise studies): the forward curve
    and the Jacobian at the starting point are computed once. ``full_level``: runs (1-3)
    of the full profile model (:func:`woundroll.pipeline.run`, coupled winding and a contact
    solve per sector, 20-50 s each) at the fitted thickness that correct the tension level
    for the reduced model's level error (:func:`_full_level`).

    Raises
    ------
    InputError
        No readings, fewer than 3 positions, a scale the instrument does not read.
    """
    from woundroll.inverse.diagnosis import RollModel

    case, readings = _case_and_readings(case, readings)
    roll = RollModel.from_case(case, readings.scale)
    notes: list[str] = []
    model, runs = _reduced_model(case, roll, readings, n_bands, n_sectors, cache, notes)
    problem = _CauseProblem.build(
        model, readings, _standard_errors(case, readings, notes), prior_band, progress, runs
    )
    # search: Gauss-Newton from the case as given
    f0, J = problem.start(cache)
    theta, fk, J = problem.search(f0, J, steps)
    cov = np.linalg.inv(problem.normal_matrix(J))
    level: dict[str, Any] = {}
    if full_level:
        theta, level = problem.correct_level(case, theta, fk, J, int(full_level), notes)
    sd, corr, sd_scale, chi2_res, dof = problem.posterior(J, cov, fk, calibrate_sd, notes)
    # rank: the causes in plain words, and whether the profile has a CMD pattern at all
    identifiable = [bool(s < 0.7 * p) for s, p in zip(sd, problem.prior, strict=True)]
    causes = _rank(model, J, theta, sd, identifiable, corr, readings)
    problem.check_flat(causes, notes)
    # verify: the P_s -> reading map against the contact model
    verification: dict[str, Any] = {}
    if level:
        verification["full_level"] = level
    if verify:
        verification.update(problem.verify(theta, notes))
    return CauseFit(
        model=model,
        readings=readings,
        theta=theta,
        sd=sd,
        prior_sd=problem.prior,
        correlation=corr,
        fitted=fk,
        initial=f0.copy(),
        causes=causes,
        identifiable=identifiable,
        notes=tuple(notes),
        verification=verification,
        forward_runs=problem.runs,
        sd_scale=sd_scale,
        residual_chi2=chi2_res,
        residual_dof=dof,
    )


def _case_and_readings(
    case: Case | str | Path, readings: Readings | str | Path | None
) -> tuple[Case, Readings]:
    """The case and its readings (the case's own [readings] file when none are given)."""
    from woundroll.case import Case, load_case
    from woundroll.io.readings import Readings, read_readings

    if not isinstance(case, Case):
        case = load_case(case)
    if readings is None:
        readings = case.measured_readings
        if readings is None:
            raise InputError("no readings: give [readings] file = ... or --readings", "readings")
    elif not isinstance(readings, Readings):
        readings = read_readings(readings, width=case.web.width, field="--readings")
    if readings.n_positions < 3:
        raise InputError("a CMD profile needs readings at >= 3 positions", "readings")
    return case, readings


def _reduced_model(
    case: Case,
    roll: RollModel,
    readings: Readings,
    n_bands: int | None,
    n_sectors: int,
    cache: dict[str, Any] | None,
    notes: list[str],
) -> tuple[ProfileModel, int]:
    """The reduced profile model on the starting thickness, and the forward runs its
    ``P_s`` -> reading map took (0 from the cache)."""
    from woundroll.inverse.diagnosis import forward_curve

    if case.thickness_profile is not None:
        base = case.thickness_profile
        notes.append(f"starting guess: the case's thickness profile ({base.source})")
    else:
        from woundroll.materials.thickness_profile import ThicknessProfile

        base = ThicknessProfile.uniform(roll.web.thickness, roll.web.width)
    pos = np.linspace(base.position[0], base.position[-1], 241)
    h0 = np.interp(pos, base.position, base.thickness)
    nip_defl = roll.schedule.nip_load > 0 and roll.schedule.friction > 0
    if roll.schedule.nip_load > 0 and roll.schedule.friction > 0:
        notes.append(
            "nip level and tension level both add a uniform wound-on tension and cannot be "
            "told apart by hardness: the level is fitted as tension, the nip's CMD deflection "
            "separately"
        )
    if case.winding.nip_roller is not None:
        notes.append(
            "the case's [winding.nip_roller] beam is not used: the nip's CMD distribution is "
            "the fitted deflection shape"
        )
    K = n_bands if n_bands is not None else int(min(8, max(2, readings.n_positions // 2)))
    # the P_s -> reading map: the case's forward curve over the readings' range (widened)
    r_lo, r_hi = float(readings.mean.min()), float(readings.mean.max())
    if cache is not None and "curve" in cache:
        curve = cache["curve"]
        runs = 0
    else:
        curve = forward_curve(roll, [0.8 * r_lo, 1.2 * r_hi])
        runs = len(curve.points)
        if cache is not None:
            cache["curve"] = curve
    return ProfileModel(roll, curve, pos, h0, K, n_sectors, nip_defl), runs


def _standard_errors(case: Case, readings: Readings, notes: list[str]) -> FloatArray:
    """One standard error per position from the pooled repeatability (a per-position SD
    from 2-3 passes is too noisy to weight with), else the case's, else the positions' own;
    1 % of the mean reading where there is no scatter."""
    from woundroll.inverse.diagnosis import _quantiles

    repeat = case.readings.repeatability if case.readings is not None else None
    pooled = readings.pooled_sd or repeat
    if pooled:
        se = np.full(readings.n_positions, float(pooled)) / np.sqrt(readings.count)
    else:
        se = _quantiles(readings, 0.6826894921370859, repeat)
    if not np.all(se > 0):
        floor = 0.01 * float(np.mean(readings.mean))
        se = np.where(se > 0, se, floor)
        notes.append(
            f"no scatter for some positions: their standard error is taken as 1 % of the "
            f"mean reading ({floor:.2g} {readings.scale})"
        )
    return se


@dataclass
class _CauseProblem:
    """The regularised least-squares problem of :func:`fit_causes`: readings ``y`` at ``x``
    with weights ``Wd`` (1/SE^2), the priors ``P_inv``, and the forward runs counted."""

    model: ProfileModel
    readings: Readings
    se: FloatArray
    prior: FloatArray
    prior_band: float
    P_inv: FloatArray
    fd_steps: FloatArray
    progress: Callable[[str, float], None] | None
    runs: int

    @classmethod
    def build(
        cls,
        model: ProfileModel,
        readings: Readings,
        se: FloatArray,
        prior_band: float,
        progress: Callable[[str, float], None] | None,
        runs: int,
    ) -> _CauseProblem:
        npar = model.n_params()
        nip_defl = model.nip_deflection
        prior = np.full(npar, prior_band)
        prior[0] = 1.0
        if nip_defl:
            prior[1] = 1.0
        # forward-difference Jacobian (steps: 1 % in ln s, 0.1 in d, 0.2 % caliper per band)
        fd_steps = np.full(npar, 0.002)
        fd_steps[0] = 0.01
        if nip_defl:
            fd_steps[1] = 0.1
        # priors, and the bands summing to zero: a uniform shift of every c_k leaves the
        # mean-removed thickness (nearly) unchanged and would otherwise be decided by the prior
        P_inv = np.diag(1.0 / prior**2)
        ones = np.zeros(npar)
        ones[1 + int(nip_defl) :] = 1.0
        P_inv += np.outer(ones, ones) / (0.1 * prior_band) ** 2
        return cls(model, readings, se, prior, prior_band, P_inv, fd_steps, progress, runs)

    @property
    def x(self) -> FloatArray:
        return self.readings.position

    @property
    def y(self) -> FloatArray:
        return self.readings.mean

    @property
    def Wd(self) -> FloatArray:
        return 1.0 / self.se**2

    def forward(self, th: FloatArray) -> FloatArray:
        self.runs += 1
        return self.model.readings(th, self.x)

    def jacobian(self, th: FloatArray, f_th: FloatArray) -> FloatArray:
        npar = self.prior.size
        out = np.empty((self.x.size, npar))
        for k in range(npar):
            if self.progress is not None:
                self.progress("jacobian", k / npar)
            t = th.copy()
            t[k] += self.fd_steps[k]
            out[:, k] = (self.forward(t) - f_th) / self.fd_steps[k]
        return out

    def normal_matrix(self, J: FloatArray) -> FloatArray:
        return J.T @ (self.Wd[:, None] * J) + self.P_inv

    def objective(self, theta: FloatArray, f_theta: FloatArray) -> float:
        return float(np.sum(self.Wd * (self.y - f_theta) ** 2) + theta @ self.P_inv @ theta)

    def start(self, cache: dict[str, Any] | None) -> tuple[FloatArray, FloatArray]:
        """Readings and Jacobian of the case as given (theta = 0), through the cache."""
        m = self.model
        key = ("jacobian", tuple(np.round(self.x, 9)), m.n_bands, m.n_sectors, m.nip_deflection)
        if cache is not None and key in cache:
            return cache[key]
        theta = np.zeros(self.prior.size)
        f0 = self.forward(theta)
        J = self.jacobian(theta, f0)
        if cache is not None:
            cache[key] = (f0, J)
        return f0, J

    def search(
        self, f0: FloatArray, J: FloatArray, steps: int
    ) -> tuple[FloatArray, FloatArray, FloatArray]:
        """Frozen-Jacobian Gauss-Newton steps on the regularised objective from theta = 0;
        when the tension level moved by more than RELINEARISE (in ln s) the Jacobian is
        recomputed at the fit and the steps repeated (once). Returns theta, its readings
        and the Jacobian the covariance is taken with."""
        Wd, y = self.Wd, self.y
        theta = np.zeros(self.prior.size)
        A = self.normal_matrix(J)
        best = (self.objective(theta, f0), theta, f0)
        relinearised = False
        while True:
            for _ in range(steps):
                th_b, f_b = best[1], best[2]
                g = J.T @ (Wd * (y - f_b)) - self.P_inv @ th_b
                theta = th_b + np.linalg.solve(A, g)
                fk = self.forward(theta)
                obj = self.objective(theta, fk)
                if obj < best[0] * (1 - 1e-6):
                    best = (obj, theta.copy(), fk.copy())
                else:
                    break
                if self.progress is not None:
                    self.progress("fit", 1.0)
            # the sensitivities change with the tension level: recompute them at the fit
            if relinearised or abs(best[1][0]) <= RELINEARISE:
                break
            relinearised = True
            J = self.jacobian(best[1], best[2])
            A = self.normal_matrix(J)
        return best[1], best[2], J

    def correct_level(
        self,
        case: Case,
        theta: FloatArray,
        fk: FloatArray,
        J: FloatArray,
        full_runs: int,
        notes: list[str],
    ) -> tuple[FloatArray, dict[str, Any]]:
        """The tension level corrected by the full profile model (:func:`_full_level`); the
        reduced model's fit ``fk`` stays the fitted readings: the full model reproduces them
        at the corrected level."""
        level = _full_level(case, self.model, theta, fk, J[:, 0], self.x, runs=full_runs)
        theta = theta.copy()
        theta[0] += level["ln_s_correction"]
        self.runs += level["full_runs"]
        notes.append(
            f"tension level corrected by the full profile model ({level['full_runs']} "
            f"run(s)): at the reduced model's level its readings were "
            f"{level['offsets'][0]:+.2g} {self.readings.scale} off on average; ln(T0/T_case) "
            f"moved by {level['ln_s_correction']:+.3f} (the SD does not include this "
            "model error)"
        )
        return theta, level

    def posterior(
        self,
        J: FloatArray,
        cov: FloatArray,
        fk: FloatArray,
        calibrate_sd: bool,
        notes: list[str],
    ) -> tuple[FloatArray, FloatArray, float, float, float]:
        """Posterior SDs and correlation: ``(J^T W J + P^-1)^-1`` trusts the weights and the
        reduced model; when the residuals are larger than the weights say (model error of
        the reduced model, a cause outside the basis), it is scaled by the reduced
        chi-square (Birge ratio) over the effective degrees of freedom n - tr(H), H the
        regularised fit's hat matrix. Returns sd, corr, the scale, chi2 and dof."""
        Wd, y = self.Wd, self.y
        chi2_res = float(np.sum(Wd * (y - fk) ** 2))
        dof = float(y.size - np.trace(J @ cov @ J.T @ np.diag(Wd)))
        sd_scale = 1.0
        if calibrate_sd:
            if dof >= 1.0:
                sd_scale = max(1.0, math.sqrt(chi2_res / dof))
            else:
                notes.append(
                    f"{y.size} positions for {self.prior.size} parameters leave no degrees of "
                    "freedom to check the posterior SDs against the residuals: they may be "
                    "optimistic"
                )
        cov = cov * sd_scale**2
        if sd_scale > 1.0:
            notes.append(
                f"the residuals are {sd_scale:.2g} times larger than the readings' scatter "
                f"(chi-square {chi2_res:.3g} on {dof:.3g} effective degrees of freedom): the "
                "posterior SDs are scaled up by that factor"
            )
        sd = np.sqrt(np.diag(cov))
        return sd, cov / np.outer(sd, sd), sd_scale, chi2_res, dof

    def check_flat(self, causes: list[dict[str, Any]], notes: list[str]) -> None:
        """Is there a CMD pattern at all? The chi-square of the means about their weighted
        mean; when it is within the scatter, no CMD cause is significant."""
        from scipy.stats import chi2

        Wd, y = self.Wd, self.y
        ybar = float(np.sum(Wd * y) / np.sum(Wd))
        stat = float(np.sum(Wd * (y - ybar) ** 2))
        p_flat = float(chi2.sf(stat, y.size - 1))
        if p_flat > 0.05:
            notes.append(
                f"the CMD variation of the readings is within their scatter (chi-square p = "
                f"{p_flat:.2f}): no CMD cause can be identified from them"
            )
            for cz in causes:
                if cz["cause"] != "tension level" and "not" not in cz["sentence"]:
                    cz["sentence"] += " (within the noise: not significant)"
                    cz["identifiable"] = False

    def verify(self, theta: FloatArray, notes: list[str]) -> dict[str, Any]:
        """The map against the contact model at three sectors (:func:`_verify`)."""
        verification = _verify(self.model, theta)
        self.runs += 3
        err = verification.get("max_abs_error")
        if err is not None and err > 2 * float(np.mean(self.se)):
            notes.append(
                f"the P_s -> reading map is off by up to {err:.2g} {self.readings.scale} "
                "against the contact model on this profile: treat the band amplitudes as "
                "indicative"
            )
        return verification


def _full_level(
    case: Case,
    model: ProfileModel,
    theta: FloatArray,
    fitted: FloatArray,
    d_ln_s: FloatArray,
    x: FloatArray,
    *,
    runs: int = 2,
) -> dict[str, Any]:
    """The tension level at which the full profile model, with the fitted thickness,
    reproduces the mean of the fitted readings: a first step along the reduced model's
    sensitivity of the mean reading to ln s, then (``runs`` 2 or 3) secants on the full
    model's own runs."""
    import tempfile

    from woundroll.pipeline import run

    ln_s, _, c = model.split(theta)
    h = model.thickness(c)

    def mean_offset(ls: float, tmp: str) -> tuple[float, FloatArray]:
        path = Path(tmp) / "fitted_thickness.csv"
        np.savetxt(
            path,
            np.column_stack([model.base_position * 1e3, h * 1e6]),
            delimiter=",",
            header="position [mm],thickness [um]",
            comments="",
        )
        winding = case.winding.model_copy(
            update={
                "thickness_profile": str(path),
                "tension": ("pressure", math.exp(ls) * model.roll.tension),
            }
        )
        profile = case.profile.model_copy(update={"sectors": model.n_sectors})
        fitted_case = case.model_copy(update={"winding": winding, "profile": profile})
        fitted_case.__dict__.pop("thickness_profile", None)  # cached from the original case
        prof = run(fitted_case).profile
        full = np.interp(x, prof.z, prof.rho)
        return float(np.mean(full - fitted)), full

    slope = float(np.mean(d_ln_s))
    levels, offsets, readings = [ln_s], [], []
    with tempfile.TemporaryDirectory() as tmp:
        for k in range(max(1, min(runs, 3))):
            off, full = mean_offset(levels[-1], tmp)
            offsets.append(off)
            readings.append(full.tolist())
            if k >= 1 and levels[k] != levels[k - 1] and offsets[k] != offsets[k - 1]:
                slope = (offsets[k] - offsets[k - 1]) / (levels[k] - levels[k - 1])
            levels.append(levels[-1] - off / slope if slope > 0 else levels[-1])
    return {
        "full_runs": len(offsets),
        "ln_s_levels": levels,
        "offsets": offsets,
        "reading_full": readings,
        "reading_reduced": fitted.tolist(),
        "full_slope": slope,
        "ln_s_correction": levels[-1] - ln_s,
    }


def _verify(model: ProfileModel, theta: FloatArray) -> dict[str, Any]:
    """The full contact model at three sectors (lowest, median, highest P_s) against the map."""
    from woundroll.contact import roll_stiffness
    from woundroll.inverse.diagnosis import reading_of
    from woundroll.pipeline import hardness_on_roll

    z, ps, res = model.sector_pressure(theta)
    order = np.argsort(ps)
    pick = sorted({int(order[0]), int(order[len(order) // 2]), int(order[-1])})
    r = model.roll
    out = []
    for j in pick:
        rr = res.radius[:, j] if res.radius.ndim == 2 else res.radius
        web = replace(r.web, thickness=float(res.thickness[j]))
        st = roll_stiffness(
            web, r.core, rr, res.sigma_r[:, j], r.setup.instrument, friction=r.friction,
            options=r.contact_options, model=r.contact_model,
        )  # fmt: skip
        h = hardness_on_roll(r.setup, st, float(rr[-1] - rr[0]), web.density)
        full = reading_of(h, r.scale)
        out.append(
            {
                "z_m": float(z[j]),
                "surface_pressure_Pa": float(ps[j]),
                "reading_map": float(model.reading_of_pressure(np.array([ps[j]]))[0]),
                "reading_full": full,
            }
        )
    return {
        "sectors": out,
        "max_abs_error": max(abs(o["reading_map"] - o["reading_full"]) for o in out),
    }


def _rank(
    model: ProfileModel,
    J: FloatArray,
    theta: FloatArray,
    sd: FloatArray,
    ident: list[bool],
    corr: FloatArray,
    readings: Readings,
) -> list[dict[str, Any]]:
    """Causes in plain words, ranked by their share of the explained CMD variation."""
    groups = [_level_cause(model, theta, sd)]
    if model.nip_deflection:
        groups.append(_nip_cause(theta, sd, ident))
    groups += _band_causes(model, theta, sd, ident)
    out = _by_share(groups, J, theta, ident, readings)
    if model.nip_deflection:
        out += _confounded_with_nip(model, corr)
    return out


#: A cause: its name, the indices of its parameters and its sentence.
_Cause = tuple[str, list[int], str]


def _level_cause(model: ProfileModel, theta: FloatArray, sd: FloatArray) -> _Cause:
    ln_s = float(theta[0])
    return (
        "tension level",
        [0],
        f"the roll reads as if wound at {100 * math.exp(ln_s):.0f} % of the case's tension "
        f"(T0 = {model.roll.tension * math.exp(ln_s) / 1e6:.3g} MPa, SD "
        f"{100 * sd[0]:.1f} %)",
    )


def _nip_cause(theta: FloatArray, sd: FloatArray, ident: list[bool]) -> _Cause:
    d = float(theta[1])
    where = "edges" if d > 0 else "middle"
    extra = ""
    if not ident[1]:
        extra = " (not identifiable: a nip deflection leaves almost no trace in these readings)"
    elif abs(d) < 2 * sd[1]:
        extra = " (within the noise: not significant)"
    return (
        "nip deflection",
        [1],
        f"the nip load is higher toward the {where} (a deflecting nip roller), "
        f"about {100 * abs(d) * 2 / 3:.0f} % more there than the average" + extra,
    )


def _band_causes(
    model: ProfileModel, theta: FloatArray, sd: FloatArray, ident: list[bool]
) -> list[_Cause]:
    """Thickness bands: contiguous runs of basis functions with the same sign and a
    meaningful amplitude (a quarter of the largest, at least 1e-4)."""
    k0 = 1 + int(model.nip_deflection)
    c = theta[k0:]
    thr = max(0.25 * float(np.max(np.abs(c))) if c.size else 0.0, 1e-4)
    out = []
    k = 0
    while k < c.size:
        if abs(c[k]) < thr:
            k += 1
            continue
        sign = np.sign(c[k])
        run = [k]
        while (
            run[-1] + 1 < c.size and np.sign(c[run[-1] + 1]) == sign and abs(c[run[-1] + 1]) >= thr
        ):
            run.append(run[-1] + 1)
        out.append(_band_cause(model, c, run, sd, ident))
        k = run[-1] + 1
    return out


def _band_cause(
    model: ProfileModel, c: FloatArray, run: list[int], sd: FloatArray, ident: list[bool]
) -> _Cause:
    """One band: the run of basis functions ``run`` of amplitudes ``c``."""
    k0 = 1 + int(model.nip_deflection)
    centres = model.band_centres
    W = model.width / model.n_bands
    lo = (centres[run[0]] - W / 2) / INCH
    hi = (centres[run[-1]] + W / 2) / INCH
    peak = float(c[run][np.argmax(np.abs(c[run]))])
    kind = "thick" if np.sign(c[run[0]]) > 0 else "thin"
    ok = all(ident[k0 + i] for i in run)
    k_peak = k0 + run[int(np.argmax(np.abs(c[run])))]
    if not ok:
        extra = " (not identifiable: the readings hardly constrain it)"
    elif abs(peak) < 2 * sd[k_peak]:
        extra = " (within the noise: not significant)"
    else:
        extra = ""
    return (
        f"{kind} band {lo:.0f}-{hi:.0f} in",
        [k0 + i for i in run],
        f"a persistent {kind} band at {lo:.0f}-{hi:.0f} in, about {100 * peak:+.1f} % "
        "caliper" + extra,
    )


def _by_share(
    groups: list[_Cause],
    J: FloatArray,
    theta: FloatArray,
    ident: list[bool],
    readings: Readings,
) -> list[dict[str, Any]]:
    """Each cause's contribution ``J_g dtheta_g`` to the reading profile, its CMD mean
    removed: the causes sorted by its squared norm's share of the sum."""
    contrib = []
    for name, idx, sentence in groups:
        v = J[:, idx] @ theta[idx]
        var = v - v.mean()
        contrib.append((name, idx, sentence, float(var @ var), float(np.mean(v))))
    total = sum(c[3] for c in contrib) or 1.0
    out = []
    for name, idx, sentence, var, mean_shift in sorted(contrib, key=lambda t: -t[3]):
        share = var / total
        ident_all = all(ident[i] for i in idx)
        text = sentence
        if name != "tension level":
            text += f"; explains {100 * share:.0f} % of the CMD variation"
        else:
            text += f"; shifts the mean reading by {mean_shift:+.1f} {readings.scale}"
        out.append(
            {
                "cause": name,
                "share": share,
                "mean_shift": mean_shift,
                "identifiable": ident_all,
                "sentence": text,
            }
        )
    return out


def _confounded_with_nip(model: ProfileModel, corr: FloatArray) -> list[dict[str, Any]]:
    """Pairs that cannot be told apart: the nip deflection and a band correlated > 0.9."""
    k0 = 1 + int(model.nip_deflection)
    centres = model.band_centres
    k1 = 1
    out = []
    for k in range(k0, corr.shape[0]):
        if abs(corr[k1, k]) > 0.9:
            out.append(
                {
                    "cause": "not identifiable",
                    "share": 0.0,
                    "mean_shift": 0.0,
                    "identifiable": False,
                    "sentence": f"the nip deflection and the band at "
                    f"{centres[k - k0] / INCH:.1f} in leave the same pattern "
                    f"(correlation {corr[k1, k]:+.2f}): the readings cannot tell them apart",
                }
            )
    return out
