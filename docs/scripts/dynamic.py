"""Generators of the dynamic FE impact's numbers in docs/studies.md ("Dynamic") and
docs/dynamic.md (docs/scripts/regenerate.py runs them): the seven Table 2 rolls and the
calibration block hit in time on the 2D FE roll, beside the 1.5D models, on today's presets
(each PET preset carries its typical unloading law) and, for comparison, an elastic stack.
About 16 FE impacts; a few minutes on a quiet machine. The 3D rows (minutes each) are not
regenerated here: ``woundroll study dynamic`` runs them."""

from __future__ import annotations

from collections.abc import Callable
from functools import cache
from typing import Any

ELASTIC = ("web.radial_unloading='elastic'",)


@cache
def _study(overrides: tuple[str, ...] = ()) -> Any:
    from woundroll.studies.dynamic import dynamic_study

    return dynamic_study(overrides=overrides, block=not overrides)


def _rows(overrides: tuple[str, ...] = ()) -> dict[str, dict[str, Any]]:
    return {r["case"]: r for r in _study(overrides).rolls}


def _markdown(result: Any) -> str:
    lines = []
    for _title, header, rows in result.summary():
        lines.append("| " + " | ".join(header) + " |")
        lines.append("|" + "---|" * len(header))
        lines += ["| " + " | ".join(str(c) for c in row) + " |" for row in rows]
    return "\n".join(lines)


def study() -> str:
    """``woundroll study dynamic``'s 2D table (the Table 2 rolls and the block)."""
    return _markdown(_study(()))  # the same cache key as _rows(): one run of the study


def study_elastic() -> str:
    """The same rolls with an elastic stack (``web.radial_unloading = "elastic"``)."""
    return _markdown(_study(ELASTIC))


def _span(values: list[float], fmt: str, unit: str = "") -> str:
    """``lo-hi unit``; ``lo to hi unit`` when a bound has a sign (no "-4--2 %")."""
    lo, hi = min(values), max(values)
    a, b = format(lo, fmt), format(hi, fmt)
    if a == b:
        return f"{a}{unit}"
    return f"{a} to {b}{unit}" if "+" in fmt or lo < 0 else f"{a}-{b}{unit}"


def summary() -> str:
    """The section's short summary: FE against FD, today's presets and an elastic stack."""
    now, el = _rows(), _rows(ELASTIC)
    pet1 = [k for k in now if k.startswith("pet1")]
    pet2 = [k for k in now if k.startswith("pet2")]

    def gap(rows: dict[str, Any], keys: list[str]) -> list[float]:
        return [100 * (rows[k]["rho_dynamic"] / rows[k]["rho_fd"] - 1) for k in keys]

    p1 = now["pet1-26.7N"]
    e1 = el["pet1-26.7N"]
    blk = next(r for r in now.values() if r["material"] == "block")
    return (
        f"With today's presets (a typical unloading law on every PET web) the FE impact reads "
        f"PET1 {_span(gap(now, pet1), '+.0f', ' %')} against the FD model (PET1 26.7 N: "
        f"{p1['rho_dynamic']:.1f} against {p1['rho_fd']:.1f} Rho) and PET2 "
        f"{_span(gap(now, pet2), '+.0f', ' %')}; the striker leaves with e = "
        f"{_span([now[k]['restitution_dynamic'] for k in pet1 + pet2], '.2f')} and an impulse "
        f"of {_span([now[k]['impulse_dynamic_N_s'] for k in pet1 + pet2], '.3f')} N s (FD "
        f"{_span([now[k]['impulse_fd_N_s'] for k in pet1 + pet2], '.3f')}; the device manual's "
        f"0.267). With an elastic stack: PET1 {_span(gap(el, pet1), '+.0f', ' %')} (26.7 N: "
        f"{e1['rho_dynamic']:.1f} against {e1['rho_fd']:.1f}), PET2 "
        f"{_span(gap(el, pet2), '+.0f', ' %')}, e = "
        f"{_span([el[k]['restitution_dynamic'] for k in pet1 + pet2], '.2f')}. The block "
        f"(linear elastic) reads {blk['rho_dynamic']:.1f} Rho in the FE impact against "
        f"{blk['rho_fd']:.1f} for FD on its quasi-static curve, e = "
        f"{blk['restitution_dynamic']:.2f}"
    )


@cache
def _pet1_with(law: tuple[str, ...]) -> Any:
    import woundroll

    case = woundroll.load_case(
        "pet1-26.7N",
        ["contact.dynamic=true", "contact.dynamic_options.steps_per_contact=400", *law],
    )
    return woundroll.run(case)


def unloading() -> str:
    """PET1 26.7 N with a stiff unloading law against the elastic stack."""
    stiff = _pet1_with(("web.radial_unloading={law='pfeiffer', K1='40 kPa', K2=400}",))
    elastic = _pet1_with(ELASTIC)
    d, de = stiff.dynamic, elastic.dynamic
    return (
        f"FE e = {d.restitution:.2f} ({de.restitution:.2f} elastic), impulse {d.impulse:.3f} N s; "
        f"the FD model's e from the stack cycle is {stiff.hardness.restitution:.2f}. The FE "
        f"roll reads {d.rho:.1f} against {de.rho:.1f} Rho elastic"
    )


# ---------------------------------------------------------------- docs/studies.md's prose
# numbers quoted from the two tables above (the same cached study runs: no extra cost); the
# discussion is on the elastic stack (the paper's roll is elastic), the block on the presets


def _keys(rows: dict[str, Any], prefix: str) -> list[str]:
    return [k for k in rows if k.startswith(prefix)]


def _gap(
    rows: dict[str, Any], keys: list[str], a: str = "rho_dynamic", b: str = "rho_fd"
) -> list[float]:
    return [100 * (rows[k][a] / rows[k][b] - 1) for k in keys]


def pet2_agreement() -> str:
    """PET2, elastic stack: FE against FD, and the active masses."""
    el = _rows(ELASTIC)
    k2 = _keys(el, "pet2")
    gaps = [abs(g) for g in _gap(el, k2)]
    col = [1e3 * el[k]["active_mass_column_kg"] for k in k2]
    fe = [1e3 * el[k]["active_mass_fe_kg"] for k in k2]
    return (
        f"agree within {max(gaps):.0f} % in Rho, and the tapered-column mass {{18}} with the "
        f"contact model's a ({_span(col, '.1f', ' g')}) is near what the FE roll shows "
        f"({_span(fe, '.1f', ' g')})"
    )


def pet1_gap() -> str:
    """PET1, elastic stack: FE against FD, the FE's active mass against the column's."""
    el = _rows(ELASTIC)
    k1 = _keys(el, "pet1")
    gaps = [-g for g in _gap(el, k1)]
    col = [1e3 * el[k]["active_mass_column_kg"] for k in k1]
    fe = [1e3 * el[k]["active_mass_fe_kg"] for k in k1]
    return (
        f"the FE reads {_span(gaps, '.0f', ' %')} lower than FD: the FE roll behaves as if "
        f"{_span(fe, '.0f', ' g')} of it moved with the striker, "
        f"{min(fe) / max(col):.1f}-{max(fe) / min(col):.1f} times the column's "
        f"{_span(col, '.1f', ' g')}"
    )


def energy_model() -> str:
    """PET1 26.7 N, elastic stack: the energy model against the FE impact."""
    r = _rows(ELASTIC)["pet1-26.7N"]
    return f"{r['rho_energy']:.1f} vs {r['rho_dynamic']:.1f}"


def impulse() -> str:
    """Elastic stack, the Table 2 rolls: impulse, restitution, the energy budget."""
    el = _rows(ELASTIC)
    ks = _keys(el, "pet")
    imp = [el[k]["impulse_dynamic_N_s"] for k in ks]
    under = [100 * (1 - el[k]["impulse_dynamic_N_s"] / el[k]["impulse_fd_N_s"]) for k in ks]
    e = [el[k]["restitution_dynamic"] for k in ks]
    kept = [100 * (1 - x * x) for x in e]
    loss = [1e3 * el[k]["energy_loss_numerical_J"] for k in ks]
    ein = [1e3 * el[k]["energy_in_J"] for k in ks]
    return (
        f"The FE impulse is {_span(imp, '.3f', ' N s')} for every roll, "
        f"{_span(under, '.0f', ' %')} under the FD model: the roll keeps "
        f"{_span(kept, '.0f', ' %')} of the impact energy when the striker leaves "
        f"(e = {_span(e, '.2f')}; the loss to the numerical damping is "
        f"{_span(loss, '.1f', ' mJ')} of {_span(ein, '.1f', ' mJ')})"
    )


def no_update() -> str:
    """The study's "no upd" columns (E_r frozen, Figure 8), elastic stack."""
    el = _rows(ELASTIC)
    k1, k2 = _keys(el, "pet1"), _keys(el, "pet2")

    def col(keys: list[str], key: str, fmt: str) -> str:
        return _span([el[k][key] for k in keys], fmt)

    above = _gap(el, k1 + k2, "rho_dynamic_no_update", "rho_fd_no_update")
    p = el["pet1-26.7N"]
    return (
        f"e = {col(k1, 'restitution_dynamic_no_update', '.2f')} (PET1) and "
        f"{col(k2, 'restitution_dynamic_no_update', '.2f')} (PET2) with E_r frozen, impulse "
        f"{col(k1, 'impulse_dynamic_no_update_N_s', '.3f')} and "
        f"{col(k2, 'impulse_dynamic_no_update_N_s', '.3f')} N s; the FE reads "
        f"{_span(above, '.0f', ' %')} above the FD model there ({p['rho_dynamic_no_update']:.1f}"
        f" against {p['rho_fd_no_update']:.1f} on PET1 26.7 N"
    )


def peak_ratio() -> str:
    """FE peak time over the FD model's, elastic stack."""
    el = _rows(ELASTIC)
    ks = _keys(el, "pet")
    return _span([el[k]["peak_time_dynamic_s"] / el[k]["peak_time_fd_s"] for k in ks], ".2f")


def block() -> str:
    """The calibration block (2D): FE in time, FD on its quasi-static curve, the Hertz curve."""
    b = next(r for r in _rows().values() if r["material"] == "block")
    return (
        f"The FE block reads {b['rho_dynamic']:.1f} Rho dynamically, {b['rho_fd']:.1f} with "
        f"the FD model on the same block's quasi-static curve (block inertia "
        f"{100 * (b['rho_dynamic'] / b['rho_fd'] - 1):+.1f} %), and {b['rho_fd_hertz']:.1f} on "
        f"the calibrated Hertz curve"
    )


def contact_times() -> str:
    """Contact times, depths and the peak pressure on the axis, elastic stack."""
    el = _rows(ELASTIC)
    k1, k2 = _keys(el, "pet1"), _keys(el, "pet2")

    def ends(keys: list[str], a: str, b: str, scale: float, fmt: str) -> str:
        first, last = el[keys[0]], el[keys[-1]]
        return (
            f"{format(scale * first[a], fmt)} / {format(scale * first[b], fmt)} ({keys[0]}) to "
            f"{format(scale * last[a], fmt)} / {format(scale * last[b], fmt)} ({keys[-1]})"
        )

    def depth(keys: list[str]) -> str:
        fe = [1e3 * el[k]["impact_depth_dynamic_m"] for k in keys]
        fd = [1e3 * el[k]["impact_depth_fd_m"] for k in keys]
        return f"FE {fe[0]:.2f}-{fe[-1]:.2f} mm against FD {fd[0]:.2f}-{fd[-1]:.2f} mm"

    pk = ", ".join(f"{el[k]['peak_pressure_dynamic_Pa'] / 1e6:.1f}" for k in k1)
    pk2 = ", ".join(f"{el[k]['peak_pressure_dynamic_Pa'] / 1e6:.1f}" for k in k2)
    b = next(r for r in _rows().values() if r["material"] == "block")
    ct = ("contact_time_dynamic_s", "contact_time_fd_s", 1e3, ".2f")
    return (
        f"Contact time FE / FD [ms]: {ends(k1, *ct)}, {ends(k2, *ct)}; maximum depth "
        f"{depth(k1)} (PET1), {depth(k2)} (PET2). Largest radial pressure on the contact axis "
        f"at the peak deceleration (Figure 10): {pk} MPa (PET1), {pk2} MPa (PET2), "
        f"{b['peak_pressure_dynamic_Pa'] / 1e6:.1f} MPa in the block"
    )


def default_step() -> str:
    """docs/dynamic.md: PET1 26.7 N on today's presets, the default time step and the
    numerical energy loss of gamma = 0.6."""
    r = _rows()["pet1-26.7N"]
    return (
        f"{r['energy_loss_numerical_J']:.1e} J of {r['energy_in_J']:.4f} J at the default step "
        f"({1e6 * r['time_step_s']:.1f} us on PET1 26.7 N)"
    ).replace("e-0", "e-")


# ---------------------------------------------------------------- docs/dynamic.md's
# verification table: tests/contact/test_dynamic.py's own problem (its pet1 fixture, the
# elastic PET1 26.7 N roll, and its _run), imported from the test module


def _dyn_tests() -> Any:
    """tests/contact/test_dynamic.py as a module (records.test_module)."""
    import records

    return records.test_module("contact/test_dynamic.py")


@cache
def _pet1_fixture() -> Any:
    fn = _dyn_tests().pet1
    for attr in ("__wrapped__", "_fixture_function"):
        if hasattr(fn, attr):
            return getattr(fn, attr)()
    wrapped = getattr(fn, "__pytest_wrapped__", None)
    return (wrapped.obj if wrapped is not None else fn)()


@cache
def _steps_run(steps: int) -> Any:
    return _dyn_tests()._run(_pet1_fixture(), steps_per_contact=steps)


_STEPS = (100, 200, 400, 800)


def massless() -> str:
    """test_massless_roll_matches_the_fd_model_on_the_same_curve."""
    from woundroll.instruments import RollSpring, TabulatedLaw, impact_energy, impact_fd

    web, core, r, s, inst, st = _pet1_fixture()
    c = st.contact
    fd = impact_fd(inst, RollSpring(TabulatedLaw(c.delta, c.force), 0.0))
    en = impact_energy(inst, TabulatedLaw(c.delta, c.force))
    dyn = _dyn_tests()._run(_pet1_fixture(), density=1e-3, steps_per_contact=200)
    return (
        f"Rho {dyn.rho:.2f} vs {fd.rho:.2f} ({100 * abs(dyn.rho / fd.rho - 1):.1f} %), impulse "
        f"{dyn.impulse:.4f} vs {fd.impulse:.4f}, max depth vs the energy model's {{19}}: "
        f"{100 * abs(dyn.max_depth / en.max_depth - 1):.1f} %, e = {dyn.restitution:.3f}"
    )


def budget() -> str:
    """The numerical loss at 100 ... 800 steps (test_energy_balance_and_time_step_convergence)."""
    runs = [_steps_run(n) for n in _STEPS]
    losses = ", ".join(f"{d.energy_contact_loss:.2g}" for d in runs)
    return f"{losses} J at {', '.join(map(str, _STEPS))} steps (of {runs[0].energy_in:.4f} J)"


def steps() -> str:
    """Rho and impulse at 100 ... 800 steps."""
    runs = [_steps_run(n) for n in _STEPS]
    return (
        "Rho "
        + ", ".join(f"{d.rho:.2f}" for d in runs)
        + f" at {', '.join(map(str, _STEPS))} steps; impulse "
        + ", ".join(f"{d.impulse:.4f}" for d in runs)
        + " N s"
    )


def block_check() -> str:
    """test_calibration_block_dynamic_reads_near_the_manual (the study's block row)."""
    b = next(r for r in _rows().values() if r["material"] == "block")
    return (
        f"{b['rho_dynamic']:.1f} Rho dynamic, FD on the FE block's quasi-static curve "
        f"{b['rho_fd']:.1f}, on the calibrated Hertz curve {b['rho_fd_hertz']:.1f}"
    )


BLOCKS: dict[str, Callable[[], str]] = {
    "study": study,
    "study_elastic": study_elastic,
    "summary": summary,
    "unloading": unloading,
    "pet2_agreement": pet2_agreement,
    "pet1_gap": pet1_gap,
    "energy_model": energy_model,
    "impulse": impulse,
    "no_update": no_update,
    "peak_ratio": peak_ratio,
    "block": block,
    "contact_times": contact_times,
    "default_step": default_step,
    "massless": massless,
    "budget": budget,
    "steps": steps,
    "block_check": block_check,
}
