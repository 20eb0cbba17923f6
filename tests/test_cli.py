"""The command line: one-line errors naming the field with exit status 2, JSON output."""

import json
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest
from typer.testing import CliRunner

from woundroll.app.cli import app

runner = CliRunner()
EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


@pytest.mark.parametrize(
    ("args", "field"),
    [
        (["run", "no-such-case"], "CASE"),
        (["run", "pet1-26.7N", "--set", "web.thickness=-1"], "web.thickness"),
        (["run", "pet1-26.7N", "--set", "web.thickness='1 psi'"], "web.thickness"),
        (["run", "pet1-26.7N", "--set", "web.radial_modulus.K2=0"], "web.radial_modulus.K2"),
        (["run", "pet1-26.7N", "--set", "winding.outer_radius='2 cm'"], "winding.outer_radius"),
        (["run", "pet1-26.7N", "--set", "winding.tension='3 furlong'"], "winding.tension"),
        (["run", "pet1-26.7N", "--set", "core.E=nan"], "core.E"),
        (["run", "pet1-26.7N", "--set", "nonsense"], "--set"),
    ],
)
def test_bad_input_is_one_line_exit_2(args, field):
    res = runner.invoke(app, args)
    assert res.exit_code == 2, res.output
    lines = [line for line in res.output.splitlines() if line.strip()]
    assert len(lines) == 1, res.output
    assert f"{field}:" in lines[0]
    assert "Traceback" not in res.output


def test_real_process_has_no_traceback():
    proc = subprocess.run(
        [
            sys.executable,
            "-m",
            "woundroll.app.cli",
            "run",
            "pet1-26.7N",
            "--set",
            "web.thickness=0",
        ],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert proc.returncode == 2
    assert proc.stderr.strip().startswith("error: web.thickness:")
    assert "Traceback" not in proc.stderr + proc.stdout


def test_cases_and_materials_list():
    res = runner.invoke(app, ["cases"])
    assert res.exit_code == 0 and "pet2-80N" in res.output
    res = runner.invoke(app, ["materials"])
    assert res.exit_code == 0 and "PET3" in res.output


def test_fit_stack_json():
    res = runner.invoke(
        app,
        [
            "fit-stack",
            str(EXAMPLES / "data" / "stack_test_pet1_synthetic.csv"),
            "--law",
            "pfeiffer",
            "--json",
        ],
    )
    assert res.exit_code == 0, res.output
    fit = json.loads(res.output)["pfeiffer"]
    # the synthetic file was generated from K2 = 123.88 with 1.5 % noise
    assert fit["K2"] == pytest.approx(123.88, rel=0.02)


def test_fit_stack_missing_file():
    res = runner.invoke(app, ["fit-stack", "nope.csv"])
    assert res.exit_code == 2
    assert "CSV_FILE: file not found" in res.output


def test_study_command_json_and_unknown_name():
    # the command's JSON path with the cheapest study (the slip study took 70-200 s of the
    # default suite here; tests/test_slip_study.py checks that study's numbers)
    res = runner.invoke(app, ["study", "pile-height", "--json", "--workers", "1"])
    assert res.exit_code == 0, res.output
    d = json.loads(res.stdout)  # the study as JSON on stdout
    assert d["study"] == "pile-height"
    bad = runner.invoke(app, ["study", "no-such-study"])
    assert bad.exit_code == 2
    assert "study:" in bad.output and "Traceback" not in bad.output


def test_bracketed_text_survives_in_messages():
    # rich markup must not eat "[length]" from a dimension error
    res = runner.invoke(app, ["run", "pet1-26.7N", "--set", "web.density='1 m'"])
    assert res.exit_code == 2
    assert "[length]" in res.output


def test_version():
    res = runner.invoke(app, ["--version"])
    assert res.exit_code == 0
    assert res.output.startswith("woundroll ")


def test_fit_stack_help_keeps_brackets():
    res = runner.invoke(app, ["fit-stack", "--help"], env={"COLUMNS": "200"})
    assert "[kPa]" in res.output


@pytest.mark.parametrize(
    ("rows", "words"),
    [
        ("0.1,5\n0.2,5\n0.3,5\n0.4,5\n", "does not rise"),  # constant: NaN R^2 before
        ("0.1,50\n0.2,20\n0.3,10\n0.4,5\n", "does not rise"),  # falling
        ("0.1,5\n0.2,10\n", "at least 3 points"),  # two points
        ("0.1,5\n0.2,10\n0.3,8\n0.4,20\n", "falls from"),  # a dip
    ],
)
def test_fit_stack_rejects_data_no_law_fits(tmp_path, rows, words):
    f = tmp_path / "stack.csv"
    f.write_text("strain,pressure [kPa]\n" + rows)
    res = runner.invoke(app, ["fit-stack", str(f), "--json"])
    assert res.exit_code == 2, res.output
    lines = [line for line in res.output.splitlines() if line.strip()]
    assert len(lines) == 1 and lines[0].startswith("error: CSV_FILE:") and words in lines[0]


def test_fit_stack_cycle_without_unloading_names_the_option(tmp_path):
    # strain rising then falling: the loading check fails and the message names --unloading
    f = tmp_path / "cycle.csv"
    f.write_text("strain,pressure [kPa]\n0.1,5\n0.2,20\n0.3,80\n0.25,30\n0.2,8\n")
    res = runner.invoke(app, ["fit-stack", str(f), "--json"])
    assert res.exit_code == 2, res.output
    assert "--unloading" in res.output and "Traceback" not in res.output
    # a dip in a loading curve is not a cycle: no hint
    f.write_text("strain,pressure [kPa]\n0.1,5\n0.2,10\n0.3,8\n0.4,20\n")
    res = runner.invoke(app, ["fit-stack", str(f), "--json"])
    assert res.exit_code == 2 and "--unloading" not in res.output


def test_bad_out_is_found_before_the_run(tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("x")
    # --out below a regular file cannot be created: exit 2 at once, naming --out
    res = runner.invoke(app, ["run", "pet1-26.7N", "--out", str(blocker / "sub")])
    assert res.exit_code == 2
    assert "--out:" in res.output


def test_implausible_tension_warns_but_runs(tmp_path):
    # the README's former example: 12 um film, 0.9 pli plus a 10 pli nip -> 57 MPa wound on
    case = tmp_path / "old.toml"
    case.write_text(
        """
[web]
thickness = "12 um"
width = "1.2 m"
E_theta = "4.9 GPa"
radial_modulus = { law = "pfeiffer", K1 = "10 kPa", K2 = 100 }
[core]
outer_radius = "3.8 cm"
stiffness = "20 GPa"
[winding]
outer_radius = "4 cm"
tension = "0.9 pli"
nip_load = "10 pli"
friction = 0.3
"""
    )
    res = runner.invoke(app, ["run", str(case), "--json"])
    assert res.exit_code == 0, res.output
    assert "warning: winding.tension: wound-on stress 56.9 MPa" in res.output
    assert "mu N / h = 43.8 MPa" in res.output


def test_help_keeps_bracketed_units_and_sections():
    # help texts are plain text (rich_markup_mode=None): "[Rho]", "[uncertainty]" and
    # "[defects]"-style words are units and case sections, and must not vanish as markup
    for cmd, word in (
        (["run", "--help"], "[uncertainty]"),
        (["readings", "--help"], "[Rho]"),
        (["fit-stack", "--help"], "[kPa]"),
    ):
        res = runner.invoke(app, cmd, env={"COLUMNS": "200"})
        assert res.exit_code == 0 and word in res.output, (cmd, res.output)


# issue 22.2: a value set over the case is reported as set, with its source; nothing claims the
# case file's value. A roll spring given in [tester] skips the contact solve (a run is cheap).
PROVENANCE_CASE = """title = "PET1 wound at 26.7 N"
[web]
preset = "PET1"
[core]
outer_radius = "4.45 cm"
rigid = true
[winding]
outer_radius = "6 cm"
tension = "26.7 N"
[tester]
instrument = "rho-meter"
roll_spring = { alpha = "2.6e8 N/m^2", beta = "1.05e5 N/m" }
"""


def _inputs_by_key(data):
    return {v["key"]: v for v in data["case"]["inputs"]}


def test_run_set_shows_the_value_used_and_its_source(tmp_path):
    import woundroll

    case = tmp_path / "pet1.toml"
    case.write_text(PROVENANCE_CASE, encoding="utf-8")
    res = runner.invoke(
        app,
        ["run", str(case), "--set", 'winding.tension="40 N"', "--out", str(tmp_path / "o")]
        + ["--report"],
    )
    assert res.exit_code == 0, res.output
    # the printed inputs: the value used, from --set; the case file's 26.7 N is not listed
    assert re.search(r"winding\.tension\s*│\s*40 N\s*│\s*--set", res.output), res.output
    assert re.search(r"core\.outer_radius\s*│\s*4\.45 cm\s*│\s*case file", res.output)
    assert re.search(r"web\.thickness\s*│.*│\s*preset PET1", res.output)
    assert "26.7 N\n" not in res.output.replace(" ", "")
    data = json.loads((tmp_path / "o" / "result.json").read_text(encoding="utf-8"))
    assert data["case"]["title"] == "PET1 wound at 26.7 N (winding.tension = 40 N by --set)"
    assert data["case"]["case_title"] == "PET1 wound at 26.7 N"
    assert data["case"]["overrides"] == [
        {"key": "winding.tension", "given": "40 N", "source": "--set"}
    ]
    inputs = _inputs_by_key(data)
    assert inputs["winding.tension"] == {
        "key": "winding.tension",
        "value": 40.0,  # "40 N" in SI: exact
        "unit": "N",
        "given": "40 N",
        "source": "--set",
    }
    assert inputs["core.outer_radius"]["source"] == "case file"
    assert inputs["core.outer_radius"]["value"] == pytest.approx(0.0445, rel=1e-12)  # 4.45 cm
    assert inputs["web.thickness"]["source"] == "preset PET1"
    assert inputs["winding.nip_load"] == {
        "key": "winding.nip_load",
        "value": 0.0,
        "unit": "N/m",
        "given": None,
        "source": "default",
    }
    # the numbers are those of the overridden value: the same as a case file saying 40 N
    direct = woundroll.run(woundroll.load_case(_toml_dict(PROVENANCE_CASE, "40 N")))
    assert data["winding"]["core_pressure_Pa"] == direct.winding.core_pressure
    html = (tmp_path / "o" / "report.html").read_text(encoding="utf-8")
    assert "<h1>PET1 wound at 26.7 N (winding.tension = 40 N by --set)</h1>" in html


def _toml_dict(text, tension):
    import tomllib

    data = tomllib.loads(text)
    data["winding"]["tension"] = tension
    return data


def test_report_set_shows_the_value_used_and_its_source(tmp_path):
    case = tmp_path / "pet1.toml"
    case.write_text(PROVENANCE_CASE, encoding="utf-8")
    res = runner.invoke(
        app,
        ["report", str(case), "--set", "winding.tension=40 N", "--set", "winding.friction=0.2"]
        + ["--out", str(tmp_path), "--quiet"],
    )
    assert res.exit_code == 0, res.output
    html = (tmp_path / "report.html").read_text(encoding="utf-8")
    title = re.search(r"<h1>(.*?)</h1>", html).group(1)
    assert title == (
        "PET1 wound at 26.7 N (winding.tension = 40 N, winding.friction = 0.2 by --set)"
    )
    # the input rows: key, value, unit, source cells
    cells = r'<td><code>([a-z_.]+)</code></td><td class="num">([^<]*)</td><td>([^<]*)</td>'
    rows = {
        m.group(1): m.groups()[1:]
        for m in re.finditer(cells + r'<td class="src">([^<]*)</td>', html)
    }
    assert rows["winding.tension"] == ("40", "N", "--set")
    assert rows["winding.friction"][2] == "--set"
    assert rows["core.outer_radius"][2] == "case file"
    assert rows["winding.nip_load"][2] == "default"


def test_set_provenance_in_python():
    import woundroll

    c = woundroll.load_case("pet1-26.7N", ["web.radial_modulus.K2=80"])
    assert c.source_of("web.radial_modulus.K2") == "--set"
    assert c.source_of("web.radial_modulus") == "--set"  # a table with a value set inside
    assert c.source_of("web.radial_modulus.K1") == "preset PET1"
    assert c.source_of("winding.tension") == "case file"
    assert c.source_of("winding.nip_load") == "default"
    assert c.display_title.endswith("(web.radial_modulus.K2 = 80 by --set)")
    # a flag that sets a key names itself (run --no-update sets contact.no_update)
    flagged = woundroll.load_case("pet1-26.7N", [("contact.no_update=true", "--no-update")])
    assert flagged.source_of("contact.no_update") == "--no-update" and flagged.contact.no_update
    assert flagged.display_title.endswith("(contact.no_update = true by --no-update)")
    plain = woundroll.load_case("pet1-26.7N")
    assert plain.display_title == plain.title and plain.overrides == ()
    # another front end names itself as the source (the web page: "web form")
    from woundroll.case import FROM_WEB_FORM, case_from_dict

    data = {**_toml_dict(PROVENANCE_CASE, "26.7 N")}
    over = [("winding.tension", "2 pli")]
    c = case_from_dict(data, overrides=over, override_source=FROM_WEB_FORM)
    assert c.source_of("winding.tension") == "web form"
    assert c.winding.tension == ("force_per_length", pytest.approx(350.2536704929527, rel=1e-12))
    assert data["winding"]["tension"] == "26.7 N"  # the caller's table is left alone


def test_run_json_loads_no_printing_or_pool_machinery():
    """``woundroll run CASE --json`` (the command a sweep or a script calls thousands of
    times) imports neither rich (~45 ms: nothing is printed through it), multiprocessing
    and concurrent.futures (one roll has no pool), numba (the kernels load through
    llvmlite), matplotlib (no plot asked) nor typer (its plain form runs without the
    parser: app/cli/run_core.py): issue 23's start-up. A fresh interpreter: the test
    process itself has imported everything."""
    import subprocess
    import sys

    code = (
        "import sys, io, contextlib\n"
        "sys.argv = ['woundroll', 'run', 'pet1-26.7N', '--json']\n"
        "from woundroll.app.cli import main\n"
        "buf = io.StringIO()\n"
        "try:\n"
        "    with contextlib.redirect_stdout(buf):\n"
        "        main()\n"
        "except SystemExit as e:\n"
        "    assert not e.code, e.code\n"
        "assert '\"hardness\"' in buf.getvalue()\n"
        "heavy = ('rich', 'multiprocessing', 'concurrent.futures.process', 'numba',"
        " 'matplotlib', 'scipy.sparse', 'typer')\n"
        "print(','.join(m for m in heavy if m in sys.modules))\n"
        # the collector, paused while the command started, is on again (util/gc_pause.py)
        "import gc\n"
        "assert gc.isenabled() and gc.get_freeze_count() > 0, gc.get_freeze_count()\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr[-2000:]
    assert out.stdout.strip() == "", out.stdout


@pytest.mark.parametrize(
    "args",
    [
        ["run", "--help"],
        ["run"],
        ["run", "pet1-26.7N", "--fields", "all"],
        ["run", "pet1-26.7N", "--bogus"],
        ["cases"],
        ["fit-stack", "--help"],
    ],
)
def test_one_command_group_behaves_as_the_whole(args):
    """``main`` gives click only the command it runs (``entry._app_for``): its help, errors
    and exit codes are those of the whole group."""
    from woundroll.app.cli.entry import _app_for

    one = _app_for(args)
    assert one is not app and [c.name for c in one.registered_commands] == [args[0]]
    whole, alone = runner.invoke(app, args), runner.invoke(one, args)
    assert (alone.exit_code, alone.output) == (whole.exit_code, whole.output)


def test_anything_but_a_command_goes_to_the_whole_group():
    from woundroll.app.cli.entry import _app_for

    for args in ([], ["--help"], ["--version"], ["rnu", "pet1-26.7N"]):
        assert _app_for(args) is app


@pytest.mark.parametrize(
    ("args", "plain"),
    [
        (["run", "pet1-26.7N", "--json"], {"case": "pet1-26.7N", "as_json": True, "set_": None}),
        (
            ["run", "a.toml", "--set", "web.width=1 m", "-q", "--set", "x=2", "--no-update"],
            {"case": "a.toml", "set_": ["web.width=1 m", "x=2"], "quiet": True, "no_update": True},
        ),
        (["run", "pet1-26.7N", "--quiet"], {"case": "pet1-26.7N", "quiet": True, "set_": None}),
        (["run"], None),
        (["run", "--json", "pet1-26.7N"], None),
        (["run", "pet1-26.7N", "--set"], None),
        (["run", "pet1-26.7N", "--set", "-x"], None),
        (["run", "pet1-26.7N", "--set=a=1"], None),
        (["run", "pet1-26.7N", "--out", "o"], None),
        (["run", "pet1-26.7N", "--help"], None),
        (["run", "pet1-26.7N", "--"], None),
        (["cases"], None),
        ([], None),
    ],
)
def test_plain_run_forms(args, plain):
    """Only ``run CASE`` with ``--set VALUE``, ``--json``, ``--quiet``/``-q`` and
    ``--no-update`` skip typer; anything else is parsed by it."""
    from woundroll.app.cli.run_core import plain_run_args

    assert plain_run_args(args) == plain


def test_completion_requests_go_to_typer(monkeypatch):
    from woundroll.app.cli.run_core import plain_run_args

    monkeypatch.setenv("_WOUNDROLL_COMPLETE", "bash_complete")
    assert plain_run_args(["run", "pet1-26.7N", "--json"]) is None


def test_plain_run_ends_as_the_group_does(monkeypatch, capsys):
    """Exit statuses of ``typer.Exit``, ``Aborted!`` on an interrupt, and an unexpected error
    marked for typer's exception hook, as when typer runs the command."""
    import typer

    from woundroll.app.cli import run_core

    def raising(exc):
        def run_command(**kwargs):
            raise exc

        return run_command

    monkeypatch.setattr(run_core, "run_command", raising(typer.Exit(3)))
    with pytest.raises(SystemExit) as stop:
        run_core.run_plain({"case": "x"})
    assert stop.value.code == 3
    monkeypatch.setattr(run_core, "run_command", raising(KeyboardInterrupt()))
    with pytest.raises(SystemExit) as stop:
        run_core.run_plain({"case": "x"})
    assert stop.value.code == 1 and "Aborted!" in capsys.readouterr().err
    bug = RuntimeError("a bug")
    monkeypatch.setattr(run_core, "run_command", raising(bug))
    monkeypatch.setattr(sys, "excepthook", sys.excepthook)
    with pytest.raises(RuntimeError):
        run_core.run_plain({"case": "x"})
    from typer.main import _typer_developer_exception_attr_name, except_hook

    assert hasattr(bug, _typer_developer_exception_attr_name) and sys.excepthook is except_hook
    # the plain road marks it with typer's defaults: the group keeps them
    pretty = [f"pretty_exceptions_{k}" for k in ("enable", "show_locals", "short")]
    default = typer.Typer()
    assert all(getattr(app, k) == getattr(default, k) for k in pretty)


def test_plain_run_is_the_typer_run(tmp_path):
    """The same outputs, messages and exit statuses through either road (a fresh process
    each: the script's entry point and the command group's)."""
    code = (
        "import atexit, os, sys\n"
        "atexit.register(lambda: print('atexit handlers ran', file=sys.stderr))\n"
        "sys.argv = ['woundroll', *sys.argv[2:]]\n"
        "if os.environ['ROAD'] == 'plain':\n"
        "    from woundroll.app.cli import main\n"
        "else:\n"
        "    from woundroll.app.cli.entry import main\n"
        "main()\n"
    )
    for args in (
        ["run", "pet1-26.7N", "--set", "web.thickness=0", "--json"],
        ["run", "pet1-26.7N", "--set", "winding.tension=30 N"],
    ):
        got = {}
        for road in ("plain", "group"):
            env = {**os.environ, "ROAD": road}
            proc = subprocess.run(
                [sys.executable, "-c", code, "-", *args], capture_output=True, text=True, env=env
            )
            got[road] = (proc.returncode, proc.stdout, proc.stderr)
        assert got["plain"] == got["group"], args
        assert got["plain"][2].endswith("atexit handlers ran\n")  # also without the teardown
