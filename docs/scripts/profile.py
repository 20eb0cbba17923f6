"""Generator of docs/profile.md's results on the bundled Table 3 cases
(docs/scripts/regenerate.py): the four ``pet3-*`` cases through ``woundroll.run`` on today's
defaults (the default roll model, the FD reading as the instrument shows it)."""

from __future__ import annotations

from collections.abc import Callable

CASES = ("pet3-2.3MPa", "pet3-3.45MPa", "pet3-2.3MPa-nip", "pet3-3.45MPa-nip")


def table3() -> str:
    """Reading statistics on the scale, saturated and slack sectors, the correlation of the
    model's reading with the thickness, and the nip's contact, per case."""
    import numpy as np

    import woundroll

    lines = [
        "| case | sectors | reading mean / SD (on the scale) | CoV (band) | min / max "
        "| saturated | slack | corr(reading, thickness) | nip: sectors touched, peak / mean |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for name in CASES:
        p = woundroll.run(woundroll.load_case(name)).profile
        st = p.rho_stats
        stats = (
            "fewer than two on the scale | | "
            if st is None
            else f"{st.mean:.1f} / {st.sd:.1f} | {100 * st.cov:.0f} % ({st.band}) | "
            f"{st.min:.1f} / {st.max:.1f}"
        )
        corr = float(np.corrcoef(p.rho, p.thickness)[0, 1])
        nip = "-"
        if p.nip_load is not None:
            mean = float(np.average(p.nip_load, weights=p.winding.dz))
            touched = 100 * float(np.mean(p.nip_load > 0))
            nip = f"{touched:.0f} %, {p.nip_load.max() / mean:.1f}" if mean > 0 else "none"
        lines.append(
            f"| `{name}` | {p.z.size} | {stats} | {int(p.saturated.sum())} | "
            f"{int(p.slack.sum())} | {corr:.2f} | {nip} |"
        )
    return "\n".join(lines)


def _scaled_profile(factor: float, into: str) -> str:
    """The bundled Table 3 profile with its deviations from the mean scaled by ``factor``,
    written as a CSV file (SI) in directory ``into``; its path."""
    from pathlib import Path

    from woundroll.materials.thickness_profile import bundled_profile

    prof = bundled_profile("table3_synthetic_pet")
    mean = prof.thickness.mean()
    scaled = mean + factor * (prof.thickness - mean)
    rows = [f"{float(x)!r},{float(h)!r}" for x, h in zip(prof.position, scaled, strict=True)]
    path = Path(into) / f"profile_x{factor:g}.csv"
    path.write_text("position [m],thickness [m]\n" + "\n".join(rows) + "\n")
    return str(path)


def amplitude() -> str:
    """pet3-2.3MPa with the profile's deviations scaled by 1, 0.5 and 0.25 (31 sectors)."""
    import tempfile

    import numpy as np

    import woundroll

    lines = [
        "| thickness SD / peak-to-peak | reading mean / CoV (on the scale) | min / max "
        "| saturated | slack sectors |",
        "|---|---|---|---|---|",
    ]
    with tempfile.TemporaryDirectory() as tmp:
        for factor in (1.0, 0.5, 0.25):
            path = _scaled_profile(factor, tmp)
            case = woundroll.load_case(
                "pet3-2.3MPa", [f"winding.thickness_profile='{path}'", "profile.sectors=31"]
            )
            p = woundroll.run(case).profile
            th, st = p.thickness_stats, p.rho_stats
            ptp = 100 * (th.max - th.min) / th.mean
            stats = (
                "- | -"
                if st is None
                else f"{st.mean:.1f} / {100 * st.cov:.0f} % | {st.min:.1f} / {st.max:.1f}"
            )
            lines.append(
                f"| {100 * th.cov:.2f} % / {ptp:.1f} % (x {factor:g}) | {stats} | "
                f"{int(p.saturated.sum())} of {p.z.size} | {int(np.sum(p.slack))} |"
            )
    return "\n".join(lines)


BLOCKS: dict[str, Callable[[], str]] = {"table3": table3, "amplitude": amplitude}
