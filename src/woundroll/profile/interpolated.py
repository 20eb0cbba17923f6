"""The contact stage of a profile on a few sectors: solved there, interpolated between, checked.

The sectors of a CMD profile differ mainly by their wound-in pressure profile under the
striker, and the roll spring {3} of a sector is a smooth function of it. So instead of one
2D contact solve per sector (:func:`woundroll.profile.hardness.map_sectors`, the exact path,
``profile.contact = "every-sector"``), the ``"interpolated"`` path

1. describes each sector by its interlayer pressure: ``v_k = ln p(d_k)`` at depths ``d_k``
   below the sector's surface over the outer three quarters of its pile
   (:data:`DESCRIPTOR_DEPTHS`), and one parameter ``x`` = the mean of ``v_k`` (the log of
   the geometric-mean pressure there);
2. groups the sectors by their contact callable (slack sectors, whose striker starts at the
   model's reach, form a group of their own and are never interpolated from taut ones);
3. solves the contact fully on the group's extremes and quartiles in ``x`` (the nodes);
   a group of sectors with one descriptor (a uniform web) is solved once and copied, so its
   profile is exactly flat;
4. interpolates ``alpha`` and ``beta`` linearly in ``x`` between the nodes (linear in
   (alpha, beta) is linear in the whole curve ``F(d) = alpha d^2 + beta d``), and so the
   semi-contact width ``a`` the contact model gives beside them (the FD reading's active
   mass {14}-{18}), with the same nodes and descriptor, so that the checks below judge the
   reading of the interpolated spring *and* width; the other active-mass input (each
   sector's pile height) is the sector's own, not interpolated;
5. **checks**: an error estimate per interpolated sector (the larger of the interpolation's
   curvature term ``0.5 |R''| (x - x_a)(x_b - x)`` from the node readings and the
   difference between the reading of the interpolated spring and the reading interpolated
   between the nodes', plus the mismatch of its pressure profile against the interpolated
   one times the local slope ``|dR/dx|``), scaled up by the largest ratio of a checked
   sector's change to its estimate so far; the
   sectors with the largest estimates solved fully (``workers`` at a time, distinct
   intervals first), each then a node. This repeats until, in one round, no checked
   sector's reading changed by more than ``tolerance`` (reading units, default 0.2) from its
   interpolated value. A sector whose interpolated reading lies beyond the scale by more
   than its estimate shows the scale's end whatever the error: it is not checked (its
   model value beyond the scale is interpolated; ``solved`` tells which sectors were).

**Anchored on a cheaper model** (``"anchored"``, for an expensive roll model such as
``contact.model = "3d"``): the cheap model (plane strain, ``"2d"``) is solved on every
sector, the expensive one on the nodes and checks above; what is interpolated in ``x`` is
the expensive model's spring *relative to the cheap one's* (``alpha / alpha_2d``, ``beta /
beta_2d``; a cheap coefficient of 0 divided as :data:`ANCHOR_FLOOR` of its median), and
the error estimates and checks act on the reading's correction (expensive minus cheap
reading), which varies far more slowly across the sectors than the reading itself: the
cheap model carries each sector's own pressure profile, the interpolation only the
3D-to-plane-strain correction. Assumption
(named): the correction depends on the sector only through ``x`` between nodes (checked
like the plain interpolation; measured against 3D on every sector in docs/profile.md).

Assumptions (named): the spring depends on the sector's pressure profile only through
``x`` between neighbouring nodes (the mismatch term of the estimate flags a sector where
it does not); the check's largest estimate finds the largest error (verified against the
exact path on all four bundled ``pet3-*`` cases, docs/profile.md section 7).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from woundroll.errors import InputError

FloatArray = NDArray[np.float64]
ContactFn = Callable[[FloatArray, FloatArray], tuple[float, ...]]
#: ``readings(alpha, beta, width, sectors) -> reading`` of the given sectors (their own pile
#: heights; ``width`` their semi-contact widths [m], NaN where the contact gives none)
ReadingFn = Callable[[FloatArray, FloatArray, FloatArray, NDArray[np.intp]], FloatArray]
#: ``solve(fns, profiles) -> (alpha, beta)`` or ``(alpha, beta, width)``: full contact
#: solves (map_sectors on the pool), in the order given
SolveFn = Callable[
    [Sequence[ContactFn], Sequence[tuple[FloatArray, FloatArray]]], tuple[FloatArray, ...]
]

#: The contact stage of a profile: ``"every-sector"`` (one full contact solve per sector,
#: exact), ``"interpolated"`` (solved on a few sectors, checked) or ``"anchored"`` (the
#: plane-strain model on every sector, the case's roll model on a few, its correction
#: interpolated and checked; for an expensive model such as 3D). The one default of every
#: entry point (``[profile] contact`` of a case, :func:`predict_profile`): every sector,
#: because on the bundled Table 3 cases the check still solves 46-61 of the 61 sectors in
#: 10-13 rounds, and the rounds cost more wall time than the skipped solves save
#: (docs/profile.md section 7).
CONTACT_STAGES = ("every-sector", "interpolated", "anchored")
DEFAULT_CONTACT_STAGE = "every-sector"
#: Largest change of a checked sector's reading the interpolation may make (the
#: instrument's reading units: 0.2 Rho, below the 1-Rho display resolution of a Rho-meter
#: and the FD model's own time-step error, docs/instruments.md).
DEFAULT_TOLERANCE = 0.2
#: Depths of the pressure descriptor, as fractions of the sector's pile height H: the outer
#: three quarters of the pile. The 2D contact model is the whole ring in plane strain and
#: its spring depends on the pressure deep below the striker (on ``pet3-2.3MPa`` two
#: sectors with equal pressure over the outer 8 mm but 36 / 27 kPa at 16 mm read 71 and 58
#: Rho); ordered by the geometric-mean pressure over 0.75 H the readings of Table 3 are as
#: smooth (sum of |second differences| 77 Rho) as ordered by alpha itself (77), against
#: 160-250 for any depth window of 1-48 mm and 109 for the whole pile (measured,
#: docs/profile.md section 7).
DESCRIPTOR_DEPTHS = np.linspace(0.75 / 24, 0.75, 24)
#: Pressure floor of the descriptor's logarithm, relative to the largest pressure of the
#: profile over all sectors' descriptor depths (a slack surface reads as this floor).
PRESSURE_FLOOR = 1e-6
#: Nodes of a group before the first check: its extremes and quantiles in ``x`` (solved in
#: one parallel batch).
FIRST_NODES = 5
#: Spread of ``x`` (ln units: a relative spread of the pressure) below which a group's
#: sectors count as one roll: one solve, copied (a uniform web's sectors agree to 1e-7,
#: docs/profile.md section 6; a 1e-6 pressure change moves a reading by ~1e-6 of it).
SAME_DESCRIPTOR = 1e-6
#: Anchored stage: a cheap spring coefficient of 0 is divided as this fraction of the
#: coefficient's median over the sectors (a ratio needs a denominator; the spring made
#: from it stays >= 0, and the check judges its reading like any other).
ANCHOR_FLOOR = 1e-3


@dataclass(frozen=True)
class InterpolatedContact:
    """The outcome of :func:`interpolated_springs`.

    Attributes
    ----------
    alpha, beta : ndarray   roll spring {3} per sector [N/m^2], [N/m].
    width : ndarray         semi-contact width a per sector [m] (the solved sectors' own,
                            interpolated like alpha and beta elsewhere; NaN where the
                            contact callable gives none).
    solved : ndarray[bool]  sectors whose contact was solved fully (nodes and checks).
    x : ndarray             the interpolation parameter per sector (ln of the geometric-mean
                            pressure over the reach, ln Pa).
    rounds : int            check rounds.
    largest_check : float   largest reading change found by the last check round
                            (reading units; 0 when every sector was solved).
    largest_change : float  largest reading change found by any check.
    """

    alpha: FloatArray
    beta: FloatArray
    width: FloatArray
    solved: NDArray[np.bool_]
    x: FloatArray
    rounds: int
    largest_check: float
    largest_change: float


def check_stage(stage: object, tolerance: object) -> tuple[str, float]:
    """The contact stage and its tolerance, checked (one-line errors naming the field)."""
    if stage not in CONTACT_STAGES:
        raise InputError(
            f"must be one of {', '.join(CONTACT_STAGES)}, got {stage!r}", "profile.contact"
        )
    if (
        isinstance(tolerance, bool)
        or not isinstance(tolerance, int | float)
        or not (math.isfinite(tolerance) and tolerance >= 0)
    ):
        raise InputError(
            f"must be a reading change >= 0, got {tolerance!r}", "profile.contact_tolerance"
        )
    return str(stage), float(tolerance)


def descriptors(profiles: Sequence[tuple[FloatArray, FloatArray]]) -> FloatArray:
    """``ln p`` at :data:`DESCRIPTOR_DEPTHS` x the pile height below each sector's surface
    (the last radius of its profile; the pile height is the last minus the first), one row
    per sector; ``p = -sigma_r`` linear in r between the profile's points, floored at
    :data:`PRESSURE_FLOOR` of the largest."""
    rows = []
    for r, s in profiles:
        r, s = np.asarray(r, dtype=float), np.asarray(s, dtype=float)
        d = DESCRIPTOR_DEPTHS * (r[-1] - r[0])
        rows.append(-np.interp(r[-1] - d, r, s))
    p = np.asarray(rows)
    floor = PRESSURE_FLOOR * max(float(p.max()), 1e-300)
    return np.log(np.maximum(p, floor))


def _interpolate(
    x: FloatArray, nodes: list[int], coefs: Sequence[FloatArray], members: NDArray[np.intp]
) -> None:
    """alpha, beta and the width (or, anchored, their relations to the cheap model's) of
    the group's ``members`` linear in x between its ``nodes`` (in place; nodes at one x
    averaged; a NaN width stays NaN)."""
    xn = x[nodes]
    order = np.argsort(xn, kind="stable")
    xs, idx = np.unique(xn[order], return_inverse=True)
    rest = np.setdiff1d(members, nodes)
    if rest.size:
        # linear in (alpha, beta) is linear in the whole curve F(d); (measured: linear in
        # ln(alpha + c) instead solves all 61 sectors of pet3-3.45MPa, against 49)
        for c in coefs:
            cn = np.bincount(idx, c[nodes][order]) / np.bincount(idx)
            c[rest] = np.interp(x[rest], xs, cn)


def _estimates(
    x: FloatArray, v: FloatArray, nodes: list[int], reading: FloatArray, members: NDArray[np.intp]
) -> dict[int, tuple[float, int, float]]:
    """Error estimate of each interpolated member: ``(estimate, interval index, reading
    interpolated linearly between the nodes' readings)``."""
    nd = sorted(set(nodes), key=lambda j: x[j])
    xs = x[nd]
    rs = reading[nd]
    slopes = np.zeros(max(len(nd) - 1, 0))
    for i in range(len(nd) - 1):
        dx = xs[i + 1] - xs[i]
        slopes[i] = (rs[i + 1] - rs[i]) / dx if dx > 0 else 0.0
    out: dict[int, tuple[float, int, float]] = {}
    for j in np.setdiff1d(members, nd):
        i = int(np.clip(np.searchsorted(xs, x[j]) - 1, 0, len(nd) - 2))
        xa, xb = xs[i], xs[i + 1]
        dx = xb - xa
        w = 0.0 if dx <= 0 else float(np.clip((x[j] - xa) / dx, 0.0, 1.0))
        # curvature from the neighbouring intervals' slopes (second divided differences)
        curv = []
        if i > 0:
            curv.append(2 * abs(slopes[i] - slopes[i - 1]) / max(xb - xs[i - 1], 1e-300))
        if i + 2 < len(nd):
            curv.append(2 * abs(slopes[i + 1] - slopes[i]) / max(xs[i + 2] - xa, 1e-300))
        if curv:
            e_curv = 0.5 * max(curv) * (x[j] - xa) * (xb - x[j])
        else:  # one interval: no curvature known, a quarter of its reading span
            e_curv = 0.25 * abs(rs[i + 1] - rs[i]) * 4 * w * (1 - w)
        # the sector's pressure profile against the one interpolated between the nodes
        mismatch = float(np.max(np.abs(v[j] - ((1 - w) * v[nd[i]] + w * v[nd[i + 1]]))))
        lin = (1 - w) * rs[i] + w * rs[i + 1]
        out[int(j)] = (e_curv + abs(slopes[i]) * mismatch, i, lin)
    return out


def _groups(fns: Sequence[ContactFn]) -> dict[int, list[int]]:
    """The sectors by contact callable: sectors with equal callables (same web and head)
    form a group, interpolated among themselves."""
    groups: dict[int, list[int]] = {}
    keys: list[ContactFn] = []
    for j, f in enumerate(fns):
        for k, g in enumerate(keys):
            if g is f or g == f:
                groups[k].append(j)
                break
        else:
            keys.append(f)
            groups[len(keys) - 1] = [j]
    return groups


def _first_nodes(
    x: FloatArray, members: dict[int, NDArray[np.intp]]
) -> tuple[list[int], dict[int, int]]:
    """The sectors solved first: the extremes and quartiles of each group's descriptor, one
    sector for a group whose descriptors are all the same (its ``copies`` entry: the group
    takes that sector's spring)."""
    first: list[int] = []
    copies: dict[int, int] = {}
    for k, m in members.items():
        xm = x[m]
        if float(np.ptp(xm)) <= SAME_DESCRIPTOR:
            first.append(int(m[0]))
            copies[k] = int(m[0])
            continue
        order = m[np.argsort(xm, kind="stable")]
        q = np.round(np.linspace(0, len(order) - 1, FIRST_NODES)).astype(int)
        first += sorted({int(order[i]) for i in q})
    return first, copies


def _candidates(
    x: FloatArray,
    x_all: FloatArray,
    live: dict[int, NDArray[np.intp]],
    solved: NDArray[np.bool_],
    reading: FloatArray,
    cached: Callable[[NDArray[np.intp]], FloatArray],
    calibration: float,
    scale: tuple[float, float] | None,
    offset: FloatArray,
) -> list[tuple[float, int, int, int]]:
    """(error estimate, group, interval, sector) of every interpolated sector whose shown
    reading the error could change, largest first. The estimates act on ``reading -
    offset`` (anchored: the correction to the cheap model's reading; else offset 0)."""
    cand: list[tuple[float, int, int, int]] = []
    for k, m in live.items():
        nodes = [int(j) for j in m if solved[j]]
        est = _estimates(x, x_all, nodes, reading - offset, m)
        if not est:
            continue
        js = np.asarray(list(est), dtype=np.intp)
        for j, r in zip(js, cached(js), strict=True):
            e, i, lin = est[int(j)]
            # the springs interpolated against the readings interpolated: two
            # approximations of one order whose difference is of the order of the error
            e = max(e, abs(r - offset[j] - lin))
            ce = calibration * e
            if scale is not None and (r - ce > scale[1] or r + ce < scale[0]):
                continue  # shows the scale's end whatever the error
            cand.append((e, k, i, int(j)))
    cand.sort(reverse=True)
    return cand


def _pick(cand: list[tuple[float, int, int, int]], batch: int) -> list[int]:
    """The ``batch`` sectors to check: the largest estimates, one per interval first."""
    pick: list[int] = []
    seen: set[tuple[int, int]] = set()
    for _e, k, i, j in cand:  # distinct intervals first
        if (k, i) not in seen and len(pick) < batch:
            pick.append(j)
            seen.add((k, i))
    for *_, j in cand:
        if len(pick) >= batch:
            break
        if j not in pick:
            pick.append(j)
    return pick


@dataclass
class _Anchor:
    """The anchored stage's bookkeeping: the cheap model's springs ``base`` (and widths)
    and the relation of each solved sector's coefficient to them, a ratio (``alpha /
    alpha_base``, ``a / a_base``). A cheap spring coefficient fitted to 0 (the fit keeps
    alpha, beta >= 0) is divided as :data:`ANCHOR_FLOOR` of the coefficient's median
    instead, so every ratio is finite and >= 0 and so is every spring made from one. A
    coefficient without a base (no base at all: the plain interpolation; the width when
    the cheap model gives none) is interpolated as itself (``denominators`` entry None)."""

    denominators: tuple[FloatArray | None, ...]
    rel: tuple[FloatArray, ...]

    @classmethod
    def of(cls, base: Sequence[FloatArray] | None, n: int) -> _Anchor:
        rel = (np.zeros(n), np.zeros(n), np.zeros(n))
        if base is None:
            return cls((None, None, None), rel)
        b = [np.asarray(c, dtype=float).reshape(-1) for c in base]
        if len(b) not in (2, 3) or any(
            c.shape != (n,) or not np.all(np.isfinite(c)) or np.any(c < 0) for c in b[:2]
        ):
            raise InputError(
                "the anchored stage needs one finite cheap spring >= 0 per sector",
                "profile.contact",
            )
        den: list[FloatArray | None] = []
        for c in b[:2]:
            pos = c[c > 0]
            floor = ANCHOR_FLOOR * float(np.median(pos)) if pos.size else 1.0
            den.append(np.maximum(c, floor))
        width = b[2] if len(b) > 2 else None
        ok = width is not None and width.shape == (n,) and bool(np.all(width > 0))
        den.append(width if ok else None)  # (NaN > 0 is False: no width, plain)
        return cls(tuple(den), rel)

    def relate(self, coefs: Sequence[FloatArray], sel: NDArray[np.intp]) -> None:
        """Record the solved sectors' relation to the base."""
        for c, full, rel in zip(self.denominators, coefs, self.rel, strict=True):
            if c is not None:
                rel[sel] = full[sel] / c[sel]

    def interpolated(self, coefs: Sequence[FloatArray]) -> list[FloatArray]:
        """The arrays interpolated in x: the relations (anchored) or the coefficients."""
        return [
            full if c is None else rel
            for c, full, rel in zip(self.denominators, coefs, self.rel, strict=True)
        ]

    def apply(self, coefs: Sequence[FloatArray], rest: NDArray[np.intp]) -> None:
        """The interpolated sectors' coefficients from their interpolated relations."""
        if rest.size:
            for c, full, rel in zip(self.denominators, coefs, self.rel, strict=True):
                if c is not None:
                    full[rest] = c[rest] * rel[rest]


def interpolated_springs(
    fns: Sequence[ContactFn],
    profiles: Sequence[tuple[FloatArray, FloatArray]],
    solve: SolveFn,
    readings: ReadingFn,
    *,
    tolerance: float = DEFAULT_TOLERANCE,
    batch: int = 2,
    scale: tuple[float, float] | None = None,
    progress: Callable[[int, int], None] | None = None,
    base: Sequence[FloatArray] | None = None,
) -> InterpolatedContact:
    """The roll spring (and semi-contact width) of every sector from full contact solves on
    a few (module docstring).

    Parameters
    ----------
    fns : one contact callable per sector (sectors with equal callables form a group).
    profiles : ``(radius, sigma_r)`` per sector (core to surface).
    solve : the full contact solves of some sectors (``map_sectors`` on the pool):
        ``(alpha, beta)`` or ``(alpha, beta, width)``.
    readings : the reading of some sectors from their springs and widths (their own pile
        heights).
    tolerance : float
        Largest reading change a check round may find before the interpolation is accepted.
    batch : int
        Sectors checked per round (the workers: one round costs one solve per worker).
    scale : (lo, hi), optional
        The instrument's scale: a sector interpolated beyond it by more than its estimate
        is not checked (it shows the scale's end).
    base : (alpha, beta) or (alpha, beta, width) per sector, optional
        Anchored (module docstring): a cheaper model's springs (and widths) on every
        sector; what is interpolated is the full solves' spring and width relative to
        these.
    """
    run = _Interpolation(fns, profiles, solve, readings, progress, base)
    first, copies = _first_nodes(run.x, run.members)
    run.full(first)
    for k, j0 in copies.items():
        for c in run.coefs:
            c[run.members[k]] = c[j0]
    run.live = {k: m for k, m in run.members.items() if k not in copies}
    while True:
        run.interpolate()
        cand = _candidates(
            run.x,
            run.x_all,
            run.live,
            run.solved,
            run.reading,
            run.cached,
            run.calibration,
            scale,
            run.offset,
        )
        if not cand or run.check(cand, batch, tolerance, scale):
            break
    run.interpolate()
    return InterpolatedContact(
        alpha=run.alpha,
        beta=run.beta,
        width=run.width,
        solved=run.solved,
        x=run.x,
        rounds=run.rounds,
        largest_check=run.largest_check,
        largest_change=run.largest_change,
    )


class _Interpolation:
    """The state of :func:`interpolated_springs`: the springs so far, which sectors are
    solved, their readings, and the check rounds' record."""

    def __init__(
        self,
        fns: Sequence[ContactFn],
        profiles: Sequence[tuple[FloatArray, FloatArray]],
        solve: SolveFn,
        readings: ReadingFn,
        progress: Callable[[int, int], None] | None,
        base: Sequence[FloatArray] | None,
    ) -> None:
        n = len(profiles)
        self.fns, self.profiles, self.solve_fn, self.readings = fns, profiles, solve, readings
        self.progress, self.n = progress, n
        self.x_all = descriptors(profiles)
        self.x = self.x_all.mean(axis=1)
        self.alpha, self.beta = np.zeros(n), np.zeros(n)
        self.width = np.full(n, np.nan)  # the semi-contact width a [m] (NaN: none given)
        self.coefs = (self.alpha, self.beta, self.width)
        self.solved = np.zeros(n, dtype=bool)
        self.reading = np.full(n, np.nan)  # readings of solved sectors
        # the nodes: extremes and median of each group (one sector for one descriptor)
        self.members = {k: np.asarray(g, dtype=np.intp) for k, g in _groups(fns).items()}
        self.live: dict[int, NDArray[np.intp]] = {}
        self.anchor = _Anchor.of(base, n)
        # anchored: the cheap springs' readings (what the checks correct)
        self.offset = np.zeros(n)
        if base is not None:
            a0, b0, *w0 = (np.asarray(c, dtype=float) for c in base)
            self.offset = readings(a0, b0, w0[0] if w0 else np.full(n, np.nan), np.arange(n))
        self.rounds, self.largest_check, self.largest_change = 0, 0.0, 0.0
        self.calibration = 1.0
        self.memo: dict[int, tuple[tuple[float, float, float], float]] = {}

    def full(self, idx: list[int]) -> None:
        """Full contact solves of the sectors ``idx`` not solved yet."""
        idx = [j for j in idx if not self.solved[j]]
        if not idx:
            return
        out = self.solve_fn([self.fns[j] for j in idx], [self.profiles[j] for j in idx])
        sel = np.asarray(idx, dtype=np.intp)
        self.alpha[sel], self.beta[sel] = out[0], out[1]
        self.width[sel] = out[2] if len(out) > 2 else np.nan
        self.anchor.relate(self.coefs, sel)
        self.solved[sel] = True
        self.reading[sel] = self.readings(self.alpha[sel], self.beta[sel], self.width[sel], sel)
        if self.progress is not None:
            self.progress(int(self.solved.sum()), self.n)

    def cached(self, js: NDArray[np.intp]) -> FloatArray:
        """Readings of interpolated springs and widths (the FD reading is 2 ms a sector: a
        sector whose interval did not change is not read again)."""
        memo = self.memo

        def key(j: int) -> tuple[float, float, float]:
            return float(self.alpha[j]), float(self.beta[j]), float(self.width[j])

        def same(j: int) -> bool:
            if j not in memo:
                return False
            return bool(np.array_equal(memo[j][0], key(j), equal_nan=True))

        new = [int(j) for j in js if not same(int(j))]
        if new:
            sel = np.asarray(new, dtype=np.intp)
            got = self.readings(self.alpha[sel], self.beta[sel], self.width[sel], sel)
            for j, r in zip(new, got, strict=True):
                memo[j] = (key(j), float(r))
        return np.array([memo[int(j)][1] for j in js])

    def interpolate(self) -> None:
        for m in self.live.values():
            nodes = [int(j) for j in m if self.solved[j]]
            _interpolate(self.x, nodes, self.anchor.interpolated(self.coefs), m)
            self.anchor.apply(self.coefs, np.setdiff1d(m, nodes))

    def check(
        self,
        cand: list[tuple[float, float, float, int]],
        batch: int,
        tolerance: float,
        scale: tuple[float, float] | None,
    ) -> bool:
        """One check round: solve the ``batch`` most doubtful candidates, compare with
        their interpolated readings; True when the interpolation is accepted."""
        pick = _pick(cand, batch)
        sel = np.asarray(pick, dtype=np.intp)
        estimate = {j: e for e, _, _, j in cand}
        before = self.cached(sel)
        self.full(pick)
        change = np.abs(self.reading[sel] - before)
        if scale is not None:  # what the instrument shows
            change = np.abs(np.clip(self.reading[sel], *scale) - np.clip(before, *scale))
        self.rounds += 1
        self.largest_check = float(change.max())
        self.largest_change = max(self.largest_change, self.largest_check)
        # the estimates, calibrated by the checks so far (never below their face value)
        for j, c in zip(pick, change, strict=True):
            self.calibration = max(self.calibration, float(c) / max(estimate[j], 1e-12))
        rest = [e for e, _, _, j in cand if j not in pick]
        return self.largest_check <= tolerance and (
            not rest or self.calibration * max(rest) <= tolerance
        )


__all__ = [
    "CONTACT_STAGES",
    "DEFAULT_CONTACT_STAGE",
    "DEFAULT_TOLERANCE",
    "InterpolatedContact",
    "check_stage",
    "descriptors",
    "interpolated_springs",
]
