"""The headline lines of a run's result, as (label, formatted value) rows: the CLI's summary
table, the report's and the web page's headline read them from here."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from woundroll.pipeline.results import RunResult


def _num(x: float, spec: str) -> str:
    """``format(x, spec)`` without a minus sign on a value that rounds to zero ("-0.0 kPa"
    at zero tension is a rounding artefact, not a tensile pressure)."""
    text = format(x, spec)
    if text.startswith("-") and not any(c in "123456789" for c in text.split("e")[0]):
        text = text[1:]
    return text


Rows = list[tuple[str, str]]


def _winding_rows(w: Any) -> Rows:
    rows = [
        ("layers", f"{w.n_layers}"),
        ("outer radius", f"{_num(w.radius[-1] * 100, '.3f')} cm"),
        ("core pressure", f"{_num(w.core_pressure / 1e3, '.1f')} kPa"),
        ("max pressure", f"{_num(-w.sigma_r.min() / 1e3, '.1f')} kPa"),
    ]
    st = w.storage or {}
    if "storage_time_s" in st:  # storage time (creep): the wound-in value beside it
        days = f"{st['storage_time_s'] / 86400:.4g} d"
        rows[2] = (f"core pressure after {days} storage", rows[2][1])
        rows.insert(
            2,
            ("core pressure as wound", f"{_num(st['core_pressure_before_Pa'] / 1e3, '.1f')} kPa"),
        )
    return rows


def _hardness_rows(result: RunResult) -> Rows:
    d = result.hardness.to_dict()
    model = d.get("roll_model") or (c.model if (c := result.contact) else "")
    shown = _num(d["reading"], ".1f")
    if d["saturated"]:
        shown += f" (saturated: the model reads {d['reading_model']:.1f}, off the scale)"
    return [
        (f"{d['readout']} reading ({d['instrument']}, roll model {model})", shown),
        (
            "Rho (finite difference / energy)",
            f"{_num(d['rho_fd'], '.1f')} / {_num(d['rho_energy'], '.1f')}",
        ),
        ("impulse", f"{_num(d['impulse_N_s'], '.4f')} N s"),
        ("max depth", f"{_num(d['impact_depth_m'] * 1e3, '.3f')} mm"),
        ("contact time", f"{_num(d['contact_time_s'] * 1e3, '.2f')} ms"),
    ]


def _contact_rows(c: Any) -> Rows:
    return [
        ("roll spring alpha", f"{_num(c.alpha, '.4g')} N/m^2"),
        ("roll spring beta", f"{_num(c.beta, '.4g')} N/m"),
        ("roll spring extrapolated", "yes" if c.extrapolated else "no"),
        ("semi-contact width at max depth", f"{_num(c.semi_contact_width * 1e3, '.3f')} mm"),
    ]


def _no_update_rows(nu: Any) -> Rows:
    d = nu.to_dict()
    both = f"{_num(d['rho_fd'], '.1f')} / {_num(d['rho_energy'], '.1f')}"
    return [("Rho, no E_r update (FD / energy)", both)]


def _dynamic_rows(dy: Any) -> Rows:
    return [
        ("Rho, FE impact in time", f"{_num(dy.rho, '.1f')}"),
        (
            "impulse / contact time (FE)",
            f"{_num(dy.impulse, '.4f')} N s / {_num(dy.contact_time * 1e3, '.2f')} ms",
        ),
        ("restitution (FE, elastic material)", f"{_num(dy.restitution, '.3f')}"),
    ]


def _profile_stats_rows(st: Any) -> Rows:
    if st is None:
        return [("Rho statistics", "fewer than two readings on the scale")]
    return [
        ("Rho mean / SD (on the scale)", f"{_num(st.mean, '.1f')} / {_num(st.sd, '.1f')}"),
        ("Rho CoV", f"{_num(100 * st.cov, '.1f')} % ({st.band})"),
        (
            "Rho min / max / peak-to-peak",
            f"{_num(st.min, '.1f')} / {_num(st.max, '.1f')} / {_num(st.peak_to_peak, '.1f')}",
        ),
    ]


def _comparison_rows(c: Any) -> Rows:
    ms = c.measured_stats
    r = "n/a" if c.correlation is None else f"{_num(c.correlation, '.2f')}"
    return [
        (
            "measured Rho mean / CoV",
            f"{_num(ms.mean, '.1f')} / {_num(100 * ms.cov, '.1f')} % ({ms.band})",
        ),
        ("predicted - measured: bias / RMS", f"{_num(c.bias, '+.1f')} / {_num(c.rms, '.1f')}"),
        ("RMS after bias / correlation", f"{_num(c.rms_shape, '.1f')} / {r}"),
    ]


def _profile_rows(p: Any) -> Rows:
    th = p.thickness_stats
    rows: Rows = [
        ("CMD sectors", f"{p.z.size}"),
        ("roll model / reading", f"{p.roll_model} / FD (energy model beside it)"),
        (
            "thickness mean / CoV",
            f"{_num(th.mean * 1e6, '.2f')} um / {_num(100 * th.cov, '.2f')} %",
        ),
    ]
    n_sat = int(p.saturated.sum())
    if n_sat:
        rows.append(("saturated sectors (off the scale, excluded)", f"{n_sat}"))
    rows += _profile_stats_rows(p.rho_stats)
    n_slack = int(p.slack.sum())
    if n_slack:
        rows.append(("slack sectors (reading set by the E_r floor)", f"{n_slack}"))
    if p.comparison is not None:
        rows += _comparison_rows(p.comparison)
    return rows


def result_summary(result: RunResult) -> Rows:
    """Headline numbers of a run, as (label, formatted value) rows: winding, reading, roll
    spring, no-update and FE readings when solved, and the CMD profile's statistics."""
    rows: Rows = []
    if result.winding is not None:
        rows += _winding_rows(result.winding)
    if result.hardness is not None:
        rows += _hardness_rows(result)
    if result.contact is not None:
        rows += _contact_rows(result.contact)
    if result.no_update is not None:
        rows += _no_update_rows(result.no_update)
    if getattr(result, "dynamic", None) is not None:
        rows += _dynamic_rows(result.dynamic)
    if result.profile is not None:
        rows += _profile_rows(result.profile)
    return rows
