"""1D nonlinear center-winding model (Hakiel, Tappi J. 70(5), 1987).

The roll is built layer by layer (or a lumped group of layers per increment). Each
increment is the linear plane-stress response of the roll wound so far, with the tangent
radial modulus ``E_r`` of {2} (or any other law), to the pressure of the new layer.

Equations (derivation in ``docs/winding.md``)
---------------------------------------------
Equilibrium ``sigma_theta = d(r sigma_r)/dr``; orthotropic plane stress
``eps_r = sigma_r/E_r - nu_theta_r sigma_theta/E_theta``,
``eps_theta = sigma_theta/E_theta - nu_r_theta sigma_r/E_r`` with
``nu_r_theta = nu_theta_r E_r/E_theta``; compatibility ``eps_r = d(r eps_theta)/dr``.
With ``F = r sigma_r`` and ``x = ln r`` these give, for any radial variation of E_r,

    F_xx = (E_theta / E_r) F,      i.e.  r^2 s'' + 3 r s' + (1 - E_theta/E_r) s = 0

for the radial-stress increment ``s`` (Hakiel's equation): the ``nu_theta_r`` terms cancel
in the roll (E_theta uniform) and ``nu_theta_r`` enters only the core condition

    u(r_c) = r_c sigma_r / E_c   <=>   sigma_theta(r_c) = (E_theta/E_c + nu_theta_r) sigma_r(r_c).

The outer boundary condition of the increment is the new layer's pressure
``sigma_r(s) = -WOT h / s`` (``F(s) = -WOT h``); the new layer itself carries
``sigma_theta = WOT`` and ``F(r) = -WOT (s + h - r)`` (a thin ring in equilibrium).

Discretisation
--------------
Nodes at the layer interfaces and ``subdivisions - 1`` sub-layer nodes per layer.
In each element E_r is uniform and the element relation between the end values of F and
of the flux ``F_x = r sigma_theta`` is the exact power-law solution
``F = A r^k + B r^-k``, ``k = sqrt(E_theta/E_r)``, i.e. ``sigma_r ~ r^(-1 +- k)``; so a
uniform-E_r roll is solved exactly on any grid, and refinement only resolves the variation
of E_r. The tridiagonal system is solved by elimination from the core outward.

E_r within an increment (assumption the paper leaves open)
-----------------------------------------------------------
``modulus_update="midpoint"`` (default): each element's E_r is evaluated at its pressure in
the middle of the increment, ``P_start + dP/2``, by fixed-point iteration (a midpoint rule
for the strain ``int dP / E_r``, second order in the increment). ``"end"`` uses
``P_start + dP`` (backward Euler), ``"explicit"`` uses ``P_start`` (no iteration). The
choice moves the core pressure by several per cent (test_hakiel.py measures it).

K1 = 0 (E_r = 0 at zero pressure, Table 3)
------------------------------------------
With the midpoint (or end) rule the top element is evaluated at the pressure it carries
during the increment, which is positive below a tensioned layer, so E_r > 0. A floor
``E_r >= modulus_floor * E_theta`` (default 1e-6 E_theta, i.e. 5 kPa for a 5 GPa film)
keeps a zero-tension layer, or the explicit rule at a free surface, finite.

Lazy deep part (speed): levels of doubling depth
-------------------------------------------------
The top ``window_layers`` layers (level 0) are re-solved with current moduli and iterated
in every increment. Below them, level l >= 1 is the band from ``window_layers x 2^(l-1)``
to ``window_layers x 2^l`` layers deep (placed when it is refreshed); its element moduli are
frozen for ``flush_interval x 2^(l-1)`` increments at the pressure predicted (quadratic
extrapolation of its last refreshes) for the middle of that period, so the frozen period
is the same fraction of the depth at every level. With frozen coefficients a band's
increments are its frozen shape (a product of Riccati factors) times one scalar, the
pending increment at its top, applied when the band is refreshed; the Riccati recursion
condenses everything below a band into one coefficient. Refresh k re-solves levels
1..1+(trailing zero bits of k): O(log N) element evaluations per increment, amortised,
O(N log N) for the roll. ``window_layers=None`` solves the whole roll with current moduli
every increment (O(N^2), the exact answer the default matches within 0.1 %).

Kernels: :mod:`woundroll.winding._kernels` (numba) and its NumPy twin
:mod:`woundroll.winding._kernels_numpy` (same algorithm, equal to rounding), used for small
rolls so that a small roll pays no compiler import (docs/winding.md).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import asdict, dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from woundroll.errors import ConvergenceError, InputError
from woundroll.materials.web import Core, Web
from woundroll.winding.result import WindingResult
from woundroll.winding.tension import TensionSchedule

FloatArray = NDArray[np.float64]

_MODES = {"midpoint": 0.5, "end": 1.0, "explicit": 0.0}
_MAX_NODES = 20_000_000
_MAX_LEVELS = 48
#: Rolls up to this many nodes (x load substeps x window / 8 layers) are wound by the NumPy
#: kernels: below it they beat loading the compiled kernels (~0.1 s with llvmlite,
#: :mod:`woundroll.winding._kernels_aot`; break-even ~120 two-node layers, measured
#: 2026-11-26 in docs/performance.md). ``window_layers=None`` (O(N^2), a check) is compiled.
_NUMPY_MAX_NODES = 250
#: Up to this size the compiled kernels are used only if already built on this machine (the
#: NumPy twin otherwise: a first small roll never waits for the one-off build, ~15 s);
#: above it a missing build is made (the NumPy kernels' 0.1-0.5 s per 1000 layers).
_BUILD_MIN_NODES = 4001
_NEW_LAYER = ("laid_on", "elastic")


@dataclass(frozen=True)
class WindingOptions:
    """Numerical options of :func:`wind`; the defaults are converged (docs/winding.md).

    Attributes
    ----------
    subdivisions : int
        Elements per layer (sub-layer nodes resolve E_r across the surface boundary layer).
    layers_per_increment : int
        Layers lumped into one increment (1: layer by layer, Hakiel's model).
    modulus_update : {"midpoint", "end", "explicit"}
        Where in the increment E_r is evaluated (module docstring).
    rtol : float
        Fixed-point tolerance on the increment, relative to the applied one (started from
        the previous increment's shape; stops when the change, or the contraction's bound
        on the remaining error, is within it: docs/winding.md).
    max_iterations : int
        Fixed-point iterations per increment before :class:`ConvergenceError`.
    modulus_floor : float
        Floor of E_r as a fraction of E_theta (keeps K1 = 0 finite).
    window_layers : int or None
        Layers below the surface solved with current moduli every increment; deeper ones
        are frozen in levels of doubling depth (module docstring). None: no freezing.
    flush_interval : int
        Increments between refreshes of the shallowest frozen level (level l: this times
        2^(l-1)).
    load_substeps : int
        Apply each increment's pressure in this many equal steps, updating E_r in between
        (a check on the E_r rule: many substeps integrate the tangent law exactly).
    new_layer : {"laid_on", "elastic"}
        How a new layer enters its own increment (docs/assumptions.md): ``"laid_on"``
        (default) the layer is laid on at its wound-on tension and presses ``T h / s`` on
        the roll below (it is not part of the elastic body during its own increment);
        ``"elastic"``: the layer is part of the elastic body and ``F = -T h`` acts on its
        outer face (Hakiel's finite-difference boundary condition; the surface then keeps
        ``sigma_r = -T h / R``).
    """

    subdivisions: int = 2
    layers_per_increment: int = 1
    modulus_update: str = "midpoint"
    rtol: float = 1e-9
    max_iterations: int = 60
    modulus_floor: float = 1e-6
    window_layers: int | None = 8
    flush_interval: int = 1
    load_substeps: int = 1
    new_layer: str = "laid_on"

    def __post_init__(self) -> None:
        f = "options"
        for name in (
            "subdivisions",
            "layers_per_increment",
            "max_iterations",
            "flush_interval",
            "load_substeps",
        ):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, int | np.integer) or v < 1:
                raise InputError(f"must be a whole number >= 1, got {v!r}", f"{f}.{name}")
        if self.subdivisions > 1000:
            raise InputError(f"must be <= 1000, got {self.subdivisions}", f"{f}.subdivisions")
        if self.modulus_update not in _MODES:
            raise InputError(
                f"choose one of {', '.join(_MODES)}, got {self.modulus_update!r}",
                f"{f}.modulus_update",
            )
        if self.new_layer not in _NEW_LAYER:
            raise InputError(
                f"choose one of {', '.join(_NEW_LAYER)}, got {self.new_layer!r}",
                f"{f}.new_layer",
            )
        if not (isinstance(self.rtol, float | int) and 0 < self.rtol < 1e-2):
            raise InputError(f"must lie in (0, 0.01), got {self.rtol!r}", f"{f}.rtol")
        if not (isinstance(self.modulus_floor, float | int) and 0 < self.modulus_floor < 1):
            raise InputError(
                f"must lie in (0, 1), got {self.modulus_floor!r}", f"{f}.modulus_floor"
            )
        w = self.window_layers
        if w is not None and (isinstance(w, bool) or not isinstance(w, int | np.integer) or w < 1):
            raise InputError(
                f"must be a whole number >= 1 or None, got {w!r}", f"{f}.window_layers"
            )

    @classmethod
    def from_dict(cls, data: Mapping[str, Any] | None, field: str = "options") -> WindingOptions:
        """Build from a case-file mapping; unknown keys raise :class:`InputError`."""
        data = dict(data or {})
        known = set(cls.__dataclass_fields__)
        unknown = sorted(set(data) - known)
        if unknown:
            raise InputError(
                f"unknown option(s) {', '.join(unknown)}; known: {', '.join(sorted(known))}", field
            )
        try:
            return cls(**data)
        except InputError as exc:
            name = exc.field.split(".", 1)[1] if exc.field and "." in exc.field else exc.field
            raise InputError(exc.message, f"{field}.{name}" if name else field) from None

    def to_dict(self) -> dict[str, Any]:
        return asdict(self)

    def kernels(self, n_layers: int) -> str:
        """Which kernels :func:`wind` winds ``n_layers`` with under these options
        (:func:`kernel_path`; :mod:`woundroll.limits` asks, which may not import winding)."""
        return kernel_path(n_layers * self.subdivisions + 1, self)


@dataclass(frozen=True)
class _Problem:
    """The discretised roll: grid, per-node self-state of the groups, law knots."""

    r: FloatArray  # node radii [m]
    dlog: FloatArray  # ln(r[e+1]/r[e]) per element
    gnode: NDArray[np.int64]  # first node of each group, plus the last node
    Fself: FloatArray  # F = r sigma_r of each node's group alone [N/m]
    stself: FloatArray  # sigma_theta of each node's layer at winding (= WOT) [Pa]
    wot_layer: FloatArray  # WOT per layer [Pa]
    layer_of_node: NDArray[np.int64]
    kp: FloatArray
    ke: FloatArray
    E_theta: float
    c: float  # core condition F_x = c F at r_c
    floor: float
    n_layers: int


def _check_inputs(web: Web, core: Core, outer_radius: float, tension: TensionSchedule) -> None:
    if not isinstance(web, Web):
        raise InputError(f"expected a Web, got {type(web).__name__}", "web")
    if not isinstance(core, Core):
        raise InputError(f"expected a Core, got {type(core).__name__}", "core")
    if not isinstance(tension, TensionSchedule):
        raise InputError(f"expected a TensionSchedule, got {type(tension).__name__}", "winding")
    if isinstance(outer_radius, bool) or not isinstance(outer_radius, float | int | np.floating):
        raise InputError(f"must be a number in m, got {outer_radius!r}", "winding.outer_radius")
    if not math.isfinite(outer_radius):
        raise InputError(f"must be finite, got {outer_radius}", "winding.outer_radius")
    if not (web.thickness > 0 and math.isfinite(web.thickness)):
        raise InputError(f"must be positive, got {web.thickness}", "web.thickness")
    if outer_radius < core.outer_radius + web.thickness * (1 - 1e-9):
        raise InputError(
            f"must exceed the core radius ({core.outer_radius:g} m) by at least one web "
            f"thickness ({web.thickness:g} m), got {outer_radius:g} m",
            "winding.outer_radius",
        )


def build_problem(
    web: Web, core: Core, outer_radius: float, tension: TensionSchedule, options: WindingOptions
) -> _Problem:
    """Grid, wound-on tensions and law knots for :func:`wind` (vectorised, no solve)."""
    _check_inputs(web, core, outer_radius, tension)
    h = web.thickness
    rc = core.outer_radius
    n = int(round((outer_radius - rc) / h))
    ns = options.subdivisions
    if n * ns + 1 > _MAX_NODES:
        raise InputError(
            f"{n} layers x {ns} subdivisions is more than {_MAX_NODES} nodes",
            "winding.outer_radius",
        )
    R = rc + n * h
    s = rc + h * np.arange(n)  # inner radius of each layer = roll radius when it is wound
    T = np.asarray(tension.wound_on_tension(s, rc, R, h), dtype=float)
    if not np.all(np.isfinite(T)) or np.any(T < 0):
        raise InputError("wound-on tension must be finite and >= 0 at every radius", "winding")
    n_nodes = n * ns + 1
    i = np.arange(n_nodes)
    r = rc + h * (i / ns)
    lay = np.minimum(i // ns, n - 1)
    L = options.layers_per_increment
    first = np.arange(0, n, L)  # first layer of each group
    gnode = np.append(first * ns, n_nodes - 1).astype(np.int64)
    # suffix sums of T h within each group: C[j] = sum_{j' >= j in j's group} T_j' h
    grp = np.arange(n) // L
    Th = T * h
    csum = np.cumsum(Th[::-1])[::-1]  # sum_{j' >= j}
    grp_end = np.minimum((grp + 1) * L, n)  # first layer after j's group
    after = np.append(csum, 0.0)[grp_end]
    C = csum - after
    frac = (r - s[lay]) / h  # position inside the node's layer (1 only at the outer surface)
    Fself = -(C[lay] - Th[lay] * frac)
    stself = T[lay]
    law = web.radial_modulus
    p_max = max(float(np.sum(Th)) / rc, 1.0) * 1.01  # |F| increments decay inward: P <= sum/rc
    kp, ke = law.tabulate(p_max)
    kp = np.ascontiguousarray(kp, dtype=float)
    ke = np.ascontiguousarray(ke, dtype=float)
    if kp.size < 2:
        raise InputError("radial modulus law needs at least two knots", "web.radial_modulus")
    c = (0.0 if core.rigid else web.E_theta / core.stiffness) + web.nu_theta_r
    return _Problem(
        r=r,
        dlog=np.log(r[1:] / r[:-1]),
        gnode=gnode,
        Fself=Fself,
        stself=stself,
        wot_layer=T,
        layer_of_node=lay,
        kp=kp,
        ke=ke,
        E_theta=web.E_theta,
        c=c,
        floor=options.modulus_floor * web.E_theta,
        n_layers=n,
    )


def _result(
    prob: _Problem,
    F: FloatArray,
    st: FloatArray,
    web: Web,
    core: Core,
    tension: TensionSchedule,
    options: WindingOptions,
    stats: dict[str, Any],
) -> WindingResult:
    r = prob.r
    sr = F / r
    if options.new_layer == "laid_on":
        sr[-1] = 0.0
    E = np.maximum(np.interp(-sr, prob.kp, prob.ke), prob.floor)
    beyond = -sr > prob.kp[-1]
    if np.any(beyond):
        slope = (prob.ke[-1] - prob.ke[-2]) / (prob.kp[-1] - prob.kp[-2])
        E = np.where(beyond, prob.ke[-1] + slope * (-sr - prob.kp[-1]), E)
    if not (np.all(np.isfinite(sr)) and np.all(np.isfinite(st))):
        raise ConvergenceError("the winding solve produced non-finite stresses")
    inputs = {
        "web": {
            "thickness_m": web.thickness,
            "width_m": web.width,
            "E_theta_Pa": web.E_theta,
            "nu_theta_r": web.nu_theta_r,
            "radial_modulus": web.radial_modulus.to_dict(),
        },
        "core": {
            "radius_m": core.outer_radius,
            "stiffness_Pa": None if core.rigid else core.stiffness,
        },
        "tension": {
            "web_stress_Pa": tension.web_stress,
            "taper": tension.taper.kind,
            "taper_fraction": tension.taper.fraction,
            "nip_load_N_per_m": tension.nip_load,
            "friction": tension.friction,
        },
        "outer_radius_m": float(r[-1]),
    }
    return WindingResult(
        radius=r.copy(),
        sigma_r=sr,
        sigma_theta=st.copy(),
        E_r=E,
        wot=prob.wot_layer[prob.layer_of_node],
        core_pressure=float(-sr[0]),
        n_layers=prob.n_layers,
        inputs=inputs,
        options=options.to_dict(),
        stats=stats,
    )


def _numpy_work(n_nodes: int, options: WindingOptions) -> float:
    """The NumPy kernels' work: nodes x load substeps x window size (Python loops over the
    window) relative to the default window (8 layers); inf for ``window_layers=None``
    (O(N^2), a check: always compiled)."""
    if options.window_layers is None:
        return math.inf
    window = max(options.window_layers, 2 * options.flush_interval * options.layers_per_increment)
    return n_nodes * options.load_substeps * max(window / 8.0, 1.0)


def kernel_path(n_nodes: int, options: WindingOptions) -> str:
    """Which kernels :func:`wind` runs a roll of ``n_nodes`` with (decided without loading
    them): ``"numpy"`` (a small roll), ``"compiled"`` (built first on a machine that has not
    built them yet) or ``"compiled if built, else numpy"`` (in between: no one-off build for
    a small roll). :mod:`woundroll.limits` estimates the winding's time by it."""
    work = _numpy_work(n_nodes, options)
    if work <= _NUMPY_MAX_NODES:
        return "numpy"
    return "compiled" if work > _BUILD_MIN_NODES else "compiled if built, else numpy"


def _kernels_for(n_nodes: int, options: WindingOptions) -> Any:
    """The kernels for a roll of ``n_nodes`` (:func:`kernel_path`): NumPy for a small roll,
    else numba's machine code loaded without numba (:mod:`woundroll.winding._kernels_aot`,
    ~0.1 s), else numba's dispatcher (if llvmlite cannot load the code here)."""
    from woundroll.winding import _kernels_numpy

    path = kernel_path(n_nodes, options)
    if path == "numpy":
        return _kernels_numpy  # no load cost (docs/winding.md)
    from woundroll.winding import _kernels_aot

    aot = _kernels_aot.load(build=path == "compiled")
    if aot is not None:
        return aot
    if path != "compiled":
        return _kernels_numpy
    from woundroll.winding import _kernels

    return _kernels


def wind(
    web: Web,
    core: Core,
    outer_radius: float,
    tension: TensionSchedule,
    *,
    options: WindingOptions | None = None,
    progress: Callable[[float], None] | None = None,
) -> WindingResult:
    """Wind a roll from ``core`` to ``outer_radius`` and return the stresses in it.

    Parameters
    ----------
    web : Web
        Thickness h [m], E_theta [Pa], radial-modulus law E_r(sigma_r) [Pa] ({2}), nu_theta_r.
    core : Core
        Core radius [m] and stiffness E_c [Pa] (inf: rigid).
    outer_radius : float [m]
        Final radius; the roll holds ``round((outer_radius - r_c) / h)`` whole layers.
    tension : TensionSchedule
        Wound-on tension WOT(r) [Pa] (web tension, taper, nip-induced mu N / h).
    options : WindingOptions, optional
        Numerical options; the defaults are converged (docs/winding.md).
    progress : callable(float), optional
        Called with the fraction done (0..1) as the roll grows.

    Returns
    -------
    WindingResult

    Raises
    ------
    InputError
        Bad input, with the dotted field name.
    ConvergenceError
        The fixed-point iteration for E_r did not converge in an increment.
    """
    options = options if options is not None else WindingOptions()
    if not isinstance(options, WindingOptions):
        raise InputError(f"expected WindingOptions, got {type(options).__name__}", "options")
    prob = build_problem(web, core, outer_radius, tension, options)
    nn = prob.r.size
    K = _kernels_for(nn, options)
    ws = _Workspace.for_problem(prob, options)
    n_groups = prob.gnode.size - 1
    n_chunks = 1 if progress is None else min(n_groups, 50)
    bounds = np.linspace(0, n_groups, n_chunks + 1).round().astype(np.int64)
    for g0, g1 in zip(bounds[:-1], bounds[1:], strict=True):
        failed = ws.run_groups(K, prob, options, int(g0), int(g1))
        if failed >= 0:
            raise ConvergenceError(
                f"E_r fixed-point iteration did not reach rtol={options.rtol:g} in "
                f"{options.max_iterations} iterations at layer "
                f"{failed * options.layers_per_increment} of {prob.n_layers}"
            )
        if progress is not None:
            progress(float(g1) / n_groups)
    K.flush_all(_MAX_LEVELS, ws.B, ws.S, prob.r, ws.F, ws.st, ws.alpha, ws.beta, prob.c)
    stats = {
        "increments": int(n_groups),
        "max_iterations_used": int(ws.state_i[2]),
        "nodes": int(nn),
        "element_evaluations_window": int(ws.state_i[3]),
        "element_evaluations_refresh": int(ws.state_i[4]),
    }
    return _result(prob, ws.F, ws.st, web, core, tension, options, stats)


@dataclass
class _Workspace:
    """The kernels' state between calls: F and sigma_theta per node, the Riccati
    coefficients, the elements' refresh history, the increment's work arrays, the lazy
    deep part's level boundaries ``B`` and pending increments ``S``, and ``state_i``
    (:func:`woundroll.winding._kernels.run_groups`)."""

    F: FloatArray
    st: FloatArray
    alpha: FloatArray
    beta: FloatArray
    hist: FloatArray
    thist: NDArray[np.int64]
    invr: FloatArray
    invd: FloatArray
    dF: FloatArray
    dFold: FloatArray
    w: float
    iterate: bool
    w_deep: float
    wnodes: int
    state_i: NDArray[np.int64]
    B: NDArray[np.int64]
    S: FloatArray

    @classmethod
    def for_problem(cls, prob: _Problem, options: WindingOptions) -> _Workspace:
        nn = prob.r.size
        alpha = np.zeros(max(nn - 1, 1))
        w = _MODES[options.modulus_update]
        # a frozen deep element stands for the moduli of every (sub)step of its period: the
        # rule evaluates substep j of nsub at fraction (j - 1 + w) / nsub of the increment
        nsub = options.load_substeps
        if options.window_layers is None:
            wnodes = -1
        else:
            # the window must hold the groups added since the last flush
            wl = max(
                options.window_layers, 2 * options.flush_interval * options.layers_per_increment
            )
            wnodes = wl * options.subdivisions
        state_i = np.zeros(7, dtype=np.int64)
        state_i[5] = -1  # no increment iterated yet (warm start, _kernels.run_groups)
        return cls(
            F=np.zeros(nn),
            st=np.zeros(nn),
            alpha=alpha,
            beta=np.zeros_like(alpha),
            hist=np.zeros((alpha.size, 2)),  # pressure of each element at its last two refreshes
            thist=np.full((alpha.size, 2), -1, dtype=np.int64),  # and when (-1: none)
            invr=1.0 / prob.r,
            invd=1.0 / prob.dlog if nn > 1 else np.ones(1),
            dF=np.zeros(nn),
            dFold=np.zeros(nn),
            w=w,
            iterate=options.modulus_update != "explicit",
            w_deep=((nsub - 1) / 2 + w) / nsub,
            wnodes=wnodes,
            state_i=state_i,
            B=np.zeros(_MAX_LEVELS + 1, dtype=np.int64),  # level boundaries (elements)
            S=np.zeros(_MAX_LEVELS + 1),  # pending increment at the top of each level
        )

    def run_groups(self, K: Any, prob: _Problem, options: WindingOptions, g0: int, g1: int) -> int:
        """Wind groups g0..g1-1 with the kernels ``K``: -1, or the group that failed."""
        return K.run_groups(
            g0, g1, prob.gnode, prob.r, self.invr, prob.dlog, self.invd, self.F, self.st,
            prob.Fself, prob.stself, self.alpha, self.beta, self.hist, self.thist, self.dF,
            self.dFold, prob.kp, prob.ke, prob.E_theta, prob.c, prob.floor, self.w,
            self.iterate, self.w_deep, options.rtol, options.max_iterations, self.wnodes,
            options.flush_interval, options.load_substeps, options.new_layer == "elastic",
            self.B, self.S, self.state_i,
        )  # fmt: skip


def wind_reference(
    web: Web,
    core: Core,
    outer_radius: float,
    tension: TensionSchedule,
    *,
    options: WindingOptions | None = None,
) -> WindingResult:
    """Straightforward per-increment banded solve (NumPy + ``scipy.linalg.solve_banded``).

    Same discretisation and E_r rule as :func:`wind` but no lazy deep part (every element's
    modulus is refreshed every increment) and no compiled code: a reference for tests and
    ``benchmarks/bench_winding.py``. ``options.window_layers``/``flush_interval`` are ignored.
    """
    options = options if options is not None else WindingOptions()
    prob = build_problem(web, core, outer_radius, tension, options)
    r = prob.r
    nn = r.size
    F = np.zeros(nn)
    st = np.zeros(nn)
    max_it = 0
    elastic = options.new_layer == "elastic"
    for g in range(prob.gnode.size - 1):
        m, top = int(prob.gnode[g]), int(prob.gnode[g + 1])
        dtop = prob.Fself[m]
        n = top if elastic else m  # the node the group's load acts on
        for _sub in range(options.load_substeps if n > 0 and dtop != 0.0 else 0):
            dsub = dtop / options.load_substeps
            its = _reference_substep(prob, options, F, st, n, dsub, g)
            max_it = max(max_it, its)
        if not elastic:
            F[m : top + 1] = prob.Fself[m : top + 1]
        st[m : top + 1] = prob.stself[m : top + 1]
    stats = {
        "increments": int(prob.gnode.size - 1),
        "max_iterations_used": max_it,
        "nodes": int(nn),
    }
    return _result(prob, F, st, web, core, tension, options, stats)


def _reference_moduli(prob: _Problem, P: FloatArray) -> FloatArray:
    """E_r at the pressures P: the law's knots, extrapolated linearly, floored."""
    E = np.interp(P, prob.kp, prob.ke)
    slope = (prob.ke[-1] - prob.ke[-2]) / (prob.kp[-1] - prob.kp[-2])
    E = np.where(P > prob.kp[-1], prob.ke[-1] + slope * (P - prob.kp[-1]), E)
    return np.maximum(E, prob.floor)


def _reference_pq(g: FloatArray, d: FloatArray) -> tuple[FloatArray, FloatArray]:
    """The element relation's coefficients (the exact power-law solution; series for
    small k d)."""
    k = np.sqrt(g)
    x = k * d
    small = x < 0.1
    x2 = x * x
    em = np.exp(-np.where(small, 1.0, x))
    e2 = em * em
    p = np.where(
        small, (1 + x2 * (1 / 3 + x2 * (-1 / 45 + x2 * 2 / 945))) / d, k * (1 + e2) / (1 - e2)
    )
    q = np.where(
        small, (1 + x2 * (-1 / 6 + x2 * (7 / 360 - x2 * 31 / 15120))) / d, 2 * k * em / (1 - e2)
    )
    return p, q


def _reference_substep(
    prob: _Problem,
    options: WindingOptions,
    F: FloatArray,
    st: FloatArray,
    n: int,
    dsub: float,
    g: int,
) -> int:
    """One load step ``dsub`` at node ``n``: the E_r fixed point on the whole roll below
    it (banded solve per iteration), then F and sigma_theta updated in place. Returns the
    iterations the fixed point used (0 when it stopped by the iteration rule)."""
    from scipy.linalg import solve_banded

    r, dlog, c = prob.r, prob.dlog, prob.c
    w = _MODES[options.modulus_update]
    max_it = 0
    P0 = -F[: n + 1] / r[: n + 1]
    P0e = 0.5 * (P0[:-1] + P0[1:])
    d_old: FloatArray | None = None
    d_full = np.zeros(n + 1)
    for it in range(options.max_iterations + 1):
        if it == 0:
            Pe = P0e
        else:
            dP = -d_full / r[: n + 1]
            Pe = P0e + w * 0.5 * (dP[:-1] + dP[1:])
        p, q = _reference_pq(prob.E_theta / _reference_moduli(prob, Pe), dlog[:n])
        # unknowns dF_0..dF_{n-1}; node i: q_{i-1} dF_{i-1} - (p_{i-1} + p_i) dF_i
        # + q_i dF_{i+1} = 0, node 0: -(p_0 + c) dF_0 + q_0 dF_1 = 0
        ab = np.zeros((3, n))
        ab[1, :] = -(p + np.concatenate(([c], p[:-1])))
        ab[0, 1:] = q[:-1]
        ab[2, :-1] = q[:-1]
        rhs = np.zeros(n)
        rhs[-1] = -q[-1] * dsub
        d_full = np.append(solve_banded((1, 1), ab, rhs), dsub)
        if options.modulus_update == "explicit":
            break
        if d_old is not None:
            if np.max(np.abs(d_full - d_old)) <= options.rtol * abs(dsub):
                max_it = it
                break
            if it == options.max_iterations:
                raise ConvergenceError(f"E_r iteration did not converge in group {g}")
        d_old = d_full
    flux = np.empty(n)
    flux[0] = c * d_full[0]
    flux[1:] = p[:-1] * d_full[1:n] - q[:-1] * d_full[: n - 1]
    F[:n] += d_full[:n]
    st[:n] += flux / r[:n]
    F[n] += dsub
    return max_it
