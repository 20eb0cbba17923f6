"""The headline lines of a run's result, as (label, formatted value) rows: the CLI's summary
table, the report's and the web page's headline read them from here."""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from woundroll.pipeline.results import RunResult


def _num(x: float, spec: str) -> str:
    """``format(x, spec)`` without a minus sign on a value that rounds to zero ("-0.0 kPa"
    at zero tension is a rounding artefact, not a tensile pressure)."""
    text = format(x, spec)
    if text.startswith("-") and not any(c in "123456789" for c in text.split("e")[0]):
        text = text[1:]
    return text


def result_summary(result: RunResult) -> list[tuple[str, str]]:
    """Headline numbers of a run, as (label, formatted value) rows."""
    rows: list[tuple[str, str]] = []
    w = result.winding
    if w is not None:
        rows += [
            ("layers", f"{w.n_layers}"),
            ("outer radius", f"{_num(w.radius[-1] * 100, '.3f')} cm"),
            ("core pressure", f"{_num(w.core_pressure / 1e3, '.1f')} kPa"),
            ("max pressure", f"{_num(-w.sigma_r.min() / 1e3, '.1f')} kPa"),
        ]
    h = result.hardness
    if h is not None:
        d = h.to_dict()
        model = d.get("roll_model") or (c.model if (c := result.contact) else "")
        shown = _num(d["reading"], ".1f")
        if d["saturated"]:
            shown += f" (saturated: the model reads {d['reading_model']:.1f}, off the scale)"
        rows += [
            (f"{d['readout']} reading ({d['instrument']}, roll model {model})", shown),
            (
                "Rho (finite difference / energy)",
                f"{_num(d['rho_fd'], '.1f')} / {_num(d['rho_energy'], '.1f')}",
            ),
            ("impulse", f"{_num(d['impulse_N_s'], '.4f')} N s"),
            ("max depth", f"{_num(d['impact_depth_m'] * 1e3, '.3f')} mm"),
            ("contact time", f"{_num(d['contact_time_s'] * 1e3, '.2f')} ms"),
        ]
    c = result.contact
    if c is not None:
        rows += [
            ("roll spring alpha", f"{_num(c.alpha, '.4g')} N/m^2"),
            ("roll spring beta", f"{_num(c.beta, '.4g')} N/m"),
            ("roll spring extrapolated", "yes" if c.extrapolated else "no"),
            ("semi-contact width at max depth", f"{_num(c.semi_contact_width * 1e3, '.3f')} mm"),
        ]
    nu = result.no_update
    if nu is not None:
        d = nu.to_dict()
        rows.append(
            (
                "Rho, no E_r update (FD / energy)",
                f"{_num(d['rho_fd'], '.1f')} / {_num(d['rho_energy'], '.1f')}",
            )
        )
    dy = getattr(result, "dynamic", None)
    if dy is not None:
        rows += [
            ("Rho, FE impact in time", f"{_num(dy.rho, '.1f')}"),
            (
                "impulse / contact time (FE)",
                f"{_num(dy.impulse, '.4f')} N s / {_num(dy.contact_time * 1e3, '.2f')} ms",
            ),
            ("restitution (FE, elastic material)", f"{_num(dy.restitution, '.3f')}"),
        ]
    p = result.profile
    if p is not None:
        st, th = p.rho_stats, p.thickness_stats
        n_sat = int(p.saturated.sum())
        rows += [
            ("CMD sectors", f"{p.z.size}"),
            ("roll model / reading", f"{p.roll_model} / FD (energy model beside it)"),
            (
                "thickness mean / CoV",
                f"{_num(th.mean * 1e6, '.2f')} um / {_num(100 * th.cov, '.2f')} %",
            ),
        ]
        if n_sat:
            rows.append(("saturated sectors (off the scale, excluded)", f"{n_sat}"))
        if st is None:
            rows.append(("Rho statistics", "fewer than two readings on the scale"))
        else:
            rows += [
                ("Rho mean / SD (on the scale)", f"{_num(st.mean, '.1f')} / {_num(st.sd, '.1f')}"),
                ("Rho CoV", f"{_num(100 * st.cov, '.1f')} % ({st.band})"),
                (
                    "Rho min / max / peak-to-peak",
                    f"{_num(st.min, '.1f')} / {_num(st.max, '.1f')} / "
                    f"{_num(st.peak_to_peak, '.1f')}",
                ),
            ]
        n_slack = int(p.slack.sum())
        if n_slack:
            rows.append(("slack sectors (reading set by the E_r floor)", f"{n_slack}"))
        c = p.comparison
        if c is not None:
            ms = c.measured_stats
            r = "n/a" if c.correlation is None else f"{_num(c.correlation, '.2f')}"
            rows += [
                (
                    "measured Rho mean / CoV",
                    f"{_num(ms.mean, '.1f')} / {_num(100 * ms.cov, '.1f')} % ({ms.band})",
                ),
                (
                    "predicted - measured: bias / RMS",
                    f"{_num(c.bias, '+.1f')} / {_num(c.rms, '.1f')}",
                ),
                ("RMS after bias / correlation", f"{_num(c.rms_shape, '.1f')} / {r}"),
            ]
    return rows
