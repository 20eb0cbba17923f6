"""The README runs as written (issue 22.6).

Every ``woundroll ...`` line of the README's command blocks is parsed from README.md itself and
run as the user runs it: from a directory holding the project's ``examples/`` (so the paths the
README names resolve), through the real command line (typer's runner in this process; ``serve``
in its own process), each checked for exit status 0 and for something meaningful in its output.

Most commands run exactly as written. A few would take minutes on the 2-core test machine;
:data:`CHEAP` says how each of those runs instead, and why. A README command this test does not
know fails the test, so a new line in the README gets a check here.
"""

import json
import math
import os
import re
import shlex
import socket
import subprocess
import sys
import time
import urllib.request
from pathlib import Path

import pytest
from typer.testing import CliRunner

import woundroll
from woundroll.case import load_case

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"
TEXT = README.read_text(encoding="utf-8")


def _readme_commands() -> list[str]:
    """The ``woundroll`` lines of the README's ``sh`` blocks, comments removed."""
    lines = []
    for block in re.findall(r"```sh\n(.*?)```", TEXT, re.S):
        for line in block.splitlines():
            words = shlex.split(line, comments=True)
            if words and words[0] == "woundroll":
                lines.append(shlex.join(words))
    return lines


COMMANDS = _readme_commands()

#: A small roll for the commands that run the contact model many times: 6 cm instead of
#: 13.34 cm (the readings' diagnosis runs the contact model about ten times: ~35 s on the full
#: pet1-26.7N roll, ~10 s on this one). tests/test_diagnosis.py and tests/report cover the
#: full roll.
SMALL_ROLL = ["--set", 'winding.outer_radius="6 cm"']

#: How the long commands run here (the README's arguments kept, these appended or replaced),
#: and why; "--help" checks that the command and its options exist without running it.
CHEAP: dict[str, tuple[str, ...] | str] = {
    # 61 CMD sectors take over a minute; 3 sectors exercise the same profile path
    "run pet3-2.3MPa": ("--set", "profile.sectors=3"),
    "diagnose": tuple(SMALL_ROLL),
    "report": tuple(SMALL_ROLL),
    # the optimiser runs the contact model ~50 times (~100 s); tests/test_design.py runs it
    "design": "--help",
    # the paper's study runs ten rolls for minutes; tests/test_studies.py (slow suite) runs it
    "study": "--help",
    # about 50 full model runs (~30-60 s); tests/test_site_calibration.py runs the same
    # command line on four rolls of the same kind and checks what it fits
    "calibrate": "--help",
    # 13 rolls with the contact model: 3 test the same sweep (see _cheap)
    "sweep": (),
    # a server: run in its own process by test_readme_serve
    "serve": "process",
}


def _key(command: str) -> str:
    words = shlex.split(command)
    two = " ".join(words[:3])
    return next((k for k in CHEAP if (two + " ").startswith(f"woundroll {k} ")), words[1])


def _cheap(command: str) -> list[str] | None:
    """The arguments this test runs ``command`` with (without ``woundroll``), or None for
    commands checked another way."""
    args = shlex.split(command)[1:]
    how = CHEAP.get(_key(command))
    if how in ("process",):
        return None
    if how == "--help":
        return [args[0], "--help"]
    if _key(command) == "sweep":
        return [re.sub(r":13$", ":3", a) for a in args]
    return args + list(how or ())


@pytest.fixture(scope="module")
def workdir(tmp_path_factory):
    """A directory like the project's top: ``examples/`` is there, outputs land in it."""
    d = tmp_path_factory.mktemp("readme")
    (d / "examples").symlink_to(ROOT / "examples", target_is_directory=True)
    return d


def _run(args: list[str], workdir: Path):
    from woundroll.app.cli import app

    old = Path.cwd()
    os.chdir(workdir)
    try:
        res = CliRunner().invoke(app, args, prog_name="woundroll")
    finally:
        os.chdir(old)
    assert res.exit_code == 0, f"woundroll {shlex.join(args)}\n{res.output}"
    return res.output


def _readme_number(pattern: str) -> float:
    # as a reader sees it: without the generated-number markers (docs/scripts/readme.py)
    m = re.search(pattern, " ".join(re.sub(r"<!--.*?-->", "", TEXT).split()))
    assert m, f"README no longer says {pattern!r}"
    return float(m.group(1).replace(",", ""))


def _check(command: str, out: str, workdir: Path) -> None:
    """Something meaningful about each command's output."""
    args = shlex.split(command)[1:]
    if args == ["cases"]:
        assert "pet1-26.7N" in out and "pet3-2.3MPa" in out
    elif args == ["materials"]:
        assert "PET1" in out
    elif args == ["run", "pet1-26.7N"]:
        assert re.search(r"core pressure\s*│\s*\d+\.\d kPa", out)
        assert re.search(r"rho reading \(rho-meter, roll model 2d\)\s*│\s*\d+\.\d", out)
        assert re.search(r"web\.thickness\s*│.*│\s*preset PET1", out)  # inputs and sources
    elif args[:2] == ["run", "examples/my_roll.toml"]:
        _check_my_roll(workdir / args[args.index("--out") + 1])
    elif args[:2] == ["run", "pet1-26.7N"] and "--json" in args:
        d = json.loads(out)
        inputs = {v["key"]: v for v in d["case"]["inputs"]}
        assert inputs["winding.tension"]["given"] == "2 pli"
        assert inputs["winding.tension"]["source"] == "--set"
        assert inputs["winding.tension"]["value"] == pytest.approx(350.25367, rel=1e-6)  # N/m
        assert inputs["web.radial_modulus.K2"]["value"] == 80
        assert math.isfinite(d["hardness"]["reading"])
    elif args == ["run", "newsprint-300Nm"]:
        # a paper preset with its sources reads on the Rho-meter's dial (docs: 42.9 Rho)
        m = re.search(r"rho reading \(rho-meter, roll model 2d\)\s*│\s*(\d+\.\d)", out)
        assert m and 0.0 < float(m.group(1)) < 100.0
        assert re.search(r"web\.thickness\s*│.*│\s*preset NEWSPRINT", out)
    elif args[:2] == ["run", "pet3-2.3MPa"]:
        d = json.loads((workdir / args[args.index("--out") + 1] / "result.json").read_text())
        rho = d["profile"]["reading"]  # one reading per CMD sector (3 here), on the dial
        assert len(rho) == 3 and all(0.0 <= r <= 100.0 for r in rho)
        assert len(d["profile"]["saturated"]) == 3 and d["profile"]["roll_model"] == "2d"
    elif args[0] == "fit-stack":
        # examples/stack_test.csv is the Pfeiffer curve K1 = 4.6 kPa, K2 = 70 with 1 % noise:
        # the fit finds both within 2 % (it gives 4.607 kPa and 69.93)
        k1 = float(re.search(r'K1 = "([\d.]+) kPa"', out).group(1))
        k2 = float(re.search(r"K2 = ([\d.]+)", out).group(1))
        assert k1 == pytest.approx(4.6, rel=0.02) and k2 == pytest.approx(70, rel=0.02)
    elif args[0] == "readings":
        # 3.0 in: passes 55 and 56 -> mean 55.50, SD 0.71
        assert re.search(r"│\s*3\s*│[^│]*│\s*55\.50\s*│\s*0\.71\s*│\s*2", out), out
        assert "pooled repeatability" in out
    elif args[0] == "diagnose":
        assert "diagnosis" in out and "wound-on" in out.lower()
    elif args[0] == "defects":
        assert "core crush" in out.replace("_", " ") and "telescoping" in out
    elif args[0] == "report":
        html = (workdir / args[args.index("--out") + 1] / "report.html").read_text()
        assert "<h1>" in html and "sheet.csv" in html  # the readings' file is in the report
    elif args[0] == "sweep":
        import csv

        path = workdir / args[args.index("--out") + 1] / "sweep.csv"
        rows = list(csv.DictReader(path.read_text().splitlines()))
        t = [float(r["winding.tension [N]"]) for r in rows]
        cp = [float(r["winding.core_pressure [Pa]"]) for r in rows]
        assert t == [20.0, 50.0, 80.0] and cp[0] < cp[1] < cp[2]  # more tension, more pressure
    elif args == ["calibrate-head"]:
        # the bundled head is calibrated in the default model: it stays where it is
        assert re.search(r"head_radius\s*│\s*7\.820 mm -> 7\.820 mm", out), out
        assert re.search(r"calibrated\s*│\s*77\.00 Rho", out), out
    elif args[0] == "schema":  # the JSON Schema of result.json, from the vocabulary
        d = json.loads(out)
        assert d["$schema"].endswith("2020-12/schema") and "impulse_N_s" in d["$defs"]
    elif args[1:] == ["--help"]:
        assert f"Usage: woundroll {args[0]}" in out
    else:  # pragma: no cover - a README line this test does not know
        pytest.fail(f"no check for the README command {command!r}: add one in {__file__}")


def _check_my_roll(out_dir: Path) -> None:
    d = json.loads((out_dir / "result.json").read_text())
    # the numbers the README quotes for examples/my_roll.toml, to its "about"
    assert d["winding"]["n_layers"] == _readme_number(r"([\d,]+) layers")
    mpa = _readme_number(r"core pressure of about ([\d.]+) MPa")
    assert d["winding"]["core_pressure_Pa"] == pytest.approx(mpa * 1e6, rel=0.05)
    assert d["hardness"]["roll_model"] == "2d"  # the registry's default: plane strain
    quoted = _readme_number(r"about (\d+) Rho \(the default roll model, plane strain\)")
    assert d["hardness"]["reading"] == pytest.approx(quoted, rel=0.05)  # "about", 2 digits
    assert not any(d["flags"].values()), d["warnings"]
    assert (out_dir / "winding.png").is_file()


def test_readme_names_only_shipped_files():
    named = set(re.findall(r"examples/[\w./-]+\.\w+", TEXT))
    assert {"examples/my_roll.toml", "examples/sheet.csv", "examples/stack_test.csv"} <= named
    for path in named:
        assert (ROOT / path).is_file(), path


def test_readme_toml_block_is_examples_my_roll():
    blocks = re.findall(r"```toml\n(.*?)```", TEXT, re.S)
    assert blocks == [(ROOT / "examples" / "my_roll.toml").read_text(encoding="utf-8")]
    case = load_case(ROOT / "examples" / "my_roll.toml")
    assert case.warnings == ()  # plausible: no value outside its usual range, no long run


def test_readme_lists_the_commands():
    # every command of the CLI has a README line
    import typer.main

    from woundroll.app.cli import app

    names = set(typer.main.get_command(app).commands)  # type: ignore[attr-defined]
    listed = {shlex.split(c)[1] for c in COMMANDS}
    assert names <= listed, names - listed


@pytest.mark.parametrize("command", [c for c in COMMANDS if _cheap(c) is not None])
def test_readme_command_runs(command, workdir):
    args = _cheap(command)
    out = _run(args, workdir)
    _check(command if args[-1] != "--help" else "woundroll " + " ".join(args), out, workdir)


def test_readme_serve(tmp_path):
    # `woundroll serve` as its own process on a free port: the page answers, then it stops
    (command,) = [c for c in COMMANDS if shlex.split(c)[1] == "serve"]
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    src = str(Path(woundroll.__file__).resolve().parents[1])
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([src, os.environ.get("PYTHONPATH", "")])}
    args = shlex.split(command)[1:] + ["--port", str(port)]
    proc = subprocess.Popen(
        [sys.executable, "-m", "woundroll.app.cli", *args],
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        env=env,
        cwd=tmp_path,
    )
    try:
        deadline = time.monotonic() + 60
        while True:
            try:
                with urllib.request.urlopen(f"http://127.0.0.1:{port}/", timeout=5) as r:
                    assert r.status == 200 and b"<html" in r.read().lower()
                break
            except OSError:
                assert proc.poll() is None, proc.stdout.read().decode()
                assert time.monotonic() < deadline, "the page did not answer in 60 s"
                time.sleep(0.3)
    finally:
        proc.terminate()
        proc.wait(timeout=30)
        proc.stdout.close()


def test_python_block_runs():
    # the README's Python lines, as written (pet1-26.7N with 30 N: one roll, a few seconds)
    (block,) = re.findall(r"```python\n(.*?)```", TEXT, re.S)
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    scope: dict = {}
    exec(compile(block, "README.md", "exec"), scope)  # noqa: S102 - the README's own code
    plt.close("all")
    result = scope["result"]
    assert result.case.source_of("winding.tension") == "--set"
    assert result.winding.core_pressure > 0
