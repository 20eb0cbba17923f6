"""Generators of the checks in docs/contact.md's later sections (the 3D model's
verification, refinement and linear solver; the layered roll's verification and cost; the
other explanations; the layered roll in 3D) (docs/scripts/regenerate.py runs them).

The checks are the tests' own problems, loaded with ``records.test_module``:
tests/contact/test_contact3d.py (moduli, element, mass, frozen modulus, the Rho-meter on
PET2 26.7 N), test_layered.py and test_layered_plates.py (the 2D layered rows),
test_layered3d.py (the coarse PET1 roll and the nine-sheet slab). Live (about 30 CPU s in
all): those checks, the default shells, two plane-strain pipeline runs, the stored 3D
references' solver statistics. Measured records (docs/scripts/records.py,
``MEASUREMENTS``): ``contact_checks.layers3d``, the layers-per-shell refinement in 3D
(about 70 CPU s), ``contact_checks.refine3d``, the 3D mesh refinement of the slow tests
(a 3D solve of 20-45 CPU s per refinement), and ``contact_checks.layered_cost``, the
layered and plane-strain runs of benchmarks/bench_layered.py in yardsticks (about 1.5 CPU
min).
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable
from functools import cache
from typing import Any

os.environ.setdefault("MKL_NUM_THREADS", "1")  # PARDISO threads only contend under load

import records  # noqa: E402  (docs/scripts is on the path of regenerate.py and records.py)
from records import Measurement, Run  # noqa: E402

#: the runs' nominal case: the tests' problems define their own rolls (not hashed), so the
#: records go stale on the models' defaults only; their code is spot-checked
NOMINAL = "pet1-26.7N"


def _layered3d() -> Any:
    return records.test_module("contact/test_layered3d.py")


def _stamp(name: str) -> str:
    """ "measured YYYY-MM-DD by `docs/scripts/records.py contact_checks.NAME`"."""
    rec = records.load(f"contact_checks.{name}")
    return f"measured {rec['measured']} by `docs/scripts/records.py contact_checks.{name}`"


def _sci(x: float, digits: int = 1) -> str:
    """A small relative difference as 4e-16 (``digits`` significant), or "0" when equal."""
    if x == 0:
        return "0"
    m, e = f"{x:.{digits - 1}e}".split("e")
    return f"{m}e{int(e)}"


def _order(f: list[float]) -> float:
    """Observed order of a sequence refined by 2 each time (coarse to fine)."""
    return math.log2(abs(f[0] - f[1]) / abs(f[1] - f[2]))


# =======================================================================================
# the layered roll in 3D: verification (tests/contact/test_layered3d.py)


def uncut3d() -> str:
    """No interfaces: the doubled numbering's stiffness against the 3D assembler (inline)."""
    import numpy as np

    from woundroll.contact.layered.roll3d import Layered3DOptions, _LayeredRoll3D, layered_mesh3d
    from woundroll.contact.solid3d.fem import orthotropic_moduli
    from woundroll.contact.solid3d.solver import Contact3DOptions, Roll3D

    t = _layered3d()
    r, s = t.pet_profile()
    base = Contact3DOptions(n_fine=4, locality_cut=True, **t.GROW)
    lopts = Layered3DOptions(base=base, layered_depth=1e-3, layers_per_shell=5)
    mesh, cut, _, _ = layered_mesh3d(t.PET1, t.RIGID, t.R_OUT, t.SPHERE, 3e-4, lopts)
    plain = Roll3D(t.PET1, t.RIGID, r, s, mesh, base)
    uncut = _LayeredRoll3D(t.PET1, t.RIGID, r, s, mesh, base, cut[:0], 1.0)
    D = orthotropic_moduli(t.PET1, t.PET1.E_r(plain.sigma_pre))
    Kp, Ku = plain.asm.matrix(D), uncut.asm.matrix(D)
    rel = float(abs(Kp - Ku).max() / abs(Kp).max())
    same = bool(np.array_equal(plain.sr, uncut.sr))
    text = "equal to the last bit" if rel == 0 else f"largest difference {_sci(rel)}"
    return text + ("" if same else " (the pre-impact stresses differ)")


@cache
def _sphere(mu: float, interfaces: bool = True, gap_tol: float | None = None) -> float:
    """The test's sphere on the coarse PET1 roll (test_layered3d.py's ``pet_roll``)."""
    t = _layered3d()
    return float(t.pet_roll(mu, t.SPHERE, interfaces=interfaces, gap_tol=gap_tol))


@cache
def _stick() -> dict[str, float]:
    """mu = 1e6 against the continuum on the same mesh, at two gap tolerances."""
    out: dict[str, float] = {}
    for key, gap in (("tight", 1e-6), ("default", None)):
        stuck = _sphere(1.0, interfaces=False, gap_tol=gap)
        out[key] = abs(_sphere(1e6, gap_tol=gap) / stuck - 1)
    return out


def stick3d() -> str:
    """The mu = 1e6 row's measured cell (inline)."""
    d = _stick()
    return (
        f"{_sci(d['tight'], 2)} with the head's gap tolerance at 1e-6 of the first step "
        f"({_sci(d['default'])} at the 3D model's 1e-3)"
    )


def slip3d() -> str:
    """The sphere at mu 0.1 (test_slip_runs_along_the_force_and_z_matters, whose checks are
    inline there: the same criteria here): the slipping pairs, how far their forces are
    from the rim and from the slip direction, the force against the stuck roll (inline)."""
    import numpy as np

    t = _layered3d()
    st: list[Any] = []
    f = float(t.pet_roll(0.1, t.SPHERE, state=st))
    x = st[0]
    w, T = x.slip_increment, x.shear
    nw, nT = np.hypot(w[:, 0], w[:, 1]), np.hypot(T[:, 0], T[:, 1])
    outside = float(np.max(nT / np.maximum(x.limit, 1e-300)) - 1)
    slip = nw > 1e-6 * np.max(nw)
    along_z = int(np.sum(slip & (np.abs(w[:, 1]) > 2 * np.abs(w[:, 0]))))
    along_t = int(np.sum(slip & (np.abs(w[:, 0]) > 2 * np.abs(w[:, 1]))))
    big = nw > 1e-2 * np.max(nw)
    rim = float(np.max(np.abs(nT[big] / x.limit[big] - 1)))
    cos = np.einsum("ij,ij->i", T[big], w[big]) / (nT[big] * nw[big])
    angle = float(np.max(np.arccos(np.clip(cos, -1.0, 1.0))))
    inside = "every force inside its disc"
    if outside > 1e-9:
        inside = f"forces up to {outside:.1e} outside their discs"
    return (
        f"{int(np.sum(slip))} of {nw.size} pairs slip ({along_z} mostly in z, {along_t} mostly "
        f"in theta); {inside}; slipping forces on the rim to {_sci(rim)}, along the slip to "
        f"{_sci(angle)} rad; F = {f / _sphere(1.0, interfaces=False):.3f} x stuck"
    )


@cache
def _plates() -> dict[str, float]:
    t = _layered3d()
    stuck, free = t.slab(1.0, interfaces=False), t.slab(1e-6)
    k_stuck, k_free = t.beam_stiffness(t.EI_STICK), t.beam_stiffness(t.EI_SLIP)
    return {
        "stuck": stuck / k_stuck - 1,
        "free": free / k_free - 1,
        "ratio": stuck / free,
        "closed": (t.EI_STICK / t.EI_SLIP) ** 0.25,
    }


def plates3d() -> str:
    """The nine-sheet slab's row: stuck, frictionless against the beam closed forms, the
    ratio (inline)."""
    p = _plates()
    miss = [abs(p["stuck"]), abs(p["free"]), abs(p["ratio"] / p["closed"] - 1)]
    note = " (beyond the test's 2 %: its slab's mesh grading)" if max(miss) > 0.02 else ""
    return (
        f"{100 * p['stuck']:+.1f} %, {100 * p['free']:+.1f} %, {p['ratio']:.3f} vs "
        f"{p['closed']:.3f}{note}"
    )


# ------------------------------------------------------------- layers per shell (record)

#: the slow test's problem (test_layered3d.py, test_layers_per_shell_refinement_converges,
#: inline there): the Rho-meter-sized cylinder on the coarse PET1 roll, a 1.2 mm zone,
#: mu 0.3, three increments
LPS_HEAD = ("cylinder", 0.00635, 0.0254)
LPS_ZONE_M, LPS_MU, LPS_STEPS = 1.2e-3, 0.3, 3
LPS = (4, 2, 1)


def _lps_runs() -> list[Run]:
    return [Run(f"{n} layers per shell", NOMINAL, (), (("layers_per_shell", n),)) for n in LPS]


def _lps_measure(run: Run) -> dict[str, Any]:
    from woundroll.contact.heads import Head

    t = _layered3d()
    st: list[Any] = []
    f = t.pet_roll(
        LPS_MU,
        Head(*LPS_HEAD),
        layers_per_shell=int(run.param("layers_per_shell")),
        layered_depth=LPS_ZONE_M,
        n_steps=LPS_STEPS,
        state=st,
    )
    return {"force_N": float(f), "shells": float(st[0].n_shells), "_passes": float(st[0].passes)}


def _lps() -> list[dict[str, Any]]:
    rec = records.results("contact_checks.layers3d")
    return [rec[f"{n} layers per shell"] for n in LPS]


@cache
def _lps_2d() -> list[float]:
    """The 2D slow test's layers per shell, 4/2/1 on 8 layers (test_layered.py)."""
    from woundroll.contact.layered.solver import ContactOptions, LayeredOptions

    t = records.test_module("contact/test_layered.py")
    return [
        t.run(
            0.3,
            LayeredOptions(
                base=ContactOptions(newton=False, n_steps=4),
                layered_depth=8 * t.H,
                layers_per_shell=k,
            ),
        )
        for k in LPS
    ]


def _lumping() -> tuple[float, float, float, float]:
    """3D: two and four sheets a shell against one; 2D: two against one, its order."""
    f = [r["force_N"] for r in _lps()]
    g = _lps_2d()
    return f[1] / f[2] - 1, f[0] / f[2] - 1, g[1] / g[2] - 1, _order(g)


def lps3d_row() -> str:
    """The layers-per-shell row's measured cell (inline; record layers3d, 2D live)."""
    f = [r["force_N"] for r in _lps()]
    two, four, two_2d, order_2d = _lumping()
    return (
        " / ".join(f"{x:.1f}" for x in f)
        + f" N: lumping 2 sheets {100 * two:+.1f} %, 4 sheets {100 * four:+.0f} %, observed "
        f"order {_order(f):.2f} (2D: {100 * two_2d:+.1f} % and {order_2d:.2f}; "
        f"{_stamp('layers3d')})"
    )


def lumping3d() -> str:
    """Two sheets a shell in 3D against 2D (inline)."""
    two, _, two_2d, _ = _lumping()
    return f"{100 * two:+.1f} % for two sheets against {100 * two_2d:+.1f} %"


def admm_passes() -> str:
    """The ADMM passes of the one-sheet run of the layers-per-shell record (inline)."""
    r = records.results("contact_checks.layers3d")["1 layers per shell"]
    return (
        f"{r['_passes']:.0f} over the {LPS_STEPS} increments of the coarse PET1 test roll "
        f"under the cylinder of the layers-per-shell row, one sheet per shell"
    )


# ----------------------------------------------------------------- the default shells


def layers_default() -> str:
    """The default layers per shell of both layered models (inline, case-files.md)."""
    from woundroll.contact.layered.roll3d import LAYERS_PER_SHELL_3D
    from woundroll.contact.layered.solver import LayeredOptions

    return (
        f'{LayeredOptions().layers_per_shell} in `"layered"`; {LAYERS_PER_SHELL_3D} in '
        f'`"layered-3d"` (unset in Python, `layers_per_shell=None`: the 3D model\'s outer '
        f"element ring in whole layers)"
    )


def layers3d_default() -> str:
    """The layered-3d model's default layers per shell (inline)."""
    from woundroll.contact.layered.roll3d import LAYERS_PER_SHELL_3D

    return f"{LAYERS_PER_SHELL_3D}"


def default_shells() -> str:
    """Layers in the 3D model's surface ring on the default mesh, the Table 2 rolls and pile
    heights (inline; the layered-3d shells of ``layers_per_shell=None``): the bundled
    Rho-meter head, solved to 1.25 x the 3D model's impact depth (the stored 3D references,
    tests/contact/data/contact3d_reference.json)."""
    import json

    from woundroll.case import load_case
    from woundroll.contact.heads import Head
    from woundroll.contact.layered.roll3d import Layered3DOptions, layered_mesh3d
    from woundroll.instruments import get_instrument

    ref = json.loads((records.ROOT / "tests/contact/data/contact3d_reference.json").read_text())
    head = Head.from_instrument(get_instrument("rho-meter"))
    n, d = [], []
    for c in ref["cases"].values():
        c3 = c["3d"]
        case = load_case(c3["case"], c3["overrides"])
        depth = 1.25 * c3["delta_max_m"]
        _, _, _, k = layered_mesh3d(
            case.web.build(), case.core.build(), c3["outer_radius_m"], head, depth,
            Layered3DOptions(layers_per_shell=None),
        )  # fmt: skip
        n.append(k)
        d.append(1e3 * depth)
    span = f"{min(n)}-{max(n)}" if min(n) != max(n) else f"{n[0]}"
    return (
        f"{span} layers (solved to {min(d):.2f}-{max(d):.2f} mm, 1.25 x the 3D "
        f"model's impact depths on the Table 2 rolls and pile heights, with the bundled "
        f"{1e3 * head.radius:.2f} mm head)"
    )


def coarse3d() -> str:
    """The layered study's coarse 3D mesh, ``COARSE_3D`` (inline)."""
    from woundroll.studies.layered import COARSE_3D

    opts = dict(o.removeprefix("contact.options3d.").split("=", 1) for o in COARSE_3D)
    growth = {k: v for k, v in opts.items() if k.endswith("_growth")}
    rest = [f"`{k}` {v}" for k, v in opts.items() if k not in growth]
    if len(growth) == 3 and len(set(growth.values())) == 1:
        head = [f"growths {next(iter(growth.values()))}"]
    else:
        head = [f"`{k}` {v}" for k, v in growth.items()]
    return ", ".join(head + rest)


# =======================================================================================
# the layered roll (2D): the verification rows the tests assert without a number shown


def _layered2d() -> Any:
    return records.test_module("contact/test_layered.py")


@cache
def _slipping2d() -> tuple[float, Any]:
    """The 5-sheet PET1 test roll at mu 0.3 (test_layered.py's ``slipping`` fixture)."""
    t = _layered2d()
    st: list[Any] = []
    return t.run(0.3, t.small(), st), st[0]


def coulomb2d() -> str:
    """Coulomb's law and the closed interfaces on the 5-sheet roll (inline)."""
    import numpy as np

    _, st = _slipping2d()
    slip = st.slip > 0
    worst = float(np.max(np.abs(st.shear) / st.limit))
    bound = f"1 - {_sci(1 - worst)}" if worst < 1 else f"1 + {_sci(worst - 1)}"
    if worst == 1:
        bound = "1 (slipping pairs on the limit to the last bit)"
    return (
        f"{int(np.sum(slip))} of {st.slip.size} pairs slip; largest \\|tau\\| / mu P = "
        f"{bound}; P {np.min(st.pressure) / 1e3:.0f} kPa to "
        f"{np.max(st.pressure) / 1e6:.0f} MPa"
    )


def softens2d() -> str:
    """The force at mu 0.05 and 0.3 against the continuum on the 5-sheet roll (inline)."""
    t = _layered2d()
    f05 = t.run(0.05, t.small())
    f3, _ = _slipping2d()
    cont = t.run(0.3, t.small(interfaces=False))
    return f"{f05:.2f} < {f3:.2f} < {cont:.2f} N"


def onset2d() -> str:
    """The slip onset of the three-sheet strip (test_layered_plates.py's ``slip_onset``)
    (inline)."""
    import numpy as np

    r = records.test_module("contact/test_layered_plates.py").slip_onset()
    stuck = r["stuck"][0]
    (f_high, high), (f_low, low) = r["high"], r["low"]
    n_high, n_low = int(np.sum(high.slip > 0)), int(np.sum(low.slip > 0))
    d = abs(f_high / stuck - 1)
    same = "equal to the stuck force" if d == 0 else f"the stuck force to {_sci(d)}"
    return (
        f"q = {r['q']:.3g}; at 1.5 q {n_high} pairs slip, {same}; at q/3 {n_low} pairs "
        f"slip, {f_low / stuck:.3f} x stuck"
    )


@cache
def _partial() -> dict[str, Any]:
    return records.test_module("contact/test_layered_partial_slip.py").comparison()


def partial_slip2d() -> str:
    """The two-sheet strip beyond onset against the derived partial-slip solution
    (test_layered_partial_slip.py's ``comparison``): a table at every other increment."""
    import numpy as np

    c = _partial()
    rows = [
        "| load / onset load | slip zone c (derived) [mm] | derived P [N/m] | model [N/m] "
        "| model - derived | softening by friction, model / derived |",
        "|---|---|---|---|---|---|",
    ]
    for k in [0, *range(1, len(c["depth"]), 2)]:
        ex = c["exact"][k]
        rows.append(
            f"| {c['load_ratio'][k]:.2f} | {ex.c * 1e3:.2f} | {ex.P:.4f} | {c['force'][k]:.4f} "
            f"| {c['rel'][k]:+.2%} | {c['softening'][k]:.4f} |"
        )
    rel = c["rel"]
    soft = np.abs(c["softening"] - 1)
    rows.append("")
    rows.append(
        f"Over all {len(c['depth'])} increments the model is {rel.min():+.2%} to "
        f"{rel.max():+.2%} above the derived force (the stuck strip's own offset against "
        f"Hetenyi, the first row); the friction's softening agrees to {soft.max():.2%}. At "
        f"the deepest press the outermost slipping pair is at {c['edge'] * 1e3:.2f} mm "
        f"against c = {c['exact'][-1].c * 1e3:.2f} mm, the largest slip "
        f"{c['slip_max']:.4g} m against {c['slip_max_exact']:.4g} m "
        f"({c['slip_max'] / c['slip_max_exact'] - 1:+.2%}); the head raises the interface "
        f"pressure over the slip zone by {c['head_share']:.1e} of p0 on average."
    )
    return "\n".join(rows)


def _against_derived(c: dict[str, Any], offset: str) -> str:
    """A verification cell: the load reached, the force's spread against the derived
    solution (``offset``: what it is), the softening's largest difference."""
    import numpy as np

    return (
        f"to {c['load_ratio'][-1]:.1f} x onset: force {c['rel'].min():+.2%} to "
        f"{c['rel'].max():+.2%} ({offset}), "
        f"friction's softening to {np.abs(c['softening'] - 1).max():.2%}"
    )


def partial_slip_row() -> str:
    """The verification table's cell (inline)."""
    c = _partial()
    return (
        _against_derived(c, "the stuck strip's offset")
        + f", slip zone {c['edge'] * 1e3:.2f} vs {c['exact'][-1].c * 1e3:.2f} mm"
    )


@cache
def _partial3d() -> dict[str, Any]:
    return records.test_module("contact/test_layered_partial_slip.py").comparison3d()


def partial_slip3d_row() -> str:
    """The 3D verification table's partial-slip cell (inline, ~5 CPU s)."""
    c = _partial3d()
    return _against_derived(c, f"the stuck slab {c['stuck_rel'][-1]:+.2%} against Hetenyi")


# =======================================================================================
# other explanations: how much E_r grows under the head


@cache
def _er_growth(case_name: str) -> float:
    """Median E_r(pre + contact) / E_r(pre) at the impact depth over the elements carrying
    at least a tenth of the peak contact-induced radial stress (plane strain, defaults)."""
    import numpy as np

    import woundroll

    case = woundroll.load_case(case_name)
    res = woundroll.run(case)
    c = res.contact.contact
    web = case.web.build()
    st = c.at_depth(res.hardness.to_dict()["impact_depth_m"])
    pre = c.sigma_r_pre
    f = web.E_r(pre + st.sigma_r) / web.E_r(pre)
    loaded = np.abs(st.sigma_r) >= 0.1 * np.abs(st.sigma_r).max()
    return float(np.median(f[loaded]))


def er_growth() -> str:
    """The factor E_r grows under the head on the readings' rolls (inline)."""
    a, b = _er_growth("pet2-53.4N"), _er_growth("pet1-26.7N")
    lo, hi = sorted((a, b))
    return (
        f"{lo:.0f}-{hi:.0f} here (PET2 53.4 N {a:.0f}, PET1 26.7 N {b:.0f}: the median over "
        "the elements that carry at least a tenth of the peak contact stress at the impact "
        "depth, plane strain)"
    )


# =======================================================================================
# the 3D model's verification (tests/contact/test_contact3d.py's problems)


def moduli3d() -> str:
    """The orthotropic moduli against the inverted compliance (inline)."""
    from woundroll.contact.solid3d.fem import D_PAIRS

    D, C, _ = _contact3d_tests().moduli_and_inverse()
    err = max(abs(v / C[p, q] - 1) for (p, q), v in zip(D_PAIRS[:6], D[:6], strict=True))
    return "equal to the last bit" if err == 0 else f"largest relative difference {_sci(err)}"


def null_space3d() -> str:
    """Zero eigenvalues of the thin and the fat brick, and the smallest nonzero one (inline)."""
    import numpy as np

    t = _contact3d_tests()
    parts = []
    for dr, label in ((1e-4, "thin"), (1e-2, "fat")):
        K = t.element_matrix(dr)
        ev = np.sort(np.abs(np.linalg.eigvalsh(K) / np.abs(K).max()))
        zero = int(np.sum(ev < 1e-10))
        parts.append(f"{label}: {zero} at most {_sci(ev[zero - 1])}, the next {_sci(ev[zero])}")
    return "; ".join(parts)


def mass3d() -> str:
    """The quarter's lumped mass against the closed form (inline)."""
    total, exact = _contact3d_tests().quarter_mass()
    err = abs(total / exact - 1)
    return "equal to the last bit" if err == 0 else f"relative difference {_sci(err)}"


def slip_emulation3d() -> str:
    """The reduced-shear slip on the test's sphere: no slip at mu 1e9, softer at 0.3
    (inline)."""
    import numpy as np

    plain, sticky, slipping = _contact3d_tests().reduced_shear_runs()
    d = float(np.max(np.abs(sticky.force[1:] / plain.force[1:] - 1)))
    same = "to the last bit" if d == 0 else f"to {_sci(d)}"
    n = slipping.stats["slipped_elements"]
    return (
        f"with a friction so large that nothing slips the curve equals the no-slip curve "
        f"{same}; with mu = 0.3 {n} elements slip and the force at "
        f"{1e3 * plain.delta[-1]:.1f} mm is {slipping.force[-1] / plain.force[-1]:.2f} x "
        "the no-slip one"
    )


def frozen3d() -> str:
    """E_r frozen against updated, and the frozen run's factorisations (inline)."""
    up, frozen = _contact3d_tests().updated_and_frozen()
    n = frozen.stats["factorisations"]
    return (
        f"frozen = {frozen.force[-1] / up.force[-1]:.2f} x updated at "
        f"{1e3 * up.delta[-1]:.1f} mm; {n} factorisation{'s' if n != 1 else ''}"
    )


# =======================================================================================
# the 3D linear solver: right-hand sides per factorisation, the anisotropy


def _reference3d() -> dict[str, Any]:
    import json

    path = records.ROOT / "tests/contact/data/contact3d_reference.json"
    return dict(json.loads(path.read_text())["cases"])


def solves_per_factorisation() -> str:
    """Right-hand sides solved per factorisation in the stored 3D references (inline)."""
    q = [c["3d"]["stats"]["rhs_solved"] / c["3d"]["stats"]["factorisations"]
         for c in _reference3d().values()]  # fmt: skip
    return (
        f"{min(q):.0f}-{max(q):.0f} per factorisation on average in the ten stored 3D "
        "references of the fast path below"
    )


def anisotropy3d() -> str:
    """E_theta / E_r of the Table 2 webs at zero pressure (the surface) (inline)."""
    from woundroll.case import load_case

    q = {}
    for name in ("pet1-26.7N", "pet2-53.4N"):
        web = load_case(name).web.build()
        q[name[:4].upper()] = float(web.E_theta / web.E_r(0.0))
    return (
        "E_theta / E_r up to "
        + " and ".join(f"{v:,.0f} ({k})" for k, v in q.items())
        + " at the surface (where the wound-in pressure vanishes)"
    )


# =======================================================================================
# the 3D model's mesh refinement (tests/contact/test_contact3d.py's slow tests, record)

REFINED = ("radial_growth", "tangential_growth", "axial_growth", "axial_size", "n_steps", "n_fine")
#: the depths the slow test compares F(d) at, as fractions of its depth_max 2.1 mm
REF_FRACTIONS = tuple(0.2 + 0.1 * k for k in range(9))


def _contact3d_tests() -> Any:
    return records.test_module("contact/test_contact3d.py")


def _refine_runs() -> list[Run]:
    return [Run(name, "pet2-26.7N", (), (("refined", name),)) for name in ("default", *REFINED)]


def _refine_measure(run: Run) -> dict[str, Any]:
    import numpy as np

    from woundroll.contact.solid3d.solver import Contact3DOptions

    t = _contact3d_tests()
    name = run.param("refined")
    opts = Contact3DOptions() if name == "default" else t._refined(Contact3DOptions(), name)
    res = t._rho_meter_pet2(opts)
    d = np.asarray(REF_FRACTIONS) * 2.1e-3
    out: dict[str, Any] = {
        "force_N": [float(x) for x in np.interp(d, res.delta, res.force)],
        "_dof": float(res.n_dof),
    }
    if name == "default":  # how far E_r moves from the first increment's K to the last
        web = records.test_module("contact/test_real_profiles.py").real_roll("pet2-26.7N")[0]
        sr = res.sigma_r_history
        first, last = (web.E_r(res.sigma_r_pre + sr[k]) for k in (1, -1))
        loaded = np.abs(sr[-1]) >= 0.1 * np.abs(sr[-1]).max()
        out["er_growth_first_to_last"] = float(np.median(last[loaded] / first[loaded]))
    return out


def refinement3d() -> str:
    """The refinement table (record refine3d)."""
    rec = records.results("contact_checks.refine3d")
    base = rec["default"]["force_N"]
    cpu = records.load("contact_checks.refine3d")["cpu_s"]
    lines = [
        "| refined alone | largest change of F(d) over 0.2-1 depth_max | at | at depth_max "
        "| CPU s |",
        "|---|---|---|---|---|",
    ]
    for name in REFINED:
        f = rec[name]["force_N"]
        ch = [x / y - 1 for x, y in zip(f, base, strict=True)]
        k = max(range(len(ch)), key=lambda i: abs(ch[i]))
        lines.append(
            f"| `{name}` | {100 * ch[k]:+.2f} % | {REF_FRACTIONS[k]:.1f} depth_max "
            f"| {100 * ch[-1]:+.2f} % | {cpu[name]:.0f} |"
        )
    lines.append("")
    lines.append(f"The default curve: {cpu['default']:.0f} CPU s; {_stamp('refine3d')}.")
    return "\n".join(lines)


def er_growth3d() -> str:
    """E_r's growth under the head from the first increment to the last (inline; record
    refine3d's default run)."""
    g = records.results("contact_checks.refine3d")["default"]["er_growth_first_to_last"]
    return (
        f"E_r under the head grows {g:.0f}-fold from the first increment to the last (PET2 "
        "26.7 N to 2.1 mm, the median over the elements carrying at least a tenth of the "
        "peak contact stress; record contact_checks.refine3d)"
    )


def refinement_bounds() -> str:
    """The largest change of the default 3D curve from the mesh and from the increments
    (inline; record refine3d)."""
    rec = records.results("contact_checks.refine3d")
    base = rec["default"]["force_N"]

    def worst(name: str) -> float:
        return max(abs(x / y - 1) for x, y in zip(rec[name]["force_N"], base, strict=True))

    mesh = max(worst(n) for n in REFINED if n != "n_steps")
    return (
        f"up to {100 * mesh:.1f} % from the mesh and {100 * worst('n_steps'):.1f} % from "
        "the increments"
    )


# =======================================================================================
# the layered roll's cost (benchmarks/bench_layered.py's rolls, record)

#: benchmarks/bench_layered.py's rolls: (run label, case, overrides)
COST_ROLLS = (
    ("PET1 26.7 N", "pet1-26.7N", ()),
    ("PET2 53.4 N", "pet2-53.4N", ()),
    ("PET2 53.4 N, H 2 cm", "pet2-53.4N", ("winding.outer_radius=0.0645 m",)),
)
COST_MODELS = ("2d", "layered")


def _cost_runs() -> list[Run]:
    return [
        Run(f"{label} {model}", case, (f"contact.model={model}", "contact.friction=0.3", *over))
        for label, case, over in COST_ROLLS
        for model in COST_MODELS
    ]


def _cost_measure(run: Run) -> dict[str, Any]:
    """The whole pipeline run (bench_layered.py's), its wall time against the yardstick
    (benchmarks/yardstick.py ``wind_per_layer``) timed before and after in the same run."""
    import sys
    import time

    from woundroll.case import load_case
    from woundroll.pipeline import run as run_pipeline

    sys.path.insert(0, str(records.ROOT / "benchmarks"))
    from yardstick import wind_per_layer

    yard0 = wind_per_layer()[1]
    t0 = time.perf_counter()
    res = run_pipeline(load_case(run.case, list(run.overrides)))
    wall = time.perf_counter() - t0
    yard1 = wind_per_layer()[1]
    return {
        "rho_fd": float(res.hardness.to_dict()["rho_fd"]),
        "_yardsticks": wall / min(yard0, yard1),
        "_load": round(os.getloadavg()[0], 1),
    }


def layered_cost() -> str:
    """The layered and plane-strain runs in yardsticks (inline; record layered_cost)."""
    rec = records.results("contact_checks.layered_cost")

    def each(model: str, fmt: str) -> str:
        return " / ".join(
            f"{rec[f'{label} {model}']['_yardsticks']:{fmt}}" for label, _, _ in COST_ROLLS
        )

    return (
        f"A layered reading (mu 0.3) costs {each('layered', '.1f')} yardsticks on "
        + " / ".join(label for label, _, _ in COST_ROLLS)
        + f", a plane-strain one {each('2d', '.2f')} ({_stamp('layered_cost')})"
    )


#: Load increments of the layered 3D roll's step refinement (test_layered3d.py step_ladder).
STEPS3D = (4, 8, 16)


def _steps3d_runs() -> list[Run]:
    return [Run(f"{n} increments", NOMINAL, (), (("n_steps", n),)) for n in STEPS3D]


def _steps3d_measure(run: Run) -> dict[str, Any]:
    ((cont, lay),) = _layered3d().step_ladder((int(run.param("n_steps")),))
    return {"continuum_force_N": cont, "layered_force_N": lay}


def steps3d_row() -> str:
    """The load-step refinement row's measured cell (inline; record steps3d)."""
    rec = records.results("contact_checks.steps3d")
    rows = [rec[f"{n} increments"] for n in STEPS3D]
    c = [r["continuum_force_N"] for r in rows]
    lay = [r["layered_force_N"] for r in rows]

    def order(x: list[float]) -> float:
        return math.log2((x[1] - x[0]) / (x[2] - x[1]))

    return (
        f"continuum {' / '.join(f'{x:.1f}' for x in c)} N, layered "
        f"{' / '.join(f'{x:.1f}' for x in lay)} N: observed order {order(c):.2f} and "
        f"{order(lay):.2f}; layered / continuum "
        f"{' / '.join(f'{b / a:.3f}' for a, b in zip(c, lay, strict=True))} "
        f"({_stamp('steps3d')})"
    )


MEASUREMENTS: dict[str, Measurement] = {
    "layers3d": Measurement(
        models=records.LAYERED_SOLID,
        about="the layered 3D roll's layers-per-shell refinement (test_layered3d.py's coarse "
        "PET1 roll, cylinder head, 1.2 mm zone, mu 0.3): 4, 2, 1 layers per shell",
        runs=_lps_runs,
        measure=_lps_measure,
        spot=("4 layers per shell",),
        rtol=1e-3,
        reason="deterministic solves; the ADMM stops at 1e-5 of the displacement increment, "
        "which moves the force by ~1e-5 (the mu = 1e6 row): 0.1 % covers that and platform "
        "rounding, far below the 6-14 % the row reports. The pass count is stored, not "
        "compared (rounding can move it by a pass)",
        cost="12 / 18 / 39 CPU s for 4 / 2 / 1 layers per shell",
    ),
    "steps3d": Measurement(
        models=records.LAYERED_SOLID,
        about="the layered 3D roll's load-step refinement (test_layered3d.py's coarse PET1 "
        "roll, cylinder head, 4 sheets a shell in a 1.2 mm zone, mu 0.3, and its continuum): "
        "4, 8, 16 increments",
        runs=_steps3d_runs,
        measure=_steps3d_measure,
        spot=("4 increments",),
        rtol=1e-3,
        reason="deterministic solves; the ADMM tolerance moves a force by ~1e-5 (as layers3d)",
        cost="about 20 / 35 / 70 CPU s for 4 / 8 / 16 increments (both rolls)",
    ),
    "layered_cost": Measurement(
        models=records.LAYERED,
        about="the whole `woundroll run` with the layered model (mu 0.3) and with plane "
        "strain on benchmarks/bench_layered.py's rolls, in yardsticks timed in the same run",
        runs=_cost_runs,
        measure=_cost_measure,
        spot=("PET1 26.7 N 2d",),
        rtol=1e-3,
        reason="only the reading is compared (the timings are stored, not compared): "
        "deterministic solves whose platform rounding is far below 1e-3",
        cost="a few CPU s the plane-strain runs, 10-20 CPU s the layered ones, two yardsticks each",
    ),
    "refine3d": Measurement(
        models=records.SOLID,
        about="the 3D model's mesh refinement (test_contact3d.py's slow tests: PET2 26.7 N, "
        "Rho-meter head 6.565 mm, 2.1 mm): each mesh parameter refined alone",
        runs=_refine_runs,
        measure=_refine_measure,
        spot=("default",),
        rtol=1e-3,
        reason="deterministic direct solves; the contact iteration stops at 1e-3 of the "
        "first increment's depth in the gaps, which moves F(d) by far less than 0.1 %, a "
        "tenth of the 1 % bar the refinements are held to",
        cost="20-45 CPU s a curve, about 3.5 CPU min the seven",
    ),
}


BLOCKS: dict[str, Callable[[], str]] = {
    "steps3d_row": steps3d_row,
    "moduli3d": moduli3d,
    "null_space3d": null_space3d,
    "mass3d": mass3d,
    "frozen3d": frozen3d,
    "slip_emulation3d": slip_emulation3d,
    "solves_per_factorisation": solves_per_factorisation,
    "anisotropy3d": anisotropy3d,
    "uncut3d": uncut3d,
    "stick3d": stick3d,
    "plates3d": plates3d,
    "slip3d": slip3d,
    "default_shells": default_shells,
    "layers_default": layers_default,
    "layers3d_default": layers3d_default,
    "er_growth": er_growth,
    "coarse3d": coarse3d,
    "coulomb2d": coulomb2d,
    "softens2d": softens2d,
    "onset2d": onset2d,
    "partial_slip2d": partial_slip2d,
    "partial_slip_row": partial_slip_row,
    "partial_slip3d_row": partial_slip3d_row,
    # rendered from the measured records (MEASUREMENTS)
    "lps3d_row": lps3d_row,
    "lumping3d": lumping3d,
    "admm_passes": admm_passes,
    "refinement3d": refinement3d,
    "refinement_bounds": refinement_bounds,
    "er_growth3d": er_growth3d,
    "layered_cost": layered_cost,
}

if __name__ == "__main__":
    import sys

    for name in sys.argv[1:] or list(BLOCKS):
        print(f"--- {name}\n{BLOCKS[name]()}", flush=True)
