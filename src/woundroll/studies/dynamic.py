"""Figures 6-10 and 14-15 against the dynamic model: the impact in time on the FE roll
(:mod:`woundroll.contact.dynamic.plane_strain`, the role of the paper's ABAQUS/Explicit model)
beside the 1.5D FD and energy models, on the seven Table 2 rolls and the calibration block.

Per roll: Rho, impulse, peak time and contact time of the dynamic FE impact and of the FD
model; the energy model's Rho; the FE's coefficient of restitution and the energy it leaves
in the roll; the tapered-column active mass {14}-{18} the FD model uses, and the active mass
the FE roll *shows*: the m_r with which the FD model (same quasi-static spring {3}, plastic
collision) reads the FE's Rho
(:func:`woundroll.contact.dynamic.plane_strain.matching_active_mass`). A case can hand that mass to
the FD model with ``[tester] active_mass``.

The calibration block (Table 1: E = 44.6 MPa, nu = 0.458, 1.4 g/cm^3; thickness 2.54 cm,
an assumption) is the FE "roll" of an isotropic, linear elastic material 2.54 cm thick on a
rigid core of 1 m radius (a block on a rigid table, curvature 1/1 m against the head's
1/6.6 mm): the device manual's 77 Rho, the paper's ABAQUS 76.1 Rho.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from woundroll.errors import InputError
from woundroll.studies._common import (
    TABLE2,
    Progress,
    SummaryTable,
    _map,
    _prefix,
    _savefig,
    _write,
)
from woundroll.studies.tension import MANUAL_IMPULSE_NS

#: The paper's 3D ABAQUS reading on the calibration block and the device manual's [Rho].
BLOCK_ABAQUS_RHO = 76.1
BLOCK_MANUAL_RHO = 77.0


def _peak_time(time: Any, decel: Any, start: float) -> float:
    return float(time[int(np.argmax(decel))] - start)


def _measure_roll(name: str, overrides: tuple[str, ...], model: str = "2d") -> dict[str, Any]:
    """One Table 2 roll through the pipeline with ``contact.dynamic = true`` on the 2D or
    the 3D FE roll; in 2D also the impact with E_r frozen (no update, Figure 8) on the
    same FE roll, against the FD model on the frozen roll's spring."""
    from dataclasses import replace

    from woundroll.case import load_case
    from woundroll.contact.dynamic.plane_strain import impact_dynamic, matching_active_mass
    from woundroll.instruments import RollSpring
    from woundroll.pipeline import run

    no_update = model == "2d"
    case = load_case(
        name,
        [
            "contact.dynamic=true",
            f"contact.no_update={str(no_update).lower()}",
            f"contact.model='{model}'",
            *overrides,
        ],
    )
    res = run(case)
    assert res.hardness is not None and res.contact is not None and res.dynamic is not None
    web = case.web.build()
    fd, en, dy = res.hardness.fd, res.hardness.energy, res.dynamic
    inst = res.hardness.instrument
    spring = RollSpring.quadratic(res.contact.alpha, res.contact.beta)
    m_fe = matching_active_mass(inst, spring, dy.rho)
    frozen: dict[str, Any] = dict.fromkeys(_NO_UPDATE_KEYS, math.nan)
    if no_update and res.no_update is not None:
        nu = res.no_update
        d0 = impact_dynamic(
            web,
            case.core.build(),
            res.winding.radius,
            res.winding.sigma_r,
            inst,
            contact_time=nu.hardness.fd.contact_time,
            depth_scale=float(nu.stiffness.contact.delta[-1]),
            options=replace(case.contact.dynamic_settings(), update_modulus=False),
        )
        frozen = {
            "rho_dynamic_no_update": d0.rho,
            "rho_fd_no_update": nu.hardness.fd.rho,
            "impulse_dynamic_no_update_N_s": d0.impulse,
            "restitution_dynamic_no_update": d0.restitution,
        }
    return {
        "case": name if model == "2d" else f"{name} (3D)",
        "model": model,
        "material": case.web.preset or "",
        "tension_N": case.winding.schedule(web).web_stress * web.width * web.thickness,
        **_comparison(dy, fd, en),
        **frozen,
        "active_mass_column_kg": res.hardness.effective_mass,
        "active_mass_fe_kg": m_fe,
        **_histories(dy, fd),
    }


#: The no-update columns (2D rows; NaN where not run).
_NO_UPDATE_KEYS = (
    "rho_dynamic_no_update",
    "rho_fd_no_update",
    "impulse_dynamic_no_update_N_s",
    "restitution_dynamic_no_update",
)


def _comparison(dy: Any, fd: Any, en: Any) -> dict[str, Any]:
    """The columns every row compares: FE in time against the FD {4}-{13} and energy
    {19}-{22} models on the same roll spring."""
    return {
        "rho_dynamic": dy.rho,
        "rho_fd": fd.rho,
        "rho_energy": en.rho,
        "impulse_dynamic_N_s": dy.impulse,
        "impulse_fd_N_s": fd.impulse,
        "peak_time_dynamic_s": dy.peak_time,
        "peak_time_fd_s": _peak_time(fd.time, fd.deceleration, fd.contact_start),
        "contact_time_dynamic_s": dy.contact_time,
        "contact_time_fd_s": fd.contact_time,
        "impact_depth_dynamic_m": dy.max_depth,
        "impact_depth_fd_m": fd.max_depth,
        "restitution_dynamic": dy.restitution,
        "energy_in_J": dy.energy_in,
        "energy_left_in_roll_J": dy.energy_roll_left,
        "energy_loss_numerical_J": dy.energy_contact_loss,
    }


def _histories(dy: Any, fd: Any) -> dict[str, Any]:
    """Peak pressure, step, cost and the histories behind Figures 6 and 10."""
    return {
        "peak_pressure_dynamic_Pa": float(np.max(dy.axis_pressure)),
        "time_step_s": dy.time_step,
        "solve_time_dynamic_s": dy.solve_time_s,
        "history": {
            "time_from_contact_s": [float(t - dy.contact_start) for t in dy.time],
            "deceleration_m_per_s2": [float(a) for a in dy.deceleration],
            "fd_time_from_contact_s": [float(t - fd.contact_start) for t in fd.time],
            "fd_deceleration_m_per_s2": [float(a) for a in fd.deceleration],
            "axis_depth_m": [float(x) for x in dy.axis_depth],
            "axis_pressure_Pa": [float(x) for x in dy.axis_pressure],
        },
    }


def block_roll(instrument: str = "rho-meter", model: str = "2d") -> tuple[Any, Any, Any, Any]:
    """The calibration block as an FE roll for ``model``: ``(web, core, radius, sigma_r)``
    (:func:`woundroll.contact.block.block_roll`: isotropic, every modulus from Table 1's E
    and nu, on a rigid table; in 3D the instrument file's block width, an assumption)."""
    from woundroll.contact.block import block_roll as roll_of_block
    from woundroll.instruments.calibration import CalibrationBlock

    return roll_of_block(CalibrationBlock.from_preset(instrument), model)


def _measure_block(_: str, overrides: tuple[str, ...], model: str = "2d") -> dict[str, Any]:
    """The calibration block: FE dynamic (2D, or 3D as wide as the instrument file's block),
    and the FD/energy models on the FE's quasi-static curve and on the calibrated
    Hertz curve (docs/instruments.md, section 6)."""
    from woundroll.contact import roll_stiffness
    from woundroll.contact.dynamic.plane_strain import impact_dynamic
    from woundroll.contact.dynamic.solid3d import impact_dynamic3d
    from woundroll.instruments import (
        RollSpring,
        TabulatedLaw,
        get_instrument,
        impact_energy,
        impact_fd,
    )
    from woundroll.instruments.calibration import CalibrationBlock, HertzLineContact

    inst = get_instrument("rho-meter")
    web, core, r, s = block_roll(model=model)
    st = roll_stiffness(web, core, r, s, inst, model=model)
    c = st.contact
    curve = TabulatedLaw(c.delta, c.force)
    fd = impact_fd(inst, RollSpring(curve, 0.0))
    en = impact_energy(inst, curve)
    dyn = impact_dynamic if model == "2d" else impact_dynamic3d
    dy = dyn(
        web,
        core,
        r,
        s,
        inst,
        contact_time=fd.contact_time,
        depth_scale=float(c.delta[-1]),
    )
    hertz = HertzLineContact(
        inst.head_radius, float(inst.head_length), CalibrationBlock.from_preset("rho-meter")
    )
    fd_h = impact_fd(inst, RollSpring(hertz.law(dy.energy_in), 0.0))
    return {
        "case": "calibration block" if model == "2d" else "calibration block (3D)",
        "model": model,
        "material": "block",
        "tension_N": math.nan,
        **_comparison(dy, fd, en),
        **dict.fromkeys(_NO_UPDATE_KEYS, math.nan),
        "rho_fd_hertz": fd_h.rho,
        "active_mass_column_kg": 0.0,
        "active_mass_fe_kg": math.nan,
        **_histories(dy, fd),
    }


def _num(v: float, fmt: str) -> str:
    return "-" if not math.isfinite(v) else fmt.format(v)


_COLUMNS = (
    ("case", "roll", str),
    ("rho_dynamic", "Rho FE dyn", lambda v: f"{v:.1f}"),
    ("rho_fd", "Rho FD", lambda v: f"{v:.1f}"),
    ("rho_energy", "Rho energy", lambda v: f"{v:.1f}"),
    ("impulse_dynamic_N_s", "impulse FE [N s]", lambda v: f"{v:.3f}"),
    ("impulse_fd_N_s", "impulse FD [N s]", lambda v: f"{v:.3f}"),
    ("peak_time_dynamic_s", "peak FE [ms]", lambda v: f"{v * 1e3:.2f}"),
    ("peak_time_fd_s", "peak FD [ms]", lambda v: f"{v * 1e3:.2f}"),
    ("restitution_dynamic", "e FE", lambda v: f"{v:.2f}"),
    ("rho_dynamic_no_update", "Rho FE dyn no upd", lambda v: _num(v, "{:.1f}")),
    ("rho_fd_no_update", "Rho FD no upd", lambda v: _num(v, "{:.1f}")),
    ("restitution_dynamic_no_update", "e FE no upd", lambda v: _num(v, "{:.2f}")),
    ("active_mass_column_kg", "m_r {18} [g]", lambda v: f"{v * 1e3:.1f}"),
    (
        "active_mass_fe_kg",
        "m_r FE [g]",
        lambda v: "-" if not math.isfinite(v) else f"{v * 1e3:.1f}",
    ),
)


@dataclass(frozen=True)
class DynamicStudy:
    """The dynamic FE impact against the 1.5D models (module docstring).

    Attributes
    ----------
    rolls : list of dict
        One row per roll (SI, unit in the key), the calibration block last; ``history``
        holds the deceleration histories and the pressure under the head at the peak.
    """

    rolls: list[dict[str, Any]]
    name: str = "dynamic"

    def to_dict(self) -> dict[str, Any]:
        return {
            "study": self.name,
            "figures": "reference paper, Figures 6-10 and 14-15 (dynamic FE against 1.5D)",
            "manual_impulse_N_s": MANUAL_IMPULSE_NS,
            "block_manual_rho": BLOCK_MANUAL_RHO,
            "block_abaqus_rho": BLOCK_ABAQUS_RHO,
            "rolls": [
                {
                    k: (None if isinstance(v, float) and not math.isfinite(v) else v)
                    for k, v in r.items()
                }
                for r in self.rolls
            ],
        }

    def summary(self) -> list[SummaryTable]:
        header = tuple(t for _, t, _ in _COLUMNS)
        rows = [tuple(f(r[k]) for k, _, f in _COLUMNS) for r in self.rolls]
        return [SummaryTable("Dynamic FE impact against the 1.5D models", header, rows)]

    def notes(self) -> list[str]:
        notes = [
            "FE dyn: the FE roll hit in time (contact.dynamic): 2D plane strain, or the 3D "
            "quarter model for rows marked (3D) (the 1.5D models then use the 3D spring); "
            "FD: {4}-{13} with the tapered-column mass {18} (plastic collision); energy: "
            "{19}-{22}. No upd: E_r frozen at its pre-impact value (Figure 8), 2D rows.",
            "m_r FE: the active mass with which the FD model reads the FE's Rho "
            "([tester] active_mass hands it to the FD model); '-': none does.",
            f"Device manual impulse {MANUAL_IMPULSE_NS} N s; calibration block: manual "
            f"{BLOCK_MANUAL_RHO:.0f} Rho, paper's 3D ABAQUS {BLOCK_ABAQUS_RHO} Rho.",
        ]
        blk = [r for r in self.rolls if r["material"] == "block"]
        if blk:
            notes.append(
                f"Block, FD on the calibrated Hertz curve: {blk[0]['rho_fd_hertz']:.1f} Rho; "
                f"FD on the FE block's quasi-static curve: {blk[0]['rho_fd']:.1f} Rho."
            )
        return notes

    def plot(self, prefix: str | Path) -> list[Path]:
        """``dynamic_rho.png`` (Rho and impulse per roll, the three models), and
        ``dynamic_histories.png`` (deceleration against time, FE solid, FD dashed; pressure
        under the head at the peak, cf. Figures 6, 10 and 12)."""
        from matplotlib.figure import Figure

        base = _prefix(prefix, "dynamic")
        rho_unit = 3.76 * 9.81
        names = [r["case"] for r in self.rolls]
        x = np.arange(len(names))
        fig = Figure(figsize=(10.0, 4.4), layout="constrained")
        ax, ax2 = fig.subplots(1, 2)
        for dx, key, lab in (
            (-0.25, "rho_dynamic", "FE dynamic"),
            (0.0, "rho_fd", "FD"),
            (0.25, "rho_energy", "energy"),
        ):
            ax.bar(x + dx, [r[key] for r in self.rolls], width=0.25, label=lab)
        ax.axhline(BLOCK_MANUAL_RHO, color="k", ls=":", lw=0.8, label="block: manual 77")
        ax.set_xticks(x, names, rotation=45, ha="right", fontsize=8)
        ax.set_ylabel("Rho [-]")
        ax.legend(fontsize=8)
        ax.grid(alpha=0.3, axis="y")
        for dx, key, lab in (
            (-0.2, "impulse_dynamic_N_s", "FE dynamic"),
            (0.2, "impulse_fd_N_s", "FD"),
        ):
            ax2.bar(x + dx, [r[key] for r in self.rolls], width=0.4, label=lab)
        ax2.axhline(MANUAL_IMPULSE_NS, color="k", ls="--", label="device manual 0.267 N s")
        ax2.set_xticks(x, names, rotation=45, ha="right", fontsize=8)
        ax2.set_ylabel("impulse [N s]")
        ax2.legend(fontsize=8)
        ax2.grid(alpha=0.3, axis="y")
        paths = [_savefig(fig, Path(f"{base}_rho.png"))]

        fig = Figure(figsize=(10.0, 4.4), layout="constrained")
        ax, ax2 = fig.subplots(1, 2)
        for i, r in enumerate(self.rolls):
            h = r["history"]
            col = f"C{i % 10}"
            ax.plot(
                np.asarray(h["time_from_contact_s"]) * 1e3,
                np.asarray(h["deceleration_m_per_s2"]) / rho_unit,
                color=col,
                lw=1.5,
                label=r["case"],
            )
            ax.plot(
                np.asarray(h["fd_time_from_contact_s"]) * 1e3,
                np.asarray(h["fd_deceleration_m_per_s2"]) / rho_unit,
                color=col,
                lw=1.0,
                ls="--",
            )
            d = np.asarray(h["axis_depth_m"])
            keep = d <= 0.02
            ax2.semilogy(
                d[keep] * 1e3, np.maximum(np.asarray(h["axis_pressure_Pa"])[keep], 1.0), color=col
            )
        ax.set_xlabel("time from contact [ms]")
        ax.set_ylabel("deceleration [Rho] (FE solid, FD dashed)")
        ax.legend(fontsize=7)
        ax.grid(alpha=0.3)
        ax2.set_xlabel("depth below the surface [mm]")
        ax2.set_ylabel("radial pressure at peak deceleration [Pa]")
        ax2.grid(alpha=0.3, which="both")
        paths.append(_savefig(fig, Path(f"{base}_histories.png")))
        return paths

    def write(self, out_dir: str | Path) -> list[Path]:
        """Write ``study.json`` and the PNGs into ``out_dir``; return the paths."""
        return _write(self, out_dir)


def dynamic_study(
    cases: Iterable[str] = TABLE2,
    progress: Progress | None = None,
    *,
    block: bool = True,
    overrides: tuple[str, ...] = (),
    workers: int = 1,
    cases3d: Iterable[str] = (),
    block3d: bool = False,
) -> DynamicStudy:
    """Run the dynamic FE impact beside the 1.5D models on ``cases`` (and the block).

    Parameters
    ----------
    cases : iterable of str
        Bundled case names or case files (default: the seven Table 2 rolls).
    block : bool
        Add the calibration block.
    overrides : tuple of str
        ``dotted.key=value`` applied to every case (e.g.
        ``"contact.dynamic_options.steps_per_contact=200"``).
    workers : int
    cases3d, block3d
        Rolls (and the block) also run on the 3D FE roll (a 3D quasi-static solve and a 3D
        dynamic impact each: minutes per row, docs/dynamic.md).
    """
    names = list(cases)
    names3d = list(cases3d)
    if not names and not block and not names3d and not block3d:
        raise InputError("no cases given", "study.cases")
    ov = tuple(overrides)
    jobs: list[tuple[Any, ...]] = [("_measure_roll", n, ov, "2d") for n in names]
    labels = list(names)
    if block:
        jobs.append(("_measure_block", "block", ov, "2d"))
        labels.append("calibration block")
    jobs += [("_measure_roll", n, ov, "3d") for n in names3d]
    labels += [f"{n} (3D)" for n in names3d]
    if block3d:
        jobs.append(("_measure_block", "block", ov, "3d"))
        labels.append("calibration block (3D)")
    out = _map(
        _dispatch,
        jobs,
        workers=workers,
        progress=progress,
        label=lambda i: f"dynamic: {labels[i]}",
    )
    return DynamicStudy(out)


def _dispatch(
    fn_name: str, name: str, overrides: tuple[str, ...], model: str = "2d"
) -> dict[str, Any]:
    fn = {"_measure_roll": _measure_roll, "_measure_block": _measure_block}[fn_name]
    return fn(name, overrides, model)


#: The rows the registry's study also runs in 3D (cost: docs/dynamic.md).
CASES_3D = ("pet1-26.7N",)


def run(progress: Progress | None = None, *, workers: int = 1) -> DynamicStudy:
    """The registry's entry: :func:`dynamic_study` on the Table 2 rolls and the block in
    2D, and :data:`CASES_3D` and the block in 3D."""
    return dynamic_study(progress=progress, workers=workers, cases3d=CASES_3D, block3d=True)
