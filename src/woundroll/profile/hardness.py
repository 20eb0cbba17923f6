"""The integrated model: CMD thickness profile -> stresses over (r, z) -> Rho across the roll.

Following the last section of the reference paper ("Integrated wound roll model with
hardness simulation"):

1. the axisymmetric winding model (:func:`woundroll.winding.axisymmetric.wind_axisymmetric`)
   gives sigma_r(r) in every CMD sector, with the web tension allocated across the CMD by
   the relaxation-radius rule (and, with a nip, the nip-induced tension by the local nip
   load from :mod:`woundroll.profile.nip`);
2. each sector is taken as a plane-strain roll and a contact callable turns its radial
   stress profile into the roll spring ``F = alpha d^2 + beta d`` {3} (default:
   :func:`woundroll.contact.indent` with the instrument's head);
3. the reading of each sector: with an instrument (default), the instrument's own reading
   by the FD model {4}-{13} (the Rho-meter's accelerometer peak, the headline of every
   woundroll result), with the energy model {19}-{22} beside it as a check; or any readout
   callable ``(alpha, beta) -> reading``. A reading beyond the instrument's scale is what
   the device shows, the scale's end, flagged ``saturated`` (the model's value kept beside
   it); the profile statistics use the on-scale readings only.

Both callables are injected, so any contact model or instrument model can be used; they run
for the sectors in parallel (``workers`` processes when the callables can be pickled,
threads otherwise).

With a nip (:class:`NipSpec`) the foundation law of each sector for the nip roller (force
per unit CMD length, ``q = alpha d^2 + beta d``) is evaluated once, on a preliminary roll
wound with the uniform nip-induced tension, at every ``foundation_stride``-th sector
(linear interpolation in between), then held fixed while the roll is wound with the nip
distribution recomputed for every winding increment from the current outer-radius profile.
"""

from __future__ import annotations

import concurrent.futures as cf
import contextlib
import math
import os
import pickle
import time
from collections.abc import Callable, Iterator, Sequence
from concurrent.futures.process import BrokenProcessPool
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any, NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

from woundroll.errors import InputError
from woundroll.instruments.definitions import as_shown as shown
from woundroll.instruments.definitions import beyond_scale as saturated
from woundroll.materials.thickness_profile import ThicknessProfile
from woundroll.materials.web import Core, Web
from woundroll.profile.compare import MeasuredProfile, ProfileComparison, compare_profiles
from woundroll.profile.interpolated import (
    DEFAULT_CONTACT_STAGE,
    DEFAULT_TOLERANCE,
    InterpolatedContact,
    check_stage,
    interpolated_springs,
)
from woundroll.profile.nip import NipRoller, nip_hook, solve_nip
from woundroll.profile.stats import ProfileStats, profile_stats, reading_stats
from woundroll.winding.axisymmetric import AxisymmetricResult, wind_axisymmetric
from woundroll.winding.tension import TensionSchedule

FloatArray = NDArray[np.float64]

#: ``contact(radius [m], sigma_r [Pa]) -> (alpha [N/m^2], beta [N/m])`` for one sector, or
#: ``(alpha, beta, a)`` with the semi-contact width a [m] at the striker's maximum depth
#: (the default :class:`ContactModel` with an instrument: the FD reading's active mass
#: {14}-{18} then takes it, as the single roll's does).
ContactFn = Callable[[FloatArray, FloatArray], tuple[float, ...]]


class SectorSprings(NamedTuple):
    """What :func:`map_sectors` returns: the roll spring {3} of every sector and its
    semi-contact width ``width`` [m] (NaN where the contact callable gives none)."""

    alpha: FloatArray
    beta: FloatArray
    width: FloatArray


#: ``readout(alpha, beta) -> reading`` (vectorised over sectors).
ReadoutFn = Callable[[FloatArray, FloatArray], ArrayLike]
#: ``progress(stage, done, total)`` with stage in {"winding", "foundation", "contact"}.
ProgressFn = Callable[[str, int, int], None]


@dataclass(frozen=True)
class ContactModel:
    """The default contact callable on one sector: the roll spring {3} from the roll model.

    With an ``instrument``: :func:`woundroll.contact.roll_stiffness` with the instrument's
    head, starting at ``depth_max`` and deepened while the striker goes further (no
    extrapolation of the fit), the spring fitted over the striker's reach; it returns
    ``(alpha, beta, a)``, a the semi-contact width at the striker's maximum depth (the
    roll's active mass, as for a single roll). Without one (the
    nip roller as a foundation): :func:`woundroll.contact.indent` with ``head_radius`` and
    ``head_length`` to ``depth_max``, the spring fitted over the whole curve. Both fits by
    :func:`woundroll.contact.fit_roll_spring` (``alpha, beta >= 0``).

    Attributes
    ----------
    web, core : Web, Core
    head_radius, head_length : float [m]
        Cylindrical head without an instrument (``head_length = 1``: force per unit length).
    depth_max : float [m]
        Depth of the (first) contact solution.
    instrument : Instrument, optional
        Striker (head and reach).
    options : ContactOptions, optional
    options3d : Contact3DOptions, optional
        The 3D models' mesh and steps (with ``model = "3d"``; None: their defaults).
    """

    web: Web
    core: Core
    head_radius: float
    head_length: float
    depth_max: float = 1e-3
    instrument: Any = None
    options: Any = None
    #: the roll model of the instrument's spring (:func:`woundroll.contact.roll_stiffness`,
    #: a name in :data:`woundroll.contact.models.ROLL_MODELS`); None: the registry's default
    model: str | None = None
    options3d: Any = None

    def __call__(self, radius: FloatArray, sigma_r: FloatArray) -> tuple[float, ...]:
        from woundroll.contact import fit_roll_spring, indent, roll_stiffness

        if self.instrument is not None:
            rs = roll_stiffness(
                self.web,
                self.core,
                radius,
                sigma_r,
                self.instrument,
                start_depth=self.depth_max,
                options=self.options,
                field="profile",
                model=self.model,
                options3d=self.options3d,
            )
            return rs.alpha, rs.beta, rs.semi_contact_width
        res = indent(
            self.web,
            self.core,
            radius,
            sigma_r,
            head_radius=self.head_radius,
            head_length=self.head_length,
            depth_max=self.depth_max,
            options=self.options,
        )
        fit = fit_roll_spring(res.delta, res.force)
        return fit.alpha, fit.beta


@dataclass(frozen=True)
class EnergyReadout:
    """The default readout: the energy model {19}-{22} of an instrument (Rho for a Rho-meter)."""

    instrument: Any

    def __call__(self, alpha: FloatArray, beta: FloatArray) -> FloatArray:
        from woundroll.instruments import rho_energy

        return np.asarray(rho_energy(alpha, beta, self.instrument), dtype=float)


@dataclass(frozen=True)
class FdReadout:
    """The finite-difference model {4}-{13} per sector, the paper's "FD optional" readout.

    The roll's active mass {14}-{18} of sector ``j`` uses its pile height ``H_j`` (build
    radius minus core radius), the roll density, and the semi-contact width a: the contact
    model's at the striker's maximum depth, ``width[j]``, as for a single roll
    (:func:`woundroll.pipeline.hardness_on_roll`); the tester's own (``tester.
    semi_contact_width``, default 0.6 cm, the paper's accepted value) where ``width`` is
    None or NaN (a contact callable that gives none, or a width the user set). Reads the
    striker's total deceleration in the instrument's units.
    """

    setup: Any
    pile_height: FloatArray
    density: float
    width: FloatArray | None = None

    def __call__(self, alpha: FloatArray, beta: FloatArray) -> FloatArray:
        from woundroll.instruments import hardness_from_spring

        out = np.empty(np.size(alpha))
        for j, (a, b) in enumerate(zip(np.ravel(alpha), np.ravel(beta), strict=True)):
            setup = self.setup
            if self.width is not None and math.isfinite(float(self.width[j])):
                setup = replace(setup, semi_contact_width=float(self.width[j]))
            h = hardness_from_spring(
                setup,
                float(a),
                float(b),
                pile_height=float(self.pile_height[j]),
                density=self.density,
            )
            out[j] = h.fd.rho
        return out

    def shared(
        self, alpha: FloatArray, beta: FloatArray, pool: cf.Executor | None, workers: int
    ) -> FloatArray:
        """The readings with the sectors shared between this process and ``workers - 1``
        of the pool's workers (``pool`` None: all here). The time loop is Python, about
        2.3 ms a sector (0.14 s for Table 3's 61): with two workers this process does half
        and a worker the other half, in the same time."""
        a, b = np.ravel(alpha), np.ravel(beta)
        if pool is None or workers < 2 or a.size < 2:
            return self(a, b)
        parts = np.array_split(np.arange(a.size), min(workers, a.size))

        def part(p: NDArray[np.intp]) -> FdReadout:
            w = None if self.width is None else self.width[p]
            return replace(self, pile_height=self.pile_height[p], width=w)

        jobs = [pool.submit(part(p), a[p], b[p]) for p in parts[1:]]
        head = part(parts[0])(a[parts[0]], b[parts[0]])
        return np.concatenate([head, *(job.result() for job in jobs)])


@dataclass(frozen=True)
class NipSpec:
    """A nip on the roll during winding.

    Attributes
    ----------
    roller : NipRoller
        Bending stiffness, mean load per width [N/m], friction mu, radius [m].
    foundation : callable, optional
        ``(radius, sigma_r) -> (alpha, beta)`` per unit CMD length for the roller on one
        sector; default :class:`ContactModel` with the roller's radius and unit length.
    foundation_stride : int
        Evaluate the foundation at every k-th sector (and the last), interpolate between.
    foundation_depth : float [m]
        Depth of the default foundation's contact solutions, over which its law is fitted.
        The nip presses far less deep than the striker (tens to hundreds of um), so the
        fit range follows the nip: after a first fit, the nip is solved on the preliminary
        roll and the foundation recomputed over ``1.25`` times the largest indentation when
        that lies outside ``[0.25, 1]`` of this depth (at most twice).
    """

    roller: NipRoller
    foundation: Callable[[FloatArray, FloatArray], tuple[float, float]] | None = None
    foundation_stride: int = 4
    foundation_depth: float = 3e-4

    def __post_init__(self) -> None:
        if not isinstance(self.roller, NipRoller):
            raise InputError("must be a NipRoller", "winding.nip.roller")
        s = self.foundation_stride
        if isinstance(s, bool) or not isinstance(s, int) or s < 1:
            raise InputError(
                f"must be a whole number >= 1, got {s!r}", "winding.nip.foundation_stride"
            )
        d = self.foundation_depth
        if isinstance(d, bool) or not isinstance(d, int | float) or not (0 < d < 0.05):
            raise InputError(
                f"must be a depth in (0, 5 cm), got {d!r}", "winding.nip.foundation_depth"
            )


@dataclass(frozen=True)
class ContactStage:
    """How the sectors' springs were found: ``stage`` (``"every-sector"`` or
    ``"interpolated"``), the check's ``tolerance`` (reading units) and, interpolated, the
    record of :func:`~woundroll.profile.interpolated.interpolated_springs`."""

    stage: str
    tolerance: float
    record: InterpolatedContact | None = None

    @property
    def solved(self) -> NDArray[np.bool_] | None:
        """Sectors solved fully (None: every one)."""
        return None if self.record is None else self.record.solved

    def to_dict(self, n: int) -> dict[str, Any]:
        rec = self.record
        solved = [True] * n if rec is None else [bool(x) for x in rec.solved]
        return {
            "stage": self.stage,
            "contact_tolerance": self.tolerance if rec is not None else None,
            "solved": solved,
            "n_solved": int(sum(solved)),
            "check_rounds": 0 if rec is None else rec.rounds,
            "largest_check": None if rec is None else rec.largest_check,
        }


@dataclass(frozen=True)
class ProfileResult:
    """Predicted CMD hardness profile, SI, one value per sector.

    Attributes
    ----------
    z : ndarray [m]               sector centres.
    thickness : ndarray [m]       sector-average web thickness.
    rho : ndarray [-]             the model's reading per sector, unclipped: with an
                                  instrument its own reading by the FD model {4}-{13}
                                  (Rho for the Rho-meter), else the readout callable's.
    alpha, beta : ndarray         roll spring {3} per sector [N/m^2], [N/m].
    wot : ndarray [Pa]            layer-weighted mean wound-on tension per sector.
    sigma_r_outer : ndarray [Pa]  radial stress of the outermost layer group.
    sigma_r_core : ndarray [Pa]   radial stress of the group on the core.
    nip_load : ndarray or None [N/m]  nip load per width of the last increment.
    nip_foundation_depth : float or None [m]  depth range of the nip foundation's fit.
    comparison : ProfileComparison or None    a measured profile beside this one.
    rho_energy : ndarray or None  the energy model's reading {19}-{22} per sector (a check).
    scale : (float, float) or None  the instrument's scale (what it can show).
    roll_model : str or None      the roll model that gave the springs (registry name).
    contact_stage : ContactStage or None  every sector solved, or interpolated (and which
                                  sectors were solved fully).
    winding : AxisymmetricResult
    rho_stats : ProfileStats or None   of the on-scale readings (None: fewer than two).
    thickness_stats : ProfileStats
    timings : dict            seconds per stage.
    """

    z: FloatArray
    thickness: FloatArray
    rho: FloatArray
    alpha: FloatArray
    beta: FloatArray
    wot: FloatArray
    sigma_r_outer: FloatArray
    sigma_r_core: FloatArray
    nip_load: FloatArray | None
    winding: AxisymmetricResult
    rho_stats: ProfileStats | None
    thickness_stats: ProfileStats
    timings: dict[str, float] = field(default_factory=dict)
    nip_foundation_depth: float | None = None
    comparison: ProfileComparison | None = None
    rho_energy: FloatArray | None = None
    scale: tuple[float, float] | None = None
    roll_model: str | None = None
    contact_stage: ContactStage | None = None

    @property
    def slack(self) -> NDArray[np.bool_]:
        """Sectors whose outer layers were wound slack or sit at the E_r floor: their
        reading is set by the modulus floor of a K1 = 0 law, not by the roll (flag them)."""
        return np.asarray(self.winding.slack, dtype=bool)

    @property
    def saturated(self) -> NDArray[np.bool_]:
        """Sectors whose reading lies beyond the instrument's scale (the device shows the
        scale's end there)."""
        return saturated(self.rho, self.scale)

    @property
    def shown(self) -> FloatArray:
        """The reading the instrument shows in each sector: the model's, clipped to the
        scale."""
        return shown(self.rho, self.scale)

    def compare(self, measured: MeasuredProfile) -> ProfileResult:
        """This result with a measured profile compared (:mod:`woundroll.profile.compare`)
        against what the instrument would show (:attr:`shown`)."""
        return replace(self, comparison=compare_profiles(self.z, self.shown, measured))

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary: lists over CMD positions (SI, unit in the key) and stats.

        ``reading``: what the instrument shows (the scale's end where ``saturated``);
        ``reading_model``: the model's value; ``reading_energy``: the energy model's.
        """

        def lst(a: FloatArray) -> list[float]:
            return [float(x) for x in a]

        sat = self.saturated
        out: dict[str, Any] = {
            "z_m": lst(self.z),
            "reading": lst(self.shown),
            "reading_model": lst(self.rho),
            "saturated": [bool(x) for x in sat],
            "reading_energy": None if self.rho_energy is None else lst(self.rho_energy),
            "scale": None if self.scale is None else list(self.scale),
            "roll_model": self.roll_model,
            "thickness_m": lst(self.thickness),
            "wound_on_tension_Pa": lst(self.wot),
            "sigma_r_outer_Pa": lst(self.sigma_r_outer),
            "sigma_r_core_Pa": lst(self.sigma_r_core),
            "alpha_N_per_m2": lst(self.alpha),
            "beta_N_per_m": lst(self.beta),
            "stats": {
                "reading": None if self.rho_stats is None else self.rho_stats.to_dict(),
                "reading_n_saturated": int(sat.sum()),
                "thickness_m": self.thickness_stats.to_dict(),
            },
            "slack": [bool(x) for x in self.slack],
            "n_layers": self.winding.n_layers,
            "n_groups": int(self.winding.layers_per_group.size),
            "timings_s": dict(self.timings),
        }
        if self.nip_load is not None:
            out["nip_load_N_per_m"] = lst(self.nip_load)
            mean = float(np.average(self.nip_load, weights=self.winding.dz))
            out["nip"] = {
                "contact_fraction": float(np.mean(self.nip_load > 0)),
                "peak_to_mean": float(self.nip_load.max() / mean) if mean > 0 else None,
                "foundation_depth_m": self.nip_foundation_depth,
            }
        if self.contact_stage is not None:
            out["contact_stage"] = self.contact_stage.to_dict(self.rho.size)
        if self.comparison is not None:
            out["measured"] = self.comparison.to_dict()
        return out

    def stats_title(self) -> str:
        """One line on the on-scale readings: mean, CoV and band, and how many sectors
        are saturated (excluded)."""
        n_sat = int(self.saturated.sum())
        st = self.rho_stats
        if st is None:
            text = f"fewer than two on-scale readings ({n_sat} of {self.rho.size} saturated)"
        else:
            text = f"mean {st.mean:.1f}, CoV {100 * st.cov:.1f} % ({st.band})"
            if n_sat:
                text += f"; {n_sat} of {self.rho.size} sectors off the scale, excluded"
        return text

    def plot(self, path_prefix: str | Path | None = None) -> list[Any]:
        """Figures: thickness and Rho along the CMD (twin axes, Figures 20-21 of the paper)
        and the radial-stress map sigma_r(r, z). Saves ``<prefix>_cmd.png`` and
        ``<prefix>_sigma_r.png`` when ``path_prefix`` is given (a ``.png`` suffix is
        dropped from it)."""
        f1 = self._plot_cmd()
        f2 = self._plot_sigma_r()
        if path_prefix is not None:
            p = str(path_prefix).removesuffix(".png")
            f1.savefig(f"{p}_cmd.png", dpi=120)
            f2.savefig(f"{p}_sigma_r.png", dpi=120)
        return [f1, f2]

    def _plot_cmd(self) -> Any:
        """Thickness and reading along the CMD (twin axes), saturated and slack sectors
        marked, the measured profile when compared."""
        from matplotlib.figure import Figure

        zc = self.z * 100.0
        f1 = Figure(figsize=(8, 4.2), layout="constrained")
        ax = f1.subplots()
        ax.plot(zc, self.thickness * 1e6, color="tab:blue", marker=".", label="thickness")
        ax.set_xlabel("CMD position [cm]")
        ax.set_ylabel("thickness (MD average) [um]", color="tab:blue")
        ax2 = ax.twinx()
        unit = "Rho" if self.scale == (0.0, 100.0) else "reading"
        ax2.plot(zc, self.shown, color="tab:red", marker="o", ms=3, label=f"{unit} (FD model)")
        if self.rho_energy is not None:
            ax2.plot(
                zc,
                shown(self.rho_energy, self.scale),
                color="tab:orange",
                ls="--",
                lw=1,
                label=f"{unit} (energy model, check)",
            )
        self._mark_sectors(ax2, zc)
        ax2.set_ylabel(f"{unit} (instrument scale)", color="tab:red")
        title = f"{unit}: " + self.stats_title()
        c = self.comparison
        if c is not None:
            ax2.plot(
                c.measured.position * 100.0,
                c.measured.reading,
                "s",
                color="black",
                ms=4,
                mfc="none",
                label=f"{unit} (measured)",
            )
            r = "n/a" if c.correlation is None else f"{c.correlation:.2f}"
            title += f"\nmeasured: bias {c.bias:+.1f}, RMS {c.rms:.1f}, correlation {r}"
        ax2.legend(loc="best", fontsize=8)
        ax.set_title(title)
        return f1

    def _mark_sectors(self, ax2: Any, zc: FloatArray) -> None:
        """The scale's ends, and the saturated and slack sectors."""
        sat = self.saturated
        if self.scale is not None:
            for end in self.scale:
                ax2.axhline(end, color="0.5", lw=0.8, ls=":")
            if np.any(sat):
                ax2.plot(
                    zc[sat],
                    self.shown[sat],
                    "^",
                    color="black",
                    ms=6,
                    mfc="none",
                    label="saturated: the model reads beyond the scale",
                )
        if np.any(self.slack):
            ax2.plot(
                zc[self.slack],
                self.shown[self.slack],
                "x",
                color="tab:red",
                ms=8,
                label="slack sector (reading set by the E_r floor)",
            )

    def _plot_sigma_r(self) -> Any:
        """The interlayer pressure over (r, z), log scale."""
        from matplotlib.colors import LogNorm
        from matplotlib.figure import Figure

        zc = self.z * 100.0
        w = self.winding
        f2 = Figure(figsize=(8, 4.2), layout="constrained")
        bx = f2.subplots()
        zz = np.broadcast_to(zc[None, :], w.radius.shape)
        # log scale: thick lanes carry MPa while slack ones carry almost nothing
        pk = np.maximum(-w.sigma_r / 1e3, 0.0)
        top = max(float(pk.max()), 1e-9)
        pcm = bx.pcolormesh(
            zz,
            w.radius * 100.0,
            np.maximum(pk, 1e-3 * top),
            shading="nearest",
            cmap="viridis",
            norm=LogNorm(1e-3 * top, top),
        )
        f2.colorbar(pcm, ax=bx, label="interlayer pressure -sigma_r [kPa] (log)")
        bx.set_xlabel("CMD position [cm]")
        bx.set_ylabel("radius [cm]")
        bx.set_title("radial stress over (r, z)")
        return f2


def _call(fn: ContactFn, radius: FloatArray, sigma_r: FloatArray) -> tuple[float, float, float]:
    out = tuple(fn(radius, sigma_r))
    width = float(out[2]) if len(out) > 2 and out[2] is not None else math.nan
    return float(out[0]), float(out[1]), width


def _picklable(obj: Any) -> bool:
    try:
        pickle.dumps(obj)
    except (pickle.PicklingError, AttributeError, TypeError):
        return False
    return True


def map_sectors(
    fn: ContactFn | Sequence[ContactFn],
    profiles: Sequence[tuple[FloatArray, FloatArray]],
    *,
    workers: int = 2,
    progress: Callable[[int, int], None] | None = None,
    pool: cf.Executor | None = None,
) -> SectorSprings:
    """Evaluate ``fn(radius, sigma_r)`` for every sector, in parallel (``fn`` one callable,
    or one per sector).

    Processes (``spawn``) when ``fn`` can be pickled and ``workers > 1``, threads when it
    cannot, in-line when ``workers == 1``. ``pool``: a process pool already started (e.g.
    :func:`early_pool`, whose workers imported the contact model while the roll was
    wound); it is used and left open. Returns :class:`SectorSprings` ``(alpha, beta,
    width)`` arrays in sector order.
    """
    n = len(profiles)
    fns = list(fn) if isinstance(fn, Sequence) else [fn] * n
    if len(fns) != n:
        raise InputError(f"{len(fns)} contact callables for {n} sectors", "tester.contact")
    out = np.empty((n, 3))
    done = 0
    if workers <= 1 or n <= 1:
        for j, (r, s) in enumerate(profiles):
            out[j] = _call(fns[j], r, s)
            done += 1
            if progress is not None:
                progress(done, n)
        return SectorSprings(out[:, 0], out[:, 1], out[:, 2])
    if _picklable(fns):
        try:
            if pool is not None:
                return _run_pool(fns, profiles, out, progress, pool, close=False)
            return _run_pool(fns, profiles, out, progress, sector_pool(workers))
        except (ImportError, AttributeError, pickle.PicklingError, BrokenProcessPool):
            # the callable pickles here but cannot be rebuilt in a fresh process (defined in
            # a script or a test module): fall back to threads
            pass
    return _run_pool(fns, profiles, out, progress, cf.ThreadPoolExecutor(max_workers=workers))


#: Environment of the sector workers: one BLAS thread each. The workers already fill the
#: cores; threaded BLAS on top of them oversubscribes the machine (single contact solves
#: measured up to tenfold slower under load, docs/profile.md, section 7). And glibc's
#: allocator keeps freed memory for reuse (fixed mmap and trim thresholds, 256 MB): the
#: contact solve allocates a fresh 3.4 MB band per increment, and with the default
#: (adaptive) thresholds a fresh worker's first sector paid the page faults of each one
#: (sector 5 of Table 3: 0.59 s first, 0.32 s again; with these 0.34 / 0.31 s). Ignored
#: by other C libraries.
WORKER_ENV = {
    "OPENBLAS_NUM_THREADS": "1",
    "OMP_NUM_THREADS": "1",
    "MKL_NUM_THREADS": "1",
    "MALLOC_MMAP_THRESHOLD_": "268435456",
    "MALLOC_TRIM_THRESHOLD_": "268435456",
}


def sector_pool(workers: int) -> cf.ProcessPoolExecutor:
    """The process pool of the per-sector solves (``spawn``: no inherited state; from
    :func:`woundroll.util.pool.process_pool`, so SIGINT/SIGTERM stop it cleanly). The one place
    where sector workers are created; they read :data:`WORKER_ENV` when they start
    (:func:`_run_pool` sets it while they do)."""
    from woundroll.util.pool import process_pool

    return process_pool(workers)


@contextlib.contextmanager
def _worker_env(ex: cf.Executor) -> Iterator[None]:
    """:data:`WORKER_ENV` in the environment while the pool's workers start (spawned
    children inherit it; this process's BLAS is already loaded and keeps its threads)."""
    if not isinstance(ex, cf.ProcessPoolExecutor):
        yield
        return
    saved = {k: os.environ.get(k) for k in WORKER_ENV}
    os.environ.update(WORKER_ENV)
    try:
        yield
    finally:
        for k, v in saved.items():
            if v is None:
                os.environ.pop(k, None)
            else:
                os.environ[k] = v


def _run_pool(
    fns: Sequence[ContactFn],
    profiles: Sequence[tuple[FloatArray, FloatArray]],
    out: FloatArray,
    progress: Callable[[int, int], None] | None,
    ex: cf.Executor,
    close: bool = True,
) -> SectorSprings:
    n = len(profiles)
    done = 0
    with ex if close else contextlib.nullcontext():
        with _worker_env(ex):
            futs = {ex.submit(_call, fns[j], r, s): j for j, (r, s) in enumerate(profiles)}
        for fut in cf.as_completed(futs):
            out[futs[fut]] = fut.result()
            done += 1
            if progress is not None:
                progress(done, n)
    return SectorSprings(out[:, 0], out[:, 1], out[:, 2])


def _warm_up() -> int:
    """Import the contact model in a sector worker (run while the roll is wound)."""
    import woundroll.contact.plane_strain.solver  # noqa: F401
    import woundroll.contact.spring  # noqa: F401
    import woundroll.instruments  # noqa: F401

    return os.getpid()


@contextlib.contextmanager
def early_pool(contact: Any, workers: int) -> Iterator[cf.Executor | None]:
    """The sector workers, started before the winding: a spawned worker spends about a
    second importing Python, NumPy, SciPy and the contact model; started first, they do it
    on the core the (serial) winding leaves free instead of after it. None when the
    contact callable does not pickle or ``workers == 1`` (:func:`map_sectors` then decides
    as before). Closed (and its workers joined) on leaving the block."""
    if workers <= 1 or not _picklable([contact]):
        yield None
        return
    ex = sector_pool(workers)
    try:
        with _worker_env(ex):
            for _ in range(workers):
                ex.submit(_warm_up)
        yield ex
    except BaseException:
        ex.shutdown(wait=False, cancel_futures=True)  # an error: do not wait for warm-ups
        raise
    ex.shutdown(wait=True)


def _check_workers(workers: Any) -> int:
    if isinstance(workers, bool) or not isinstance(workers, int | np.integer) or workers < 1:
        raise InputError(f"must be a whole number >= 1, got {workers!r}", "profile.workers")
    return int(workers)


def predict_profile(
    web: Web,
    core: Core,
    tension: TensionSchedule,
    thickness_profile: ThicknessProfile | None = None,
    *,
    outer_radius: float,
    contact: ContactFn | None = None,
    instrument: Any = None,
    n_sectors: int = 61,
    n_groups: int | None = None,
    nip: NipSpec | None = None,
    depth_max: float = 1e-3,
    workers: int = 2,
    progress: ProgressFn | None = None,
    pool: cf.Executor | None = None,
    setup: Any = None,
    model: str | None = None,
    contact_stage: str = DEFAULT_CONTACT_STAGE,
    contact_tolerance: float = DEFAULT_TOLERANCE,
    semi_contact_width_given: bool = False,
) -> ProfileResult:
    """Predict the CMD hardness profile of a center-wound roll.

    Parameters
    ----------
    web, core : Web, Core
        Material and core (SI). ``web.thickness`` [m] is the nominal thickness that, with
        ``tension.web_stress`` [Pa] and the profile's CMD extent [m], sets the line tension.
    tension : TensionSchedule
        Web stress [Pa], taper; without ``nip`` its ``nip_load`` [N/m] and ``friction`` add a
        uniform nip-induced tension (1D rule).
    thickness_profile : ThicknessProfile, optional
        CMD profile (default uniform ``web.thickness`` over ``web.width``).
    outer_radius : float [m]
        Final roll radius.
    contact : callable, optional
        ``(radius, sigma_r) -> (alpha, beta)``; default :class:`ContactModel` with the
        instrument's head and ``depth_max``.
    instrument : Instrument or callable, optional
        An :class:`~woundroll.instruments.Instrument` (its own reading by the FD model, the
        energy model beside it) or a callable ``(alpha, beta) -> reading``; default the
        ``rho-meter`` preset.
    n_sectors, n_groups : int
        CMD sectors; winding increments (see :func:`wind_axisymmetric`).
    nip : NipSpec, optional
        Nip roller whose CMD load distribution allocates the nip-induced tension.
    depth_max : float [m]
        Indentation depth of the default contact model.
    workers : int
        Parallel workers for the per-sector contact solutions.
    progress : callable, optional
        ``progress(stage, done, total)``.
    pool : Executor, optional
        Sector workers already started (:func:`early_pool` entered by the caller, which
        can give them other work while the roll is wound); used and left open. None: the
        profile starts (and closes) its own.
    setup : TesterSetup, optional
        The tester's settings for the FD reading (collision, restitution, time step);
        default the instrument's (or the Rho-meter's) with the case defaults.
    model : str, optional
        Roll model of the default contact callable (a name in
        :data:`woundroll.contact.models.ROLL_MODELS`; None: the registry's default).
    contact_stage : {"every-sector", "interpolated"}
        One full contact solve per sector (exact), or full solves on a few sectors with the
        springs interpolated between and checked (:mod:`woundroll.profile.interpolated`).
    contact_tolerance : float
        Largest reading change (the instrument's units) the interpolation's last check may
        find.
    semi_contact_width_given : bool
        The tester's ``semi_contact_width`` was set by the user: the FD reading's active
        mass takes it on every sector instead of each sector's contact width (as for a
        single roll, :func:`woundroll.pipeline.hardness_on_roll`).

    Raises
    ------
    InputError
        Bad input (dotted field names). ConvergenceError: a solver did not converge.
    """
    workers = _check_workers(workers)
    stage_name, tolerance = check_stage(contact_stage, contact_tolerance)
    t0 = time.perf_counter()
    readout, contact = _readout_and_contact(
        web, core, contact, instrument, depth_max, setup=setup, model=model,
        contact_width=not semi_contact_width_given,
    )  # fmt: skip
    scope = contextlib.nullcontext(pool) if pool is not None else early_pool(contact, workers)
    with scope as pool:
        return _predict_profile(
            web,
            core,
            tension,
            thickness_profile,
            outer_radius,
            contact,
            readout,
            n_sectors=n_sectors,
            n_groups=n_groups,
            nip=nip,
            workers=workers,
            progress=progress,
            pool=pool,
            t0=t0,
            stage_name=stage_name,
            tolerance=tolerance,
        )


def _predict_profile(
    web: Web,
    core: Core,
    tension: TensionSchedule,
    thickness_profile: ThicknessProfile | None,
    outer_radius: float,
    contact: ContactFn,
    readout: InstrumentReadout | ReadoutFn,
    *,
    n_sectors: int,
    n_groups: int | None,
    nip: NipSpec | None,
    workers: int,
    progress: ProgressFn | None,
    pool: cf.Executor | None,
    t0: float,
    stage_name: str = DEFAULT_CONTACT_STAGE,
    tolerance: float = DEFAULT_TOLERANCE,
) -> ProfileResult:
    """The steps of :func:`predict_profile` (nip foundation, winding, contact, reading) on
    the sector pool ``pool``."""
    timings: dict[str, float] = {}

    def stage(name: str) -> Callable[[int, int], None] | None:
        if progress is None:
            return None
        return lambda d, n: progress(name, d, n)

    hook, f_depth = None, None
    if nip is not None:
        hook, f_depth, tension = _nip_on_the_roll(
            web, core, tension, thickness_profile, outer_radius, nip, n_sectors=n_sectors,
            n_groups=n_groups, workers=workers, progress=stage("foundation"), pool=pool,
        )  # fmt: skip
        timings["nip_foundation"] = time.perf_counter() - t0
    # 1. stresses in the roll, (r, z)
    t1 = time.perf_counter()
    w = wind_axisymmetric(
        web, core, outer_radius, tension, thickness_profile, n_sectors=n_sectors,
        n_groups=n_groups, nip=hook, progress=stage("winding"),
    )  # fmt: skip
    timings["winding"] = time.perf_counter() - t1
    # 2. the roll spring under the striker, sector by sector
    t2 = time.perf_counter()
    profiles = [w.sector_profile(j) for j in range(w.z.size)]
    fns = sector_contacts(contact, w.slack)
    contact_stage = None
    if stage_name == "anchored" and _anchors_itself(contact):
        stage_name = "every-sector"  # plane strain anchored on plane strain: every sector
    if stage_name == "every-sector":
        alpha, beta, width = map_sectors(
            fns, profiles, workers=workers, progress=stage("contact"), pool=pool
        )
    else:
        base = None
        if stage_name == "anchored":
            base = map_sectors(
                sector_contacts(_cheap_contact(contact), w.slack), profiles,
                workers=workers, progress=stage("contact (plane strain)"), pool=pool,
            )  # fmt: skip
        contact_stage = _interpolated_contact(
            fns, profiles, readout, w, web, pool, workers, tolerance, stage("contact"), base
        )
        alpha, beta, width = contact_stage.alpha, contact_stage.beta, contact_stage.width
    timings["contact"] = time.perf_counter() - t2
    # 3. the reading: the instrument's own (FD), the energy model beside it
    rho, rho_energy, scale = _sector_readings(readout, alpha, beta, w, web, pool, workers, width)
    roll_model = None
    if isinstance(contact, ContactModel) and contact.instrument is not None:
        from woundroll.contact.models import resolve_model

        roll_model = resolve_model(contact.model, contact.instrument.head_shape).name
    timings["total"] = time.perf_counter() - t0
    return ProfileResult(
        z=w.z,
        thickness=w.thickness,
        rho=rho,
        alpha=alpha,
        beta=beta,
        wot=w.wot_mean,
        sigma_r_outer=w.sigma_r_outer.copy(),
        sigma_r_core=w.sigma_r_core.copy(),
        nip_load=w.nip_load[-1].copy() if nip is not None else None,
        winding=w,
        rho_stats=reading_stats(rho, scale, "profile.reading"),
        thickness_stats=profile_stats(w.thickness, "profile.thickness"),
        timings=timings,
        nip_foundation_depth=f_depth,
        rho_energy=rho_energy,
        scale=scale,
        roll_model=roll_model,
        contact_stage=ContactStage(stage_name, tolerance, contact_stage),
    )


def _interpolated_contact(
    fns: list[ContactFn],
    profiles: list[tuple[FloatArray, FloatArray]],
    readout: InstrumentReadout | ReadoutFn,
    w: Any,
    web: Web,
    pool: cf.Executor | None,
    workers: int,
    tolerance: float,
    progress: Callable[[int, int], None] | None,
    base: SectorSprings | None = None,
) -> InterpolatedContact:
    """The springs and semi-contact widths by
    :func:`woundroll.profile.interpolated.interpolated_springs`: full solves by
    :func:`map_sectors` on the pool (alpha, beta and width, in the order asked), readings
    of the checked sectors with their own pile heights and their widths (the solved
    sectors' own, interpolated like the springs elsewhere); anchored on the cheap model's
    springs and widths ``base`` when given."""
    pile = w.build_radius - w.core_radius
    scale = None
    if isinstance(readout, InstrumentReadout):
        setup = readout.setup
        scale = setup.instrument.reading_range

        def readings(
            a: FloatArray, b: FloatArray, width: FloatArray, sel: NDArray[np.intp]
        ) -> FloatArray:
            return FdReadout(setup, pile[sel], web.density, readout.widths(width))(a, b)
    else:

        def readings(
            a: FloatArray, b: FloatArray, width: FloatArray, sel: NDArray[np.intp]
        ) -> FloatArray:
            return np.asarray(readout(a, b), dtype=float).reshape(-1)

    def solve(f: Sequence[ContactFn], p: Sequence[tuple[FloatArray, FloatArray]]) -> SectorSprings:
        return map_sectors(list(f), list(p), workers=workers, pool=pool)

    return interpolated_springs(
        fns,
        profiles,
        solve,
        readings,
        tolerance=tolerance,
        batch=2 * workers,
        scale=scale,
        progress=progress,
        base=base,
    )


#: The cheap model of the anchored contact stage (``[profile] contact = "anchored"``): the
#: paper's plane-strain ring, solved on every sector.
ANCHOR_MODEL = "2d"


def _cheap_contact(contact: ContactFn) -> ContactModel:
    """The anchored stage's cheap contact callable: ``contact`` with the plane-strain roll
    model (:data:`ANCHOR_MODEL`); a custom callable cannot be anchored."""
    if not (isinstance(contact, ContactModel) and contact.instrument is not None):
        raise InputError(
            "the anchored contact stage needs the default contact model with an instrument",
            "profile.contact",
        )
    if contact.instrument.head_shape not in ("cylinder",):
        raise InputError(
            f"the anchored contact stage reads a cylindrical head in plane strain, not a "
            f"{contact.instrument.head_shape}",
            "profile.contact",
        )
    return replace(contact, model=ANCHOR_MODEL)


def _anchors_itself(contact: ContactFn) -> bool:
    """The contact model is the anchored stage's cheap model itself (the stage is then
    every sector: nothing to anchor)."""
    from woundroll.contact.models import resolve_model

    if not (isinstance(contact, ContactModel) and contact.instrument is not None):
        return False
    return resolve_model(contact.model, contact.instrument.head_shape).name == ANCHOR_MODEL


def _sector_readings(
    readout: InstrumentReadout | ReadoutFn,
    alpha: FloatArray,
    beta: FloatArray,
    w: Any,
    web: Web,
    pool: cf.Executor | None,
    workers: int,
    width: FloatArray | None = None,
) -> tuple[FloatArray, FloatArray | None, tuple[float, float] | None]:
    """Each sector's reading from its roll spring and semi-contact width (the energy
    model's beside it, and the instrument's scale, for an instrument readout)."""
    scale, rho_energy = None, None
    if isinstance(readout, InstrumentReadout):
        rho, rho_energy = readout.read(
            alpha, beta, w.build_radius - w.core_radius, web.density, pool, workers, width
        )
        scale = readout.setup.instrument.reading_range
    else:
        rho = np.asarray(readout(alpha, beta), dtype=float).reshape(-1)
    if rho.shape != alpha.shape or not np.all(np.isfinite(rho)):
        raise InputError(
            "the readout must return one finite reading per sector", "tester.instrument"
        )
    return rho, rho_energy, scale


def sector_contacts(contact: ContactFn, slack: NDArray[np.bool_]) -> list[ContactFn]:
    """The contact callable of each sector. A slack sector (its outer layers wound without
    tension or at the E_r floor, :attr:`AxisymmetricResult.slack`) lets the striker sink to
    the contact model's reach: the default :class:`ContactModel` starts it there instead of
    at ``depth_max`` and deepening (up to three redundant solutions)."""
    if not (isinstance(contact, ContactModel) and contact.instrument is not None):
        return [contact] * len(slack)
    deep = replace(contact, depth_max=math.inf)  # roll_stiffness starts at min(., reach)
    return [deep if s else contact for s in slack]


@dataclass(frozen=True)
class InstrumentReadout:
    """The readout of an instrument: its own reading by the FD model {4}-{13}
    (:class:`FdReadout`, with each sector's pile height once the roll is wound) and the
    energy model {19}-{22} beside it (:class:`EnergyReadout`). ``contact_width``: the
    active mass takes each sector's contact semi-contact width (False: the tester's
    ``semi_contact_width``, which the user set)."""

    setup: Any
    contact_width: bool = True

    def widths(self, width: FloatArray | None) -> FloatArray | None:
        """The per-sector widths the FD reading uses (None: the tester's)."""
        return width if self.contact_width else None

    def read(
        self,
        alpha: FloatArray,
        beta: FloatArray,
        pile_height: FloatArray,
        density: float,
        pool: cf.Executor | None,
        workers: int,
        width: FloatArray | None = None,
    ) -> tuple[FloatArray, FloatArray]:
        """(FD reading, energy reading) per sector; ``width``: each sector's contact
        semi-contact width [m]."""
        fd = FdReadout(self.setup, pile_height, density, self.widths(width))
        return fd.shared(alpha, beta, pool, workers), EnergyReadout(self.setup.instrument)(
            alpha, beta
        )


def _readout_and_contact(
    web: Web,
    core: Core,
    contact: Any,
    instrument: Any,
    depth_max: float,
    setup: Any = None,
    model: str | None = None,
    contact_width: bool = True,
) -> tuple[InstrumentReadout | ReadoutFn, ContactFn]:
    """The reading from (alpha, beta) (an Instrument's own reading, default the
    Rho-meter, with the tester ``setup`` when given; or a callable) and the per-sector
    contact callable (default :class:`ContactModel` with the instrument's head and the
    roll model ``model``)."""
    from woundroll.instruments import TesterSetup, get_instrument

    readout: InstrumentReadout | ReadoutFn
    inst = None
    if setup is not None:
        inst = setup.instrument
        readout = InstrumentReadout(setup, contact_width)
    elif instrument is None or (
        hasattr(instrument, "spring_stiffness") and hasattr(instrument, "head_radius")
    ):
        inst = get_instrument("rho-meter") if instrument is None else instrument
        readout = InstrumentReadout(TesterSetup(inst))
    elif callable(instrument):
        readout = instrument
    else:
        raise InputError(
            "must be an Instrument or a callable (alpha, beta) -> reading", "tester.instrument"
        )
    if contact is None:
        if inst is None or inst.head_length is None:
            raise InputError(
                "a readout callable without an Instrument needs a contact callable "
                "(or an instrument with a cylindrical head)",
                "tester.contact",
            )
        contact = ContactModel(
            web, core, inst.head_radius, inst.head_length, depth_max, instrument=inst, model=model
        )
    elif not callable(contact):
        raise InputError("must be a callable (radius, sigma_r) -> (alpha, beta)", "tester.contact")
    return readout, contact


def _nip_on_the_roll(
    web: Web,
    core: Core,
    tension: TensionSchedule,
    thickness_profile: ThicknessProfile | None,
    outer_radius: float,
    nip: Any,
    *,
    n_sectors: int,
    n_groups: int | None,
    workers: int,
    progress: Callable[[int, int], None] | None,
    pool: cf.Executor | None = None,
) -> tuple[Any, float | None, TensionSchedule]:
    """The nip roller riding on the roll: a preliminary roll wound with the uniform
    nip-induced tension, the roll's foundation law for the roller at every
    ``foundation_stride``-th sector (fit depth following the nip's reach), and the hook that
    gives :func:`wind_axisymmetric` the CMD nip load of every increment. Returns the hook,
    the foundation's fit depth and the tension schedule without the uniform nip load."""
    if not isinstance(nip, NipSpec):
        raise InputError("must be a NipSpec (roller, foundation) or None", "winding.nip")
    if tension.nip_load > 0:
        raise InputError(
            "set the nip load in the NipSpec's roller, not in the tension "
            "schedule, when a nip distribution is computed",
            "winding.nip_load",
        )
    roller = nip.roller
    pre = wind_axisymmetric(
        web,
        core,
        outer_radius,
        replace(tension, nip_load=roller.line_load, friction=roller.friction),
        thickness_profile,
        n_sectors=n_sectors,
        n_groups=n_groups,
    )
    ns = pre.z.size
    picks = sorted(set(range(0, ns, nip.foundation_stride)) | {ns - 1})
    edges = np.concatenate(
        [[pre.z[0] - 0.5 * pre.dz[0]], pre.z[0] - 0.5 * pre.dz[0] + np.cumsum(pre.dz)]
    )
    gap = float(np.max(pre.outer_radius)) - pre.outer_radius
    f_depth: float | None = nip.foundation_depth
    for attempt in range(3):
        found = nip.foundation or ContactModel(web, core, roller.radius, 1.0, f_depth)
        fa, fb, _ = map_sectors(
            found,
            [pre.sector_profile(j) for j in picks],
            workers=workers,
            progress=progress,
            pool=pool,
        )
        alpha_n = np.interp(pre.z, pre.z[picks], fa)
        beta_n = np.interp(pre.z, pre.z[picks], fb)
        if nip.foundation is not None:
            f_depth = None  # the caller's foundation: no depth range of ours
            break
        reach = float(np.max(solve_nip(edges, alpha_n, beta_n, roller, gap=gap).indentation))
        if reach <= 0 or 0.25 * f_depth <= reach <= f_depth or attempt == 2:
            break  # f_depth stays the depth the laws were fitted over
        f_depth = 1.25 * reach
    hook = nip_hook(edges, alpha_n, beta_n, roller)
    return hook, f_depth, replace(tension, nip_load=0.0, friction=roller.friction)


__all__ = [
    "ContactModel",
    "ContactStage",
    "EnergyReadout",
    "FdReadout",
    "InstrumentReadout",
    "NipSpec",
    "ProfileResult",
    "map_sectors",
    "predict_profile",
    "solve_nip",
]
