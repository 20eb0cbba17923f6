"""CLI commands of the reverse road: ``woundroll readings FILE`` (registered in woundroll.app.cli).

Kept out of :mod:`woundroll.app.cli` so that the shared module only registers them; imports of
numpy-heavy modules happen inside the commands (``woundroll --help`` stays light).
"""

from __future__ import annotations

import math
import sys
from pathlib import Path
from typing import TYPE_CHECKING, Annotated, Any

import typer

from woundroll.app.cli.console import escape, table
from woundroll.app.cli.options import CaseArg, JsonOpt, LaneWidthOpt, SetOpt, out_option
from woundroll.errors import ConvergenceError, InputError
from woundroll.pipeline.vocabulary import SCHEMA_VERSION, versioned
from woundroll.util.output import strict_json, write_result_files

if TYPE_CHECKING:
    from rich.table import Table


def _length(text: str | None, field: str) -> float | None:
    if text is None:
        return None
    from woundroll.units import to_si

    v = to_si(text, "length", field)
    if not v > 0:
        raise InputError(f"must be positive, got {text!r}", field)
    return v


def readings_cmd(
    csv_files: Annotated[
        list[str],
        typer.Argument(
            help="Readings file(s): a CSV 'position [in],reading [Rho]' (or [R], [L], [g]; "
            "lane numbers with --lane-width; several value columns or repeated positions are "
            "passes), a TAPPI T 834 sheet or a dense profile export (see --format). Several "
            "files (or a sheet of several rolls with --trend): the roll-to-roll trend.",
            metavar="CSV_FILE",
        ),
    ],
    width: Annotated[
        str | None,
        typer.Option(help="Web width ('24 in'): positions outside the roll are an error."),
    ] = None,
    lane_width: LaneWidthOpt = None,
    fmt: Annotated[
        str,
        typer.Option(
            "--format",
            help="File layout: auto (detected), generic, tappi (T 834 sheet), profile.",
        ),
    ] = "auto",
    roll: Annotated[
        str | None, typer.Option("--roll", help="Roll id on a TAPPI sheet with several rolls.")
    ] = None,
    trend: Annotated[
        bool,
        typer.Option(
            "--trend",
            help="Roll-to-roll trend of every roll in the files (production order): mean, "
            "CoV, faults per roll and X-mR control charts of mean and CoV.",
        ),
    ] = False,
    band: Annotated[
        str | None,
        typer.Option(
            "--band",
            help="Fault threshold: a position more than this far from the roll mean is in a "
            "hard or soft band ('5 %', or a fraction '0.05'; default 5 %).",
        ),
    ] = None,
    unit: Annotated[
        str | None,
        typer.Option(
            "--unit",
            help="Length unit of the positions shown: in, cm, mm, m (default: the file's).",
        ),
    ] = None,
    out_dir: Annotated[
        Path | None,
        typer.Option(
            "--out",
            help="Write readings.json and readings.png (profile.png), or with a trend trend.json, "
            "trend.csv and trend.png, here.",
        ),
    ] = None,
    as_json: Annotated[bool, typer.Option("--json", help="Print the readings as JSON.")] = False,
) -> None:
    """Read a sheet of hardness readings; print the mean and scatter per position, the
    profile's CoV, peak-to-peak, band verdict and hard/soft bands; with several rolls the
    roll-to-roll trend."""
    from woundroll.app.cli.console import fail
    from woundroll.assess.profile_check import FAULT_BAND
    from woundroll.io.readings import DISPLAY_UNITS
    from woundroll.io.tester_files import FORMATS

    try:
        if fmt not in FORMATS:
            raise InputError(f"unknown format {fmt!r}; one of {', '.join(FORMATS)}", "--format")
        if unit is not None and unit not in DISPLAY_UNITS:
            raise InputError(
                f"unknown length unit {unit!r} (use {', '.join(DISPLAY_UNITS)})", "--unit"
            )
        frac = FAULT_BAND if band is None else _band(band)
        w, lw = _length(width, "--width"), _length(lane_width, "--lane-width")
        if trend or len(csv_files) > 1:
            if roll is not None:
                raise InputError(
                    "--roll picks one roll; a trend takes every roll of the files", "--roll"
                )
            _readings_trend(csv_files, fmt, w, lw, frac, unit, out_dir, as_json)
            return
        layout, r = _read_one(csv_files[0], fmt, roll, w, lw)
        check = _check_one(csv_files[0], layout, r, frac)
        if out_dir is not None:
            _write_readings(out_dir, r, check, unit)
    except InputError as exc:
        fail(exc, 2)
    except ConvergenceError as exc:  # pragma: no cover - nothing iterative here
        fail(exc, 1)
    if as_json:
        payload = versioned(r.to_dict())
        payload["profile_check"] = None if check is None else check.to_dict()
        sys.stdout.write(strict_json(payload) + "\n")
        return
    _print_readings(r, check, unit, out_dir)


def _read_one(csv_file: str, fmt: str, roll: str | None, w: float | None, lw: float | None):  # type: ignore[no-untyped-def]
    """(layout, readings) of one file; a missing or unknown roll id is --roll's error."""
    from woundroll.io.tester_files import detect_format, read_tester_file

    layout = detect_format(csv_file, "CSV_FILE") if fmt == "auto" else fmt
    try:
        r = read_tester_file(
            csv_file, format=layout, roll=roll, width=w, lane_width=lw, field="CSV_FILE"
        )
    except InputError as exc:
        if layout == "tappi" and (exc.message.startswith("no roll") or "pick one" in exc.message):
            raise InputError(exc.message, "--roll") from None
        raise
    return layout, r


def _print_readings(r, check, unit: str | None, out_dir: Path | None) -> None:  # type: ignore[no-untyped-def]
    """The readings per position, their repeatability and the profile check, as tables."""
    from woundroll.app.cli.console import out
    from woundroll.io.readings import DISPLAY_UNITS

    u = unit or r.position_unit or "in"
    f = DISPLAY_UNITS[u]
    cols = [f"position [{u}]"] + ([] if u == "m" else ["position [m]"])
    shown = (
        {}
        if check is None
        else {k: v for k, v in check.ids.items() if not (k == "roll" and f"roll {v}" in r.source)}
    )
    ids = " (" + _ids_text(shown) + ")" if shown else ""
    t = table(
        *(escape(c) for c in cols),
        escape(f"mean [{r.scale}]"),
        escape(f"SD [{r.scale}]"),
        "count",
        title=escape(f"{r.source}{ids}: {r.passes} pass(es), scale {r.scale}"),
    )
    for x, m, s_, n in zip(r.position, r.mean, r.sd, r.count, strict=True):
        pos = [f"{x / f:.4g}"] + ([] if u == "m" else [f"{x:.4f}"])
        t.add_row(*pos, f"{m:.2f}", f"{s_:.2f}" if n > 1 else "-", f"{n}")
    out.print(t)
    pooled = r.pooled_sd
    if pooled is not None:
        out.print(f"pooled repeatability (SD): {pooled:.2f} {r.scale}", highlight=False)
    else:
        out.print("no repeated readings: the scatter must come from the instrument's repeatability")
    if check is None:
        out.print("no profile statistics: they need readings at 2 positions or more")
        return
    out.print(
        escape(
            f"profile: mean {check.mean:.2f} {r.scale}, SD {check.sd:.2f}, "
            f"min {check.min:.2f}, max {check.max:.2f}; {check.verdict}"
        ),
        highlight=False,
    )
    rows = check.fault_rows(u)
    if rows:
        ft = table(*(escape(k) for k in rows[0]), title="hard and soft bands")
        for row in rows:
            ft.add_row(*(escape(v) for v in row.values()))
        out.print(ft)
    if out_dir is not None:
        out.print(f"wrote {out_dir / 'readings.json'}, readings.png, profile.png")


def _band(text: str) -> float:
    """``"5 %"``, ``"5%"`` or ``"0.05"`` -> 0.05; one-line error naming --band otherwise."""
    t = text.strip()
    pct = t.endswith("%")
    try:
        v = float(t.rstrip("%").strip())
    except ValueError:
        raise InputError(f"{text!r} is not a number ('5 %' or 0.05)", "--band") from None
    if pct:
        v /= 100.0
    if not (math.isfinite(v) and 0 < v < 1):
        raise InputError(f"must lie between 0 and 100 % (got {text!r})", "--band")
    return v


def _ids_text(ids: dict[str, str]) -> str:
    return ", ".join(f"{k} {v}" for k, v in ids.items())


def _check_one(path: str, layout: str, r, frac: float):  # type: ignore[no-untyped-def]
    """The profile check of one roll (None below 2 positions or with a zero mean), with the
    ids of its file."""
    from woundroll.assess.profile_check import check_profile, file_ids
    from woundroll.io.tester_files import read_profile_export

    if r.n_positions < 2 or not float(r.mean.mean()) > 0:
        return None
    ids = file_ids(path)
    if layout == "profile":
        ids = file_ids(path, read_profile_export(path, field="CSV_FILE").metadata)
    elif layout == "tappi":
        ids["roll"] = r.source.split(": roll ", 1)[-1]
    return check_profile(r, band=frac, ids=ids)


def _write_readings(out_dir: Path, r, check, unit) -> None:  # type: ignore[no-untyped-def]
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt

    payload = versioned(r.to_dict())
    payload["profile_check"] = None if check is None else check.to_dict()
    u = unit or r.position_unit or "in"
    try:
        out_dir.mkdir(parents=True, exist_ok=True)
        (out_dir / "readings.json").write_text(strict_json(payload, indent=1), encoding="utf-8")
        plt.close(r.plot(out_dir / "readings.png", unit=u))
        if check is not None:
            plt.close(check.plot(out_dir / "profile.png", unit=u))
    except OSError as exc:
        raise InputError(f"cannot write to {out_dir}: {exc.strerror or exc}", "--out") from None


def _trend_table(tr: Any, checks: list[Any]) -> Table:
    """The roll-to-roll trend as a table: one row per roll with its profile statistics and
    whether its mean or CoV falls outside the X-mR chart limits."""
    s = tr.scale
    lots = any("lot" in c.ids for c in checks)
    t = table(title=f"roll-to-roll trend: {len(checks)} rolls, scale {s}")
    t.add_column("#", justify="right")
    t.add_column("roll", no_wrap=True)
    if lots:
        t.add_column("lot", no_wrap=True)
    for name in (f"mean [{s}]", "CoV [%]", f"p2p [{s}]"):
        t.add_column(escape(name), justify="right")
    t.add_column("band", no_wrap=True)
    t.add_column("hard/soft", justify="right")
    t.add_column("limits", no_wrap=True)
    mc, cc = tr.mean_chart, tr.cov_chart
    for i, c in enumerate(checks):
        flag = [n for n, ch in (("mean", mc), ("CoV", cc)) if i in ch.out_of_control]
        nh = sum(b.kind == "hard" for b in c.faults)
        cells = [f"{i + 1}", escape(c.label)]
        if lots:
            cells.append(escape(c.ids.get("lot", "")))
        cells += [
            f"{c.mean:.2f}",
            f"{100 * c.cov:.2f}",
            f"{c.peak_to_peak:.3g}",
            c.band,
            f"{nh}/{len(c.faults) - nh}",
            "out: " + ", ".join(flag) if flag else "in",
        ]
        t.add_row(*cells)
    return t


def _readings_trend(  # type: ignore[no-untyped-def]
    files: list[str], fmt, width, lane_width, frac, unit, out_dir, as_json
) -> None:
    from woundroll.app.cli.console import out
    from woundroll.assess.profile_check import (
        TREND_MIN_ROLLS,
        check_profile,
        read_rolls,
        roll_trend,
    )

    rolls = read_rolls(files, format=fmt, width=width, lane_width=lane_width, field="CSV_FILE")
    checks = []
    for r, ids in rolls:
        if r.n_positions < 2:
            raise InputError(
                f"{r.source}: a roll in a trend needs readings at 2 positions or more", "CSV_FILE"
            )
        checks.append(check_profile(r, band=frac, ids=ids))
    tr = roll_trend(checks)
    if out_dir is not None:
        import matplotlib

        matplotlib.use("Agg", force=False)
        import matplotlib.pyplot as plt

        try:
            out_dir.mkdir(parents=True, exist_ok=True)
            (out_dir / "trend.json").write_text(
                strict_json(versioned(tr.to_dict()), indent=1), encoding="utf-8"
            )
            (out_dir / "trend.csv").write_text(tr.to_csv(), encoding="utf-8")
            plt.close(tr.plot(out_dir / "trend.png"))
        except OSError as exc:
            raise InputError(f"cannot write to {out_dir}: {exc.strerror or exc}", "--out") from None
    if as_json:
        sys.stdout.write(strict_json(versioned(tr.to_dict())) + "\n")
        return
    s = tr.scale
    mc, cc = tr.mean_chart, tr.cov_chart
    out.print(_trend_table(tr, checks))
    out.print(
        f"X-mR charts (limits = centre +- 2.66 mR-bar): mean centre {mc.center:.2f} {s}, "
        f"limits {mc.lcl:.2f} to {mc.ucl:.2f}; CoV centre {100 * cc.center:.2f} %, limits "
        f"{100 * cc.lcl:.2f} to {100 * cc.ucl:.2f} %",
        highlight=False,
    )
    if tr.provisional:
        out.print(
            f"limits provisional: {len(checks)} rolls, fewer than {TREND_MIN_ROLLS}",
            highlight=False,
        )
    for line in tr.flagged():
        out.print(escape(line), highlight=False)
    if out_dir is not None:
        out.print(f"wrote {out_dir / 'trend.json'}, trend.csv, trend.png")


def diagnose_cmd(
    case: CaseArg,
    readings: Annotated[
        str | None,
        typer.Option("--readings", help="Readings CSV (default: the case's [readings] file)."),
    ] = None,
    lane_width: LaneWidthOpt = None,
    confidence: Annotated[
        float, typer.Option(help="Two-sided confidence of the intervals.")
    ] = 0.95,
    set_: SetOpt = None,
    out_dir: out_option("diagnosis.json and PNG plots") = None,  # type: ignore[valid-type]
    as_json: JsonOpt = False,
    quiet: Annotated[bool, typer.Option("--quiet", "-q", help="No progress or table.")] = False,
    causes: Annotated[
        bool,
        typer.Option(
            "--causes",
            help="Also fit the profile's causes (thickness bands, tension level, nip "
            "deflection) with the reduced axisymmetric model (~20-40 forward runs).",
        ),
    ] = False,
    bands: Annotated[
        int | None, typer.Option(help="Thickness bands fitted with --causes (default n/2, <= 8).")
    ] = None,
    full_level: Annotated[
        int,
        typer.Option(
            "--full-level",
            min=0,
            max=3,
            help="Full profile-model runs that correct the --causes tension level (the "
            "reduced model's level was 41 % low on a soft PET2 roll; 3 runs: within 2 %). "
            "0 skips them.",
        ),
    ] = 3,
) -> None:
    """Readings -> the effective wound-on tension and near-surface pressure at each position."""
    from woundroll.app.cli.console import fail, with_progress
    from woundroll.case import load_case
    from woundroll.inverse.diagnosis import diagnose
    from woundroll.io.readings import read_readings

    try:
        c = load_case(case, set_ or [])
        lw = _length(lane_width, "--lane-width")
        if lw is None and c.readings is not None:
            lw = c.readings.lane_width
        r = None
        if readings is not None:
            r = read_readings(readings, width=c.web.width, lane_width=lw, field="--readings")
        if quiet or as_json or not sys.stderr.isatty():
            d = diagnose(c, r, confidence=confidence)
        else:
            d = with_progress(
                lambda progress: diagnose(c, r, confidence=confidence, progress=progress)
            )
        from woundroll.assess.defects import defect_report

        defects = defect_report(c, d)
        payload = {
            "schema_version": SCHEMA_VERSION,
            "case": {"title": c.display_title},
            "readings": d.readings.to_dict(),
            "diagnosis": {**d.to_dict(), "defects": defects.to_dict()},
        }
        fit = _causes_into(payload, c, d, bands, full_level) if causes else None
        written = _write(out_dir, payload, d, defects) if out_dir is not None else []
        if fit is not None and out_dir is not None:
            import matplotlib.pyplot as plt

            plt.close(fit.plot(out_dir / "causes.png"))
            written.append(out_dir / "causes.png")
    except InputError as exc:
        fail(exc, 2)
    except ConvergenceError as exc:
        fail(exc, 1)
    if as_json:
        sys.stdout.write(strict_json(payload) + "\n")
        return
    if quiet:
        return
    _print_diagnosis(c.display_title or case, d, defects, fit, written)


def _causes_into(payload: dict, c, d, bands: int | None, full_level: int):  # type: ignore[no-untyped-def]
    """Fit the causes of the CMD profile and put them into the diagnosis payload."""
    from woundroll.inverse.causes import fit_causes

    fit = fit_causes(c, d.readings, n_bands=bands, full_level=full_level)
    fd = fit.to_dict()
    payload["diagnosis"]["profile"] = fd["profile"]
    payload["diagnosis"]["causes"] = fd["causes"]
    payload["diagnosis"]["cause_fit"] = {
        k: fd[k] for k in ("parameters", "verification", "forward_runs", "notes")
    }
    return fit


def _print_diagnosis(title: str, d, defects, fit, written: list[Path]) -> None:  # type: ignore[no-untyped-def]
    """The diagnosis' sentence, its table, the defect risks and the causes, as tables."""
    from woundroll.app.cli.console import out

    out.print(escape(d.sentence()), highlight=False, soft_wrap=True)
    # headers escaped: rich reads "[in]" and "[kPa]" as markup and drops them
    t = table(
        escape("position [in]"),
        escape(f"reading [{d.curve.scale}]"),
        escape("wound-on tension [MPa]"),
        escape(f"P at {d.pressure_depth * 1e3:.1f} mm [kPa]"),
        "status",
        title=escape(f"{title}: diagnosis ({100 * d.confidence:.0f} % intervals in brackets)"),
    )
    for row in d.summary():
        t.add_row(*[escape(v) for v in row])
    out.print(t)
    v = d.verification
    if v:
        out.print(
            f"check: full forward run at {v['web_tension_Pa'] / 1e6:.3g} MPa reads "
            f"{v['full_forward_reading']:.2f} (target {v['target_reading']:.2f})",
            highlight=False,
        )
    for note in d.notes:
        out.print(f"note: {escape(note)}", highlight=False)
    _print_defects(defects)
    if fit is not None:
        tc = table("rank", "cause", title="causes of the CMD profile (reduced axisymmetric model)")
        for i, cz in enumerate(fit.causes, 1):
            tc.add_row(f"{i}", escape(cz["sentence"]))
        out.print(tc)
        out.print(
            f"fit: residual RMS {fit.residual_rms:.2f} {d.curve.scale}, "
            f"{fit.forward_runs} forward runs",
            highlight=False,
        )
        for note in fit.notes:
            out.print(f"note: {escape(note)}", highlight=False)
    for p in written:
        out.print(f"wrote {escape(str(p))}")


def _print_defects(defects) -> None:  # type: ignore[no-untyped-def]
    from woundroll.app.cli.console import out

    t = table("criterion", "risk", "finding", title=f"defect risk: {defects.risk}")
    for name, risk, sentence in defects.summary():
        t.add_row(escape(name), escape(risk), escape(sentence))
    out.print(t)
    note = defects.needs_note()
    if note:
        out.print(escape(note), highlight=False)


def defects_cmd(
    case: CaseArg,
    set_: SetOpt = None,
    as_json: JsonOpt = False,
    out_dir: out_option("defects.json and defects.png") = None,  # type: ignore[valid-type]
) -> None:
    """Defect risk of a roll from its wound-in stresses: starring, core crush, slip,
    telescoping, blocking, slack (limits in the case's defects section)."""

    from woundroll.app.cli.console import fail
    from woundroll.assess.defects import defect_report
    from woundroll.case import load_case

    try:
        c = load_case(case, set_ or [])
        rep = defect_report(c)
        if out_dir is not None:
            write_result_files(out_dir, "defects", rep, versioned({}))
    except InputError as exc:
        fail(exc, 2)
    except ConvergenceError as exc:
        fail(exc, 1)
    if as_json:
        sys.stdout.write(strict_json(versioned({"defects": rep.to_dict()})) + "\n")
        return
    _print_defects(rep)


def _write(out_dir: Path, payload: dict, d, defects) -> list[Path]:  # type: ignore[no-untyped-def]

    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt

    try:
        out_dir.mkdir(parents=True, exist_ok=True)
        paths = [out_dir / "diagnosis.json"]
        paths[0].write_text(strict_json(payload, indent=1), encoding="utf-8")
        plt.close(d.readings.plot(out_dir / "readings.png"))
        for fig in d.plot(out_dir / "diagnosis"):
            plt.close(fig)
        plt.close(defects.plot(out_dir / "defects.png"))
    except OSError as exc:
        raise InputError(f"cannot write to {out_dir}: {exc.strerror or exc}", "--out") from None
    return paths + [
        out_dir / n for n in ("readings.png", "diagnosis_curve.png", "diagnosis_cmd.png")
    ]


def run_uncertainty(case, n: int, out_dir: Path | None, written: list, quiet: bool, profile=None):  # type: ignore[no-untyped-def]
    """``woundroll run --uncertainty N``: the Monte Carlo bands (None for N = 0); adds its
    files to ``written`` when ``out_dir`` is given. ``profile``: the run's CMD profile, the
    centre of the profile band."""
    if not n:
        return None
    from woundroll.app.cli.console import with_progress
    from woundroll.assess.uncertainty import propagate

    if quiet or not sys.stderr.isatty():
        uq = propagate(case, n, profile=profile)
    else:
        uq = with_progress(lambda progress: propagate(case, n, progress=progress, profile=profile))
    if out_dir is not None:
        written.extend(uq.write(out_dir))
    return uq


def json_with_uncertainty(result, uq) -> str:  # type: ignore[no-untyped-def]
    """The run's JSON, with ``uncertainty`` added when it was propagated."""
    if uq is None:
        return result.to_json()
    from woundroll.util.output import strict_json

    return strict_json({**result.to_dict(), "uncertainty": uq.to_dict()})


def print_uncertainty(uq) -> None:  # type: ignore[no-untyped-def]
    if uq is None:
        return
    from woundroll.app.cli.console import out

    t = table("quantity", "value", title="uncertainty (Monte Carlo)")
    for name, value in uq.summary():
        t.add_row(escape(name), escape(value))
    out.print(t)
    for note in uq.notes:
        out.print(f"note: {escape(note)}", highlight=False)


def _range(text: str | None, kind: str, field: str, convert=None) -> tuple[float, float] | None:  # type: ignore[no-untyped-def]
    """``"10 kPa..300 kPa"`` -> (1e4, 3e5) in SI (``convert`` for tensions)."""
    if text is None:
        return None
    lo, sep, hi = text.partition("..")
    if not sep:
        raise InputError(f"expected low..high, e.g. '10 kPa..300 kPa', got {text!r}", field)
    from woundroll.units import to_si

    def one(v: str) -> float:
        return convert(v.strip()) if convert else to_si(v.strip(), kind, field)

    return one(lo), one(hi)


def design_cmd(
    case: CaseArg,
    target: Annotated[
        str, typer.Option(help="Target surface hardness with its scale: '60 Rho' (or g).")
    ],
    pressure: Annotated[
        str | None,
        typer.Option(help="Interlayer pressure window, core to near-surface: '10 kPa..300 kPa'."),
    ] = None,
    tension: Annotated[
        str | None,
        typer.Option(
            help="Winder tension range: '0.5 pli..4 pli', '100 N..500 N', '1 MPa..8 MPa'."
        ),
    ] = None,
    nip: Annotated[
        str | None, typer.Option(help="Nip load range: '0 pli..3 pli' (needs winding.friction).")
    ] = None,
    taper: Annotated[
        str, typer.Option(help="Taper law: linear, hyperbolic or table (knots optimised).")
    ] = "linear",
    max_taper: Annotated[float, typer.Option(help="Largest taper fraction (0-1).")] = 0.6,
    knots: Annotated[int, typer.Option(help="Table taper: knots from core to surface.")] = 4,
    monotone: Annotated[
        bool, typer.Option(help="Table taper: the tension only falls as the roll grows.")
    ] = True,
    hoop_min: Annotated[
        str | None,
        typer.Option(help="Smallest accepted layer-mean hoop stress: '-20 kPa' (default 0)."),
    ] = None,
    tolerance: Annotated[float, typer.Option(help="Accepted |reading - target|.")] = 1.0,
    allow_negative_hoop: Annotated[
        bool, typer.Option(help="Do not require a non-negative hoop stress.")
    ] = False,
    set_: SetOpt = None,
    as_json: JsonOpt = False,
    out_dir: out_option("design.json and design.png") = None,  # type: ignore[valid-type]
) -> None:
    """Setpoint design: tension, taper and nip load for a target hardness, a pressure
    window and no negative hoop stress, within the winder's ranges."""

    from woundroll.app.cli.console import fail, out
    from woundroll.case import load_case
    from woundroll.case.schema import _tension
    from woundroll.inverse.design import DesignTarget, design_setpoints
    from woundroll.io.readings import _scale_of
    from woundroll.units import to_si

    try:
        c = load_case(case, set_ or [])
        web = c.web.build()
        value, _, unit = target.strip().partition(" ")
        scale = _scale_of(unit) if unit else None
        try:
            reading = float(value)
        except ValueError:
            reading = math.nan
        if scale is None or not math.isfinite(reading):
            raise InputError(
                f"expected a reading with its scale, e.g. '60 Rho', got {target!r}", "--target"
            )

        def stress(text: str) -> float:
            try:
                kind, v = _tension(text)
            except ValueError as exc:
                raise InputError(str(exc), "--tension") from None
            return {
                "force": v / (web.width * web.thickness),
                "force_per_length": v / web.thickness,
                "pressure": v,
            }[kind]

        p = _range(pressure, "pressure", "--pressure") or (0.0, math.inf)
        t = _range(tension, "pressure", "--tension", stress) or (0.0, math.inf)
        n = _range(nip, "force_per_length", "--nip") or (c.winding.nip_load, c.winding.nip_load)
        tgt = DesignTarget(
            reading=reading,
            scale=scale,
            tolerance=tolerance,
            pressure_min=p[0],
            pressure_max=p[1],
            tension_min=t[0],
            tension_max=t[1],
            nip_min=n[0],
            nip_max=n[1],
            taper_kind=taper,
            taper_max=max_taper,
            allow_negative_hoop=allow_negative_hoop,
            hoop_min=to_si(hoop_min, "pressure", "--hoop-min") if hoop_min else 0.0,
            knots=knots,
            monotone=monotone,
        )
        d = design_setpoints(c, tgt)
        if out_dir is not None:
            write_result_files(out_dir, "design", d, versioned({}))
    except InputError as exc:
        fail(exc, 2)
    except ConvergenceError as exc:
        fail(exc, 1)
    if as_json:
        sys.stdout.write(strict_json(versioned({"design": d.to_dict()})) + "\n")
        return
    tb = table("quantity", "value", title=escape(f"{c.display_title or case}: setpoint design"))
    for name, value in d.summary():
        tb.add_row(escape(name), escape(value))
    out.print(tb)
    for note in d.notes:
        out.print(f"note: {escape(note)}", highlight=False)
    out.print("case file lines:\n" + escape(d.case_snippet()), highlight=False)
    if out_dir is not None:
        out.print(escape(f"wrote {out_dir / 'design.json'}\nwrote {out_dir / 'design.png'}"))


def register(app: typer.Typer) -> None:
    """Add the reverse-road commands to the ``woundroll`` app."""
    app.command("readings")(readings_cmd)
    app.command("diagnose")(diagnose_cmd)
    app.command("defects")(defects_cmd)
    app.command("design")(design_cmd)
