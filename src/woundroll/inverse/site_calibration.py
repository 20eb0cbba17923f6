"""Site calibration: the model tied to a mill's own instrument and rolls.

A mill measures rolls whose winding settings it knows (case files) with its own tester
(readings). ``woundroll calibrate READINGS --cases A.toml B.toml ... --fit NAME`` fits the
parameters the user names, those the model cannot know for this site, by least squares on
the individual readings, and says whether the calibrated model predicts rolls it was not
fitted to (leave-one-out).

Parameters that can be fitted (:data:`PARAMETERS`), each positive and searched on its log:

``head_length``
    the head's effective length [m] (``tester.head_length``): the instrument's contact
    length on a roll, which the block does not pin.
``K2_scale``
    a factor on the web's ``K2`` [-] (``web.radial_modulus.K2``, the Pfeiffer law {2}):
    the stack's stiffness in this mill's rolls against the preset's.
``slip_fraction``
    the reduced-shear emulation's shear fraction [-] (``contact.slip = "reduced-shear"``,
    ``contact.slip_shear_fraction``): how much of the interlayer shear survives slip.
``mu``
    the interlayer friction [-] (``contact.friction``) with the slip emulation on.

Statistics (stated assumptions, docs/calibration.md): the readings of one roll share that
roll's own deviation (roll-to-roll variation and what the model misses), so the fit is on the
K roll means, each counted once; their scatter about the fit, ``s^2 = sum (ybar_k -
m_k)^2 / (K - p)``, gives the standard errors ``s^2 (J^T J)^-1`` at the optimum (J: the mean
readings' sensitivity to the log-parameters, by central differences of full model runs).
Leave-one-out: every roll in turn is left out, the parameters refitted on the others, and
the left-out roll's mean predicted; its allowance is three standard deviations of what a
roll mean scatters about a *correct* model, ``sqrt(s_rep^2 / n_k + tau^2 + J_k C J_k^T)``:
the tester's repeatability ``s_rep`` (pooled over repeated readings of a roll; the fit's
``s`` when every roll was read once), the roll-to-roll scatter ``tau`` the user states
(``--roll-scatter``, default 0) and the uncertainty of the refitted parameters. A model that
misses an effect predicts the rolls it did not see worse than that, and the verdict says so.
A parameter the readings cannot identify (its relative standard error beyond
:data:`MAX_RELATIVE_SE`, no reading that moves by more than the scatter across the
parameter's range, or the other rolls unable to pin it when one is left out) is refused with a
"not identifiable" verdict. A parameter that ends on the bound of its range is noted.
"""

from __future__ import annotations

import csv
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from woundroll.errors import ConvergenceError, InputError

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class Parameter:
    """A parameter the site calibration can fit.

    Attributes
    ----------
    name : str         as the user names it (``--fit``).
    unit : str         its unit in outputs ("m" or "-").
    bounds : (float, float)  search bracket (SI).
    describe : str     one line.
    """

    name: str
    unit: str
    bounds: tuple[float, float]
    describe: str

    def base(self, case: Any) -> float:
        """The parameter's value in ``case`` (the starting point of the fit)."""
        if self.name == "head_length":
            h = case.tester_setup.instrument.head_length
            if h is None:
                raise InputError("the instrument's head has no length", "--fit")
            return float(h)
        if self.name == "K2_scale":
            return 1.0
        if self.name == "slip_fraction":
            return float(case.contact.slip_shear_fraction) if case.contact.slip != "none" else 0.1
        return float(case.contact.friction)

    def overrides(self, case: Any, value: float) -> list[str]:
        """The ``--set`` lines that put ``value`` into ``case``."""
        if self.name == "head_length":
            return [f"tester.head_length={value!r} m"]
        if self.name == "K2_scale":
            law = case.web.build().radial_modulus
            k2 = getattr(law, "K2", None)
            if k2 is None:
                raise InputError(
                    f"K2_scale needs a radial-modulus law with K2 (Pfeiffer), not "
                    f"{type(law).__name__}",
                    "--fit",
                )
            return [f"web.radial_modulus.K2={float(k2) * value!r}"]
        if self.name == "slip_fraction":
            return ["contact.slip='reduced-shear'", f"contact.slip_shear_fraction={value!r}"]
        slip = [] if case.contact.slip != "none" else ["contact.slip='reduced-shear'"]
        return [*slip, f"contact.friction={value!r}"]


#: The parameters a site calibration can fit, by name.
PARAMETERS: dict[str, Parameter] = {
    p.name: p
    for p in (
        Parameter("head_length", "m", (2e-3, 0.2), "the head's effective length on a roll"),
        Parameter("K2_scale", "-", (0.05, 20.0), "a factor on the web's K2 (Pfeiffer law {2})"),
        Parameter("slip_fraction", "-", (1e-3, 1.0), "reduced-shear emulation's shear fraction"),
        Parameter("mu", "-", (0.02, 2.0), "interlayer friction with the slip emulation"),
    )
}

#: A fitted parameter whose standard error exceeds this fraction of its value is "not
#: identifiable" from the readings given.
MAX_RELATIVE_SE = 1.0

#: Relative step of the finite-difference sensitivities (on the log-parameter).
FD_STEP = 0.02


def read_calibration_readings(
    path: str | Path, labels: Sequence[str], scale: tuple[float, float] | None
) -> tuple[list[FloatArray], list[str]]:
    """Readings per roll from a CSV with a ``case`` column (the case file's stem, or a bundled
    case's name, as given to ``--cases``) and a ``reading`` column (unit in brackets allowed:
    ``reading [Rho]``). Returns the readings of each label and notes (readings at the
    scale's end, which bound the roll's hardness from one side only, are left out and
    counted).

    Raises
    ------
    InputError
        A missing file or column, a reading that is not a number, beyond the instrument's
        scale (file and line named), a case with no reading, a label not in ``labels``.
    """
    p = Path(path)
    if not p.is_file():
        raise InputError(f"file not found: {p}", "READINGS")
    try:
        text = p.read_text(encoding="utf-8-sig")
    except (OSError, UnicodeDecodeError) as exc:
        raise InputError(f"cannot read {p.name} as UTF-8 text ({exc})", "READINGS") from None
    rows = list(csv.reader(line for line in text.splitlines() if not line.startswith("#")))
    if not rows:
        raise InputError(f"{p.name}: empty", "READINGS")
    header = [h.strip().lower().split("[")[0].strip() for h in rows[0]]
    if "case" not in header or "reading" not in header:
        raise InputError(
            f"{p.name}: needs a header with 'case' and 'reading' columns, got {rows[0]!r}",
            "READINGS",
        )
    ic, ir = header.index("case"), header.index("reading")
    per: dict[str, list[float]] = {k: [] for k in labels}
    dropped = 0
    for n, row in enumerate(rows[1:], start=2):
        if not row or all(not c.strip() for c in row):
            continue
        where = f"{p.name}, line {n}"
        if len(row) <= max(ic, ir):
            raise InputError(f"{where}: too few columns", "READINGS")
        label = row[ic].strip()
        if label not in per:
            raise InputError(
                f"{where}: case {label!r} is not among --cases ({', '.join(labels)})", "READINGS"
            )
        try:
            v = float(row[ir])
        except ValueError:
            raise InputError(f"{where}: reading {row[ir]!r} is not a number", "READINGS") from None
        if not math.isfinite(v):
            raise InputError(f"{where}: reading {row[ir]!r} is not finite", "READINGS")
        if scale is not None and not scale[0] <= v <= scale[1]:
            raise InputError(
                f"{where}: reading {v:g} is outside the instrument's scale "
                f"{scale[0]:g}-{scale[1]:g}",
                "READINGS",
            )
        if scale is not None and v in scale:
            dropped += 1  # saturated: only a bound
            continue
        per[label].append(v)
    notes = []
    if dropped:
        notes.append(
            f"{dropped} reading(s) at the scale's end left out: a saturated reading only bounds "
            "the roll's hardness from one side"
        )
    for k, v in per.items():
        if not v:
            raise InputError(f"{p.name}: no reading of case {k!r} on the scale", "READINGS")
    return [np.asarray(per[k], dtype=float) for k in labels], notes


@dataclass
class _Model:
    """Memoised full runs: reading of roll ``k`` at log-parameters ``x``."""

    sources: list[str]
    cases: list[Any]
    params: list[Parameter]
    progress: Callable[[int], None] | None = None
    cache: dict[tuple[int, tuple[float, ...]], float] = field(default_factory=dict)
    runs: int = 0

    def reading(self, k: int, x: FloatArray) -> float:
        key = (k, tuple(round(float(v), 12) for v in x))
        if key not in self.cache:
            from woundroll.case import load_case
            from woundroll.pipeline import run

            case = self.cases[k]
            sets = [
                s
                for p, v in zip(self.params, x, strict=True)
                for s in p.overrides(case, math.exp(v))
            ]
            h = run(load_case(self.sources[k], sets)).hardness
            self.cache[key] = float(h.reading)
            self.runs += 1
            if self.progress is not None:
                self.progress(self.runs)
        return self.cache[key]

    def means(self, ks: Sequence[int], x: FloatArray) -> FloatArray:
        return np.array([self.reading(k, x) for k in ks])

    def jacobian(self, ks: Sequence[int], x: FloatArray) -> FloatArray:
        """d reading / d log-parameter, central differences of step :data:`FD_STEP`."""
        J = np.empty((len(ks), x.size))
        for j in range(x.size):
            e = np.zeros_like(x)
            e[j] = FD_STEP
            J[:, j] = (self.means(ks, x + e) - self.means(ks, x - e)) / (2 * FD_STEP)
        return J


def _log_bounds(params: Sequence[Parameter]) -> tuple[FloatArray, FloatArray]:
    """The search range of the log-parameters: each parameter's bounds, less one
    finite-difference step, so that the sensitivities are taken inside the bounds (a
    slip fraction of 1.02 is not a case a user could write)."""
    lo = np.log([p.bounds[0] for p in params]) + FD_STEP
    hi = np.log([p.bounds[1] for p in params]) - FD_STEP
    return lo, hi


#: Convergence of the fit: the largest step of a log-parameter (1e-3: 0.1 % of the value,
#: far below any standard error the readings of a mill support).
STEP_TOL = 1e-3


def _gauss_newton(
    model: _Model,
    ks: Sequence[int],
    ybar: FloatArray,
    n: FloatArray,
    x0: FloatArray,
    J: FloatArray | None = None,
) -> tuple[FloatArray, FloatArray]:
    """Log-parameters minimising sum_k n_k (ybar_k - m_k(x))^2 (weights ``n``: ones for the
    roll means counted once), within the parameters' bounds, by Gauss-Newton
    with the sensitivities kept while the steps are small (a chord method: each full-model
    run is expensive). Returns ``(x, J)``, J the last sensitivities of the rolls ``ks``."""
    lo, hi = _log_bounds(model.params)
    x = np.clip(np.asarray(x0, dtype=float), lo, hi)
    if J is None:
        J = model.jacobian(ks, x)
    for _ in range(20):
        r = ybar - model.means(ks, x)
        A = J.T @ (n[:, None] * J)
        if np.linalg.cond(A) > 1e12:
            return x, J  # not identifiable: the caller says so
        step = np.linalg.solve(A, J.T @ (n * r))
        step = np.clip(step, -1.0, 1.0)  # at most a factor e per step
        x_new = np.clip(x + step, lo, hi)
        if np.max(np.abs(x_new - x)) < STEP_TOL:
            return x_new, J
        if np.max(np.abs(x_new - x)) > 0.1:  # far from where J was taken: take it anew
            J = model.jacobian(ks, x_new)
        x = x_new
    raise ConvergenceError("calibrate: the least-squares fit did not converge in 20 steps")


@dataclass(frozen=True)
class SiteCalibration:
    """Result of :func:`calibrate_site`.

    Attributes
    ----------
    params : list of Parameter
    values, standard_errors : ndarray (SI)   fitted values and their standard errors.
    labels : list of str                    the rolls (as named in the readings file).
    measured_mean, n_readings : ndarray     per roll.
    before, fitted : ndarray                model reading per roll before and after.
    scatter_fit : float                     s = sqrt(RSS / (n - p)) of the fit [reading].
    scatter_repeat : float or None          pooled SD of repeated readings on a roll.
    loo_predicted, loo_error, loo_allowed : ndarray   leave-one-out per roll.
    runs : int                              full model runs made.
    notes : list of str
    """

    params: list[Parameter]
    values: FloatArray
    standard_errors: FloatArray
    labels: list[str]
    sources: list[str]
    measured_mean: FloatArray
    n_readings: FloatArray
    before: FloatArray
    fitted: FloatArray
    scatter_fit: float
    scatter_repeat: float | None
    loo_predicted: FloatArray
    loo_error: FloatArray
    loo_allowed: FloatArray
    runs: int
    scale_name: str
    notes: list[str]

    @property
    def predicts(self) -> bool:
        """Every left-out roll predicted within its allowance (3 standard errors of the
        difference between its measured mean and the prediction)."""
        return bool(np.all(np.abs(self.loo_error) <= self.loo_allowed))

    @property
    def verdict(self) -> str:
        rms = float(np.sqrt(np.mean(self.loo_error**2)))
        worst = int(np.argmax(np.abs(self.loo_error) / self.loo_allowed))
        if self.predicts:
            return (
                f"the calibrated model predicts rolls it was not fitted to: leave-one-out RMS "
                f"error {rms:.2f} {self.scale_name}, every roll within its allowance"
            )
        return (
            f"the calibrated model does NOT predict rolls it was not fitted to: leave-one-out "
            f"RMS error {rms:.2f} {self.scale_name}; {self.labels[worst]} is off by "
            f"{self.loo_error[worst]:+.2f} against an allowance of {self.loo_allowed[worst]:.2f} "
            "(the model is mis-specified for these rolls, or another parameter is unknown)"
        )

    def to_dict(self) -> dict[str, Any]:
        return {
            "fitted": {
                p.name: {
                    f"value_{p.unit}" if p.unit != "-" else "value": float(v),
                    f"standard_error_{p.unit}" if p.unit != "-" else "standard_error": float(e),
                    "describe": p.describe,
                }
                for p, v, e in zip(self.params, self.values, self.standard_errors, strict=True)
            },
            "rolls": [
                {
                    "case": lab,
                    "source": src,
                    "n_readings": int(n),
                    "measured_mean": float(m),
                    "model_before": float(b),
                    "model_fitted": float(f),
                    "loo_predicted": float(lp),
                    "loo_error": float(le),
                    "loo_allowed": float(la),
                }
                for lab, src, n, m, b, f, lp, le, la in zip(
                    self.labels,
                    self.sources,
                    self.n_readings,
                    self.measured_mean,
                    self.before,
                    self.fitted,
                    self.loo_predicted,
                    self.loo_error,
                    self.loo_allowed,
                    strict=True,
                )
            ],
            "scale": self.scale_name,
            "scatter_fit": self.scatter_fit,
            "scatter_repeat": self.scatter_repeat,
            "predicts_left_out_rolls": self.predicts,
            "verdict": self.verdict,
            "runs": self.runs,
            "notes": list(self.notes),
        }

    def to_toml(self) -> str:
        """The fitted values as case-file lines (``[tester]``, ``[contact]``, ``K2``), each
        with its standard error and where it came from; paste them into a case or keep the
        file with the instrument."""
        head = [
            "# woundroll calibrate: fitted on "
            f"{len(self.labels)} rolls ({', '.join(self.labels)}), "
            f"{int(self.n_readings.sum())} readings; {self.verdict}",
            "",
        ]
        tables: dict[str, list[str]] = {}
        for p, v, e in zip(self.params, self.values, self.standard_errors, strict=True):
            src = (
                f"# fitted by woundroll calibrate: {v:.5g} +- {e:.2g} ({p.unit}, 1 SE) on "
                f"{', '.join(self.labels)}"
            )
            if p.name == "head_length":
                tables.setdefault("tester", []).append(src)
                tables["tester"].append(f'head_length = "{v * 1e3:.3f} mm"')
            elif p.name == "K2_scale":
                tables.setdefault("calibration", []).append(src)
                tables["calibration"].append(
                    f"K2_scale = {v:.5g}  # multiply web.radial_modulus.K2 by this"
                )
            elif p.name == "slip_fraction":
                tables.setdefault("contact", []).append(src)
                tables["contact"] += ['slip = "reduced-shear"', f"slip_shear_fraction = {v:.5g}"]
            else:
                tables.setdefault("contact", []).append(src)
                tables["contact"].append(f"friction = {v:.5g}")
        body = []
        for name, lines in tables.items():
            body += [f"[{name}]", *lines, ""]
        return "\n".join(head + body)


def calibrate_site(
    readings: str | Path,
    cases: Sequence[str],
    fit: Sequence[str],
    *,
    roll_scatter: float = 0.0,
    progress: Callable[[str, int], None] | None = None,
) -> SiteCalibration:
    """Fit the parameters named in ``fit`` (keys of :data:`PARAMETERS`) to the readings of
    rolls of known winding settings (``cases``: case files or bundled names, all with a
    ``[tester]`` read through the contact model), and leave each roll out in turn.
    ``roll_scatter``: the SD of the mean reading between rolls wound alike [reading units]
    (0: the rolls differ only by the tester's repeatability), used by the leave-one-out test.

    Raises
    ------
    InputError
        Bad files, readings off the scale, an unknown parameter, rolls that are all the same,
        too few rolls or readings for the parameters, a parameter the readings cannot
        identify (message "not identifiable"). ConvergenceError: the fit did not converge.
    """
    from woundroll.io.readings import SCALES

    names = _parameter_names(fit)
    if len(cases) < 2:
        raise InputError("give at least two rolls (case files)", "--cases")
    srcs, loaded, labels = _load_rolls(cases, names)
    scale = loaded[0].tester_setup.instrument.reading_range
    readout = loaded[0].tester_setup.instrument.readout
    scale_name = {readout: name for name, readout in SCALES.items()}[readout]
    ys, notes = read_calibration_readings(readings, labels, scale)
    params = [PARAMETERS[nm] for nm in names]
    n_k = np.array([y.size for y in ys], dtype=float)
    ybar = np.array([y.mean() for y in ys])
    K = len(labels)
    _check_counts(K, len(params), roll_scatter)

    def tick(stage: str) -> Callable[[int], None] | None:
        return None if progress is None else (lambda runs: progress(stage, runs))

    model = _Model(srcs, loaded, params, tick("fit"))
    x0 = np.log([pm.base(loaded[0]) for pm in params])
    notes += _slip_notes(params, loaded[0])
    ks = list(range(K))
    before = model.means(ks, x0)
    # each roll counts once: its readings share the roll's own deviation (roll-to-roll
    # variation, what the model misses), so the information is in the K roll means
    x, _ = _gauss_newton(model, ks, ybar, np.ones(K), x0)
    fitted = model.means(ks, x)
    J = model.jacobian(ks, x)  # central differences at the optimum, for the errors
    s2, s_rep, se_log = _fit_errors(
        J, ybar - fitted, ys, n_k, params, names, x, roll_scatter, scale_name, notes
    )
    rep = s_rep if s_rep is not None else math.sqrt(s2) if s2 > 0 else 0.0
    # what a roll mean scatters about a correct model: repeatability / n_k plus the
    # roll-to-roll scatter the user states (--roll-scatter; 0: the rolls alike but for it)
    var_k = rep**2 / n_k + roll_scatter**2
    model.progress = tick("leave-one-out")
    loo_pred, loo_allow = _leave_one_out(model, J, x, ybar, var_k, labels, names)
    values = np.exp(x)
    return SiteCalibration(
        params=params,
        values=values,
        standard_errors=values * se_log,
        labels=labels,
        sources=srcs,
        measured_mean=ybar,
        n_readings=n_k,
        before=before,
        fitted=fitted,
        scatter_fit=math.sqrt(s2),
        scatter_repeat=s_rep,
        loo_predicted=loo_pred,
        loo_error=loo_pred - ybar,
        loo_allowed=loo_allow,
        runs=model.runs,
        scale_name=scale_name,
        notes=notes,
    )


def _check_counts(K: int, p: int, roll_scatter: float) -> None:
    """At least one roll more than parameters; a roll scatter >= 0."""
    if K < p + 1:
        raise InputError(f"{p} parameter(s) need at least {p + 1} rolls; got {K}", "--cases")
    if roll_scatter < 0 or not math.isfinite(roll_scatter):
        raise InputError(f"must be a reading SD >= 0, got {roll_scatter!r}", "--roll-scatter")


def _slip_notes(params: list[Parameter], case: Any) -> list[str]:
    """Fitting a slip parameter switches the slip emulation on: say so."""
    return [
        f"fitting {pm.name} switches the slip emulation on "
        "(contact.slip = 'reduced-shear'): 'model before' is read with it"
        for pm in params
        if pm.name in ("slip_fraction", "mu") and case.contact.slip == "none"
    ]


def _parameter_names(fit: Sequence[str]) -> list[str]:
    """The parameters to fit, once each, all known."""
    names = list(dict.fromkeys(fit))
    if not names:
        raise InputError("name at least one parameter to fit", "--fit")
    for nm in names:
        if nm not in PARAMETERS:
            raise InputError(f"unknown parameter {nm!r}: one of {', '.join(PARAMETERS)}", "--fit")
    return names


def _load_rolls(cases: Sequence[str], names: list[str]) -> tuple[list[str], list[Any], list[str]]:
    """The rolls' sources, cases and labels: single rolls, read through the contact model,
    not all alike, with one instrument (and one head when its length is fitted)."""
    from woundroll.case import load_case

    srcs = [str(c) for c in cases]
    loaded = [load_case(c) for c in srcs]
    labels = [Path(s).stem if s.endswith(".toml") else s for s in srcs]
    if len(set(labels)) != len(labels):
        raise InputError("two --cases have the same name", "--cases")
    for lab, c in zip(labels, loaded, strict=True):
        if c.tester is None or "roll_spring" in c.tester:
            raise InputError(
                f"case {lab!r} needs a [tester] read through the contact model", "--cases"
            )
        if c.winding.thickness_profile is not None:
            raise InputError(f"case {lab!r} is a CMD profile: give single rolls", "--cases")
    dumps = [c.model_dump(mode="json", exclude={"title"}) for c in loaded]
    if all(d == dumps[0] for d in dumps[1:]):
        raise InputError(
            "all the rolls have the same settings: the readings cannot tell a parameter from "
            "the scatter; calibrate on rolls wound differently",
            "--cases",
        )
    inst = loaded[0].tester_setup.instrument
    for lab, c in zip(labels[1:], loaded[1:], strict=True):
        other = c.tester_setup.instrument
        if (other.name, other.readout) != (inst.name, inst.readout):
            raise InputError(
                f"case {lab!r} is read with {other.name!r}, {labels[0]!r} with {inst.name!r}: "
                "calibrate one instrument at a time",
                "--cases",
            )
        if "head_length" in names and other.head_length != inst.head_length:
            raise InputError(
                f"case {lab!r} gives another head length than {labels[0]!r}: the fit of "
                "head_length needs one head",
                "--cases",
            )
    return srcs, loaded, labels


def _fit_errors(
    J: FloatArray,
    resid: FloatArray,
    ys: list[FloatArray],
    n_k: FloatArray,
    params: list[Parameter],
    names: list[str],
    x: FloatArray,
    roll_scatter: float,
    scale_name: str,
    notes: list[str],
) -> tuple[float, float | None, FloatArray]:
    """The fit's residual variance s2, the repeatability (None: one reading per roll) and
    the standard errors of the log parameters; a parameter the readings cannot identify
    raises, one on the bound of its range gets a note."""
    K, p = J.shape
    dof = K - p
    s2 = float(resid @ resid) / dof if dof > 0 else math.nan
    JtJ = J.T @ J
    if np.linalg.cond(JtJ) > 1e12:
        raise InputError(
            f"not identifiable: the readings do not change with "
            f"{' and '.join(names)} (or not independently); choose other parameters or rolls",
            "--fit",
        )
    within = [np.sum((y - y.mean()) ** 2) for y in ys]
    dof_rep = float(np.sum(n_k - 1))
    s_rep = math.sqrt(float(np.sum(within)) / dof_rep) if dof_rep > 0 else None
    if not math.isfinite(s2):  # as many rolls as parameters + 1 would leave no freedom
        s2 = (s_rep or 0.0) ** 2 / float(np.mean(n_k)) + roll_scatter**2
        notes.append(
            "no degree of freedom about the fit: the standard errors use the repeatability"
        )
    cov = s2 * np.linalg.inv(JtJ)
    se_log = np.sqrt(np.diag(cov))
    lo_b, hi_b = _log_bounds(params)
    moves = np.max(np.abs(J), axis=0) * (hi_b - lo_b)
    spread = math.sqrt(s2) if s2 > 0 else 0.0
    for pm, se, mv in zip(params, se_log, moves, strict=True):
        if se > MAX_RELATIVE_SE or mv <= spread:
            raise InputError(
                f"not identifiable: {pm.name} is fitted with a relative standard error of "
                f"{100 * se:.0f} % (the readings move by at most {mv:.2g} {scale_name} over its "
                f"range, the scatter is {spread:.2g}); choose rolls that differ in it",
                "--fit",
            )
    for pm, v, lo, hi in zip(params, x, lo_b, hi_b, strict=True):
        if v <= lo + 1e-6 or v >= hi - 1e-6:
            notes.append(
                f"{pm.name} ended on the bound of its range ({math.exp(v):.4g}): the readings "
                "ask for more than the parameter can give; the model may lack another effect"
            )
    if s_rep is None:
        notes.append("one reading per roll: the repeatability is taken from the fit's residuals")
    return s2, s_rep, se_log


def _leave_one_out(
    model: _Model,
    J: FloatArray,
    x: FloatArray,
    ybar: FloatArray,
    var_k: FloatArray,
    labels: list[str],
    names: list[str],
) -> tuple[FloatArray, FloatArray]:
    """Refit on the other rolls, predict the left-out roll's mean; the allowed error is 3
    SDs of the prediction under a correct model (the roll's scatter and the refit's)."""
    K = ybar.size
    ks = list(range(K))
    loo_pred = np.empty(K)
    loo_allow = np.empty(K)
    for k in ks:
        rest = [j for j in ks if j != k]
        A = J[rest].T @ J[rest]
        if np.linalg.cond(A) > 1e12:
            raise InputError(
                f"not identifiable without roll {labels[k]!r}: the other rolls cannot pin "
                f"{' and '.join(names)}; calibrate on more rolls that differ in it",
                "--cases",
            )
        xk, _ = _gauss_newton(model, rest, ybar[rest], np.ones(len(rest)), x, J[rest])
        loo_pred[k] = model.reading(k, xk)
        # the prediction's variance under a correct model, from the full fit's sensitivities
        W = 1.0 / np.maximum(var_k[rest], 1e-300)
        Ck = np.linalg.inv(J[rest].T @ (W[:, None] * J[rest]))
        var_pred = float(J[k] @ Ck @ J[k])
        loo_allow[k] = 3.0 * math.sqrt(var_k[k] + var_pred)
    return loo_pred, loo_allow


__all__ = [
    "PARAMETERS",
    "Parameter",
    "SiteCalibration",
    "calibrate_site",
    "read_calibration_readings",
]
