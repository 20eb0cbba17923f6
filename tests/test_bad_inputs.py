"""Every kind of bad input ends in exit status 2 and one line naming the field (or the file),
within seconds: no traceback, no exit 1, no run with nonsense (issue 13's list, and more).

Each kind is a case file written to a temporary directory and run through the CLI in-process
(``woundroll run FILE -q``). The base roll is a 12 um film on a rigid 3.8 cm core wound to
5 cm, valid and quick; each kind breaks one thing.
"""

import json
import re
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from woundroll.app.cli import app

runner = CliRunner()

BASE = """
title = "t"
[web]
thickness = "12 um"
width = "0.5 m"
E_theta = "4.9 GPa"
radial_modulus = { law = "pfeiffer", K1 = "10 kPa", K2 = 100 }
[core]
outer_radius = "3.8 cm"
rigid = true
[winding]
outer_radius = "5 cm"
tension = "1 pli"
"""
LAW = '{ law = "pfeiffer", K1 = "10 kPa", K2 = 100 }'
TESTER = BASE + '[tester]\ninstrument = "rho-meter"\n'


def web(extra: str) -> str:
    return BASE.replace('E_theta = "4.9 GPa"', 'E_theta = "4.9 GPa"\n' + extra)


def wind(extra: str) -> str:
    return BASE.replace('tension = "1 pli"', 'tension = "1 pli"\n' + extra)


#: kind -> (case file content, field named in the message)
KINDS: dict[str, tuple[str | bytes, str]] = {
    # files that are not UTF-8 TOML
    "binary file": (b"\x00\x01\x02\xff\xfe garbage", "CASE"),
    "UTF-16 file": (BASE.encode("utf-16"), "CASE"),
    "Latin-1 file": (BASE.replace('"t"', '"Gr\xfc\xdfe"').encode("latin-1"), "CASE"),
    "TOML syntax": ("[web\nthickness=", "CASE"),
    "empty file": ("", "web"),
    # types
    "tabulated file not text": (
        BASE.replace(LAW, '{ law = "tabulated", file = 3 }'),
        "web.radial_modulus.file",
    ),
    "tabulated pressure not a list": (
        BASE.replace(LAW, '{ law = "tabulated", strain = [0.1, 0.2, 0.3], pressure = 5 }'),
        "web.radial_modulus.pressure",
    ),
    "tabulated strain text": (
        BASE.replace(LAW, '{ law = "tabulated", strain = "abc", pressure = [1, 2, 3] }'),
        "web.radial_modulus",
    ),
    "radial modulus a list": (BASE.replace(LAW, "[1, 2]"), "web.radial_modulus"),
    "npy map of strings": (wind('thickness_profile = "strings.npy"'), "winding.thickness_profile"),
    "binary CSV profile": (wind('thickness_profile = "bin.csv"'), "winding.thickness_profile"),
    "profile is a directory": (wind('thickness_profile = "."'), "winding.thickness_profile"),
    "missing profile file": (wind('thickness_profile = "nope.csv"'), "winding.thickness_profile"),
    "title a number": (BASE.replace('title = "t"', "title = 5"), "title"),
    "tension a boolean": (BASE.replace('"1 pli"', "true"), "winding.tension"),
    "tension a list": (BASE.replace('"1 pli"', "[1, 2]"), "winding.tension"),
    "web a string": (
        'web = "x"\n' + BASE.split("[web]")[0] + "[core]" + BASE.split("[core]")[1],
        "web",
    ),
    "contact option wrong type": (
        TESTER + '[contact]\noptions = { surface_size = "abc" }\n',
        "contact.options",
    ),
    "roll spring a string": (TESTER + 'roll_spring = "x"\n', "tester.roll_spring"),
    "sectors a string": (BASE + '[profile]\nsectors = "many"\n', "profile.sectors"),
    # keys
    "undocumented base_dir": ('base_dir = "/tmp"\n' + BASE, "base_dir"),
    "unknown contact option": (TESTER + "[contact]\noptions = { nonsense = 1 }\n", "contact"),
    "unknown winding option": (wind("options = { nonsense = 1 }"), "winding.options"),
    "unknown instrument": (BASE + '[tester]\ninstrument = "foo"\n', "tester.instrument"),
    "missing web": (BASE.split("[web]")[0] + "[core]" + BASE.split("[core]")[1], "web"),
    "measured without profile": (BASE + '[profile]\nmeasured = "x.csv"\n', "profile.measured"),
    # magnitudes outside physics
    "E_theta 1e300": (BASE.replace('"4.9 GPa"', "1e300"), "web.E_theta"),
    "E_z 1e-300": (web("E_z = 1e-300"), "web.E_z"),
    "G_r_theta 1e-300": (web("G_r_theta = 1e-300"), "web.G_r_theta"),
    "density 1e300": (web("density = 1e300"), "web.density"),
    "thickness 1e-30": (BASE.replace('"12 um"', "1e-30"), "web.thickness"),
    "thickness inf": (BASE.replace('"12 um"', '"inf m"'), "web.thickness"),
    "width 1 nm": (BASE.replace('"0.5 m"', "1e-9"), "web.width"),
    "K2 1e300": (BASE.replace("K2 = 100", "K2 = 1e300"), "web.radial_modulus"),
    "K1 1e300": (BASE.replace('"10 kPa"', '"1e300 Pa"'), "web.radial_modulus"),
    "K2 negative": (BASE.replace("K2 = 100", "K2 = -5"), "web.radial_modulus.K2"),
    "tension 1e300 N": (BASE.replace('"1 pli"', '"1e300 N"'), "winding.tension"),
    "tension negative": (BASE.replace('"1 pli"', '"-1 pli"'), "winding.tension"),
    "tension stretching the web 20 %": (BASE.replace('"1 pli"', '"1 GPa"'), "winding.tension"),
    "nip load 1e300": (wind('nip_load = "1e300 N/m"\nfriction = 0.3'), "winding.nip_load"),
    "friction 1e6": (wind('friction = 1e6\nnip_load = "1 pli"'), "winding.friction"),
    "taper fraction 5": (wind('taper = { kind = "linear", fraction = 5 }'), "winding.taper"),
    "taper table of one point": (
        wind('taper = { kind = "table", radius = ["4 cm"], factor = [1, 2] }'),
        "winding.taper",
    ),
    "core radius 1 nm": (BASE.replace('"3.8 cm"', "1e-9"), "core.outer_radius"),
    "outer radius 1e300": (
        BASE.replace('outer_radius = "5 cm"', "outer_radius = 1e300"),
        "winding.outer_radius",
    ),
    "outer radius below the core": (
        BASE.replace('outer_radius = "5 cm"', 'outer_radius = "3 cm"'),
        "winding.outer_radius",
    ),
    "wound length 1e7 m": (
        BASE.replace('outer_radius = "5 cm"\n', 'length = "1e7 m"\n'),
        "winding.length",  # the key the user wrote, not the radius it makes (issue 22.5)
    ),
    "1e300 layers": (
        BASE.replace('"12 um"', '"1e-300 m"').replace('"5 cm"', "1e300"),
        "web.thickness",
    ),
    "Poisson ratios not positive definite": (
        web('E_z = "9.8 GPa"\nnu_theta_z = 0.9'),
        "web.nu_theta_z",
    ),
    "Poisson ratio 1.5": (web("nu_theta_r = 1.5"), "web.nu_theta_r"),
    "sectors 0": (BASE + "[profile]\nsectors = 0\n", "profile.sectors"),
    # the tester
    "striker mass 1e300 kg": (TESTER + 'mass = "1e300 kg"\n', "tester.mass"),
    "head radius 1e300": (TESTER + "head_radius = 1e300\n", "tester.head_radius"),
    "release position 1 km": (TESTER + 'release_position = "1 km"\n', "tester.release_position"),
    "spring stiffness 1e300": (TESTER + "spring_stiffness = 1e300\n", "tester.spring_stiffness"),
    "roll spring alpha 1e300": (
        TESTER + "[tester.roll_spring]\nalpha = 1e300\nbeta = 1e5\n",
        "tester.roll_spring.alpha",
    ),
    "steps_per_contact 1e10": (
        TESTER + "steps_per_contact = 10000000000\n",
        "tester.steps_per_contact",
    ),
    "time_step 1e-15 s": (
        TESTER + 'time_step = "1e-15 s"\n[tester.roll_spring]\nalpha = 1e9\nbeta = 1e5\n',
        "tester.time_step",
    ),
    "restitution 2": (TESTER + "restitution = 2\n", "tester.restitution"),
    "depth_max 1 km": (TESTER + '[contact]\ndepth_max = "1 km"\n', "contact.depth_max"),
}


@pytest.fixture(scope="module")
def case_dir(tmp_path_factory):
    d = tmp_path_factory.mktemp("bad")
    np.save(d / "strings.npy", np.array([["a", "b"], ["c", "d"]]))
    (d / "bin.csv").write_bytes(b"\xff\xfe\x00\x00garbage\x00")
    return d


@pytest.mark.parametrize("kind", list(KINDS))
def test_bad_input_exit_2_one_line(case_dir: Path, kind: str):
    text, field = KINDS[kind]
    path = case_dir / (kind.replace(" ", "_") + ".toml")
    path.write_bytes(text if isinstance(text, bytes) else text.encode())
    res = runner.invoke(app, ["run", str(path), "-q"])
    lines = [line for line in res.output.splitlines() if line.strip()]
    assert res.exit_code == 2, res.output
    # one error line, last; before it at most the case's warnings ("long run: ...")
    errors = [line for line in lines if not line.startswith("warning: ")]
    assert len(errors) == 1 and lines[-1] == errors[0], res.output
    assert errors[0].startswith(f"error: {field}"), errors[0]
    assert "Traceback" not in res.output


def test_count_of_kinds():
    # the report quotes this number
    assert len(KINDS) >= 60


@pytest.mark.parametrize("outer", ["4.46 cm"])
def test_roll_too_thin_for_the_tester_names_its_size(outer):
    # PET1 (100 um) on its 4.45 cm core: 1 layer under the Rho-meter. The contact model
    # cannot mesh 1 layer: the roll's size, said as such (not a contact option the user
    # never set, not a solver failure with exit 1). (3 layers used to end here too, because
    # the FD impact on its beta = 0 spring never ended; it now reads like 2 layers, below.)
    res = runner.invoke(
        app,
        [
            "run",
            "pet1-26.7N",
            "-q",
            "--set",
            f'winding.outer_radius="{outer}"',
        ],
    )
    lines = [line for line in res.output.splitlines() if line.strip()]
    assert res.exit_code == 2, res.output
    assert len(lines) == 1 and lines[0].startswith("error: winding.outer_radius: the roll is too")


@pytest.mark.parametrize("outer", ["4.47 cm", "4.48 cm"])
def test_two_layer_roll_runs_with_both_flags(outer):
    # 2 and 3 layers (4.47, 4.48 cm): the contact mesh's half-layer surface ring
    # (docs/contact.md) meshes them, but the striker goes past the contact model's reach and
    # reads far beyond the scale; the run is valid input, so it ends with exit 0 and says
    # both, never silently.
    res = runner.invoke(
        app, ["run", "pet1-26.7N", "--json", "--set", f'winding.outer_radius="{outer}"']
    )
    assert res.exit_code == 0, res.output
    data = json.loads(res.stdout)
    assert data["flags"]["reading_outside_range"] and data["flags"]["spring_extrapolated"]


@pytest.mark.parametrize(
    ("args", "name"),
    [
        (["study", "tension", "--workers", "0"], "'--workers'"),
        (["run"], "'case'"),
        (["run", "pet1-26.7N", "--bogus"], "--bogus"),
        (["sweep"], "'case'"),
        (["nope"], "'nope'"),
    ],
)
def test_usage_errors_are_one_line(args, name):
    # an option out of range, a missing argument, an unknown option or command: one line
    # naming it with where to look, exit 2 (not click's usage block)
    res = runner.invoke(app, args)
    lines = [line for line in res.output.splitlines() if line.strip()]
    assert res.exit_code == 2, res.output
    assert len(lines) == 1 and lines[0].startswith("error: ") and name in lines[0], res.output
    assert "--help" in lines[0]


# issue 22.5: messages show the user's text as written, numbers without a false sign, the
# field the user wrote, and a failing case's error alone


def test_user_text_is_not_markup_or_emoji(tmp_path):
    # ":x:" is an emoji code and "[bold]" rich markup: both stay text in the one-line error
    f = tmp_path / "[bold]stack.csv"
    f.write_text("root:x:0:0:[red]root,b\n1,2\n", encoding="utf-8")
    res = runner.invoke(app, ["fit-stack", str(f)])
    assert res.exit_code == 2
    lines = res.output.strip().splitlines()
    assert len(lines) == 1, res.output
    assert "root:x:0:0:[red]root" in lines[0] and "[bold]stack.csv" in lines[0]
    assert "\u274c" not in res.output  # the emoji rich makes of ":x:"


def test_fit_stack_passwd_like_file_one_line(tmp_path):
    f = tmp_path / "passwd"
    f.write_text("root:x:0:0:root:/root:/bin/bash\ndaemon:x:1:1::/:/bin/false\n")
    res = runner.invoke(app, ["fit-stack", str(f)])
    assert res.exit_code == 2 and res.output.count("\n") == 1, res.output
    assert res.output.startswith("error: CSV_FILE: passwd:") and ":x:" in res.output


def test_zero_tension_prints_no_negative_zero(tmp_path):
    case = tmp_path / "zero.toml"
    case.write_text(BASE.replace('"1 pli"', '"0 N"'), encoding="utf-8")
    res = runner.invoke(app, ["run", str(case)])
    assert res.exit_code == 0, res.output
    # no tension: no pressure; "-0.0" would claim a (rounded) tensile radial stress
    assert re.search(r"core pressure\s*│\s*0\.0 kPa", res.output), res.output
    assert "-0.0" not in res.output


def test_num_drops_the_sign_of_a_rounded_zero():
    from woundroll.pipeline.summary import _num

    assert _num(-1e-12, ".1f") == "0.0"
    assert _num(-0.0, ".3g") == "0"
    assert _num(-0.06, ".1f") == "-0.1"  # a real negative value keeps its sign
    assert _num(-2e-7, ".1e") == "-2.0e-07"
    assert _num(-0.04, "+.1f") == "0.0"


def test_failing_case_prints_its_error_alone(tmp_path, monkeypatch):
    # a case with a plausibility warning (tension far below the usual range) whose run fails:
    # the error alone, not after the unrelated warning
    from woundroll.errors import InputError

    def fails(case, progress=None):
        raise InputError("the solver met something it cannot handle", "contact.options")

    monkeypatch.setattr("woundroll.pipeline.run", fails)
    case = tmp_path / "t.toml"
    case.write_text(BASE.replace('"1 pli"', '"0.001 N"'), encoding="utf-8")
    from woundroll.case import load_case

    assert load_case(case).warnings  # the premise: the case warns
    res = runner.invoke(app, ["run", str(case), "-q"])
    assert res.exit_code == 2
    assert res.output.strip().splitlines() == [
        "error: contact.options: the solver met something it cannot handle"
    ]


def test_warnings_follow_a_run_that_succeeds(tmp_path):
    case = tmp_path / "t.toml"
    case.write_text(BASE.replace('"1 pli"', '"0.001 N"'), encoding="utf-8")
    res = runner.invoke(app, ["run", str(case), "-q"])
    assert res.exit_code == 0
    assert res.output.startswith("warning: winding.tension:"), res.output
