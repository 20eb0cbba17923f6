"""The registry of roll models: one default, read by every entry point.

The same roll must give the same reading whichever way it is asked: ``woundroll.run``,
``roll_stiffness`` + ``hardness_on_roll`` (the API a notebook follows), the CLI, the web
API and a sweep row. They all resolve the model in :mod:`woundroll.contact.models`, so the
readings agree to round-off (rel 1e-12: the same floating-point operations in the same
order; the JSON round trip of the CLI and the web keeps every digit).
"""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

import woundroll
from woundroll.contact import roll_stiffness
from woundroll.contact.models import (
    DEFAULT_ROLL_MODEL,
    ROLL_MODELS,
    check_model_name,
    default_model_name,
    resolve_model,
)
from woundroll.errors import InputError
from woundroll.instruments import get_instrument
from woundroll.pipeline import hardness_on_roll
from woundroll.winding.hakiel import wind

CASE = "pet1-26.7N"


@pytest.fixture(scope="module")
def by_run():
    return woundroll.run(woundroll.load_case(CASE))


def test_default_is_plane_strain_for_the_cylindrical_head():
    # the reference paper's own validated setting (issue 25, item 5): plane strain
    assert DEFAULT_ROLL_MODEL["cylinder"] == "2d"
    assert default_model_name("cylinder") == "2d"
    # heads plane strain cannot represent are read in 3D
    assert default_model_name("sphere") == "3d" == default_model_name("punch")
    assert set(DEFAULT_ROLL_MODEL.values()) <= set(ROLL_MODELS)


def test_names_and_heads_checked():
    assert resolve_model("3d", "sphere").name == "3d"
    with pytest.raises(InputError, match="takes a cylinder head") as exc:
        resolve_model("2d", "sphere", "contact.model")
    assert exc.value.field == "contact.model"
    with pytest.raises(InputError, match="'2d', '2d\\+cmd-spread', '3d'"):
        check_model_name("plane")
    with pytest.raises(InputError, match="retired.*2d\\+cmd-spread"):
        check_model_name("auto")


def test_case_file_default_and_bad_name():
    case = woundroll.load_case(CASE)
    assert case.contact.model is None
    assert case.contact.roll_model("cylinder").name == "2d"
    with pytest.raises(InputError) as exc:
        woundroll.load_case(CASE, ["contact.model='plane'"])
    assert exc.value.field == "contact.model"
    # a spherical head with the plane-strain model: refused at load time
    with pytest.raises(InputError, match="takes a cylinder head") as exc:
        woundroll.load_case(CASE, ["tester.instrument='schmidt-l'", "contact.model='2d'"])
    assert exc.value.field == "contact.model"


def test_the_json_names_the_model_behind_the_reading(by_run):
    d = by_run.to_dict()
    assert d["contact"]["model"] == "2d"
    assert d["hardness"]["roll_model"] == "2d"


def test_run_equals_roll_stiffness_and_hardness(by_run):
    case = woundroll.load_case(CASE)
    web, core = case.web.build(), case.core.build()
    r_out = case.winding.final_radius(web, core)
    w = wind(web, core, r_out, case.winding.schedule(web))
    inst = get_instrument("rho-meter")
    # the notebook path of docs/api.md: no model named, the registry's default
    st = roll_stiffness(web, core, w.radius, w.sigma_r, inst)
    assert st.model == "2d"
    h = hardness_on_roll(case.tester_setup, st, r_out - core.outer_radius, web.density)
    assert h.reading == pytest.approx(by_run.hardness.reading, rel=1e-12)


def test_cli_equals_run(by_run):
    out = subprocess.run(
        [sys.executable, "-m", "woundroll.app.cli", "run", CASE, "--json"],
        capture_output=True,
        text=True,
        check=True,
    )
    d = json.loads(out.stdout)
    assert d["hardness"]["roll_model"] == "2d"
    assert d["hardness"]["reading_model"] == pytest.approx(by_run.hardness.reading, rel=1e-12)


def test_web_api_equals_run(by_run):
    pytest.importorskip("fastapi")
    pytest.importorskip("httpx2")
    import time

    from fastapi.testclient import TestClient

    from woundroll.app.web import create_app

    with TestClient(create_app()) as client:
        text = client.get(f"/api/cases/{CASE}").text
        r = client.post("/api/run", json={"case": text})
        assert r.status_code == 200, r.text
        job = r.json()["job"]
        t0 = time.time()
        while time.time() - t0 < 120:
            s = client.get(f"/api/jobs/{job}").json()
            if s["state"] not in ("queued", "running"):
                break
            time.sleep(0.05)
    assert s["state"] == "done", s.get("error")
    assert s["result"]["numbers"]["hardness.reading"] == pytest.approx(
        by_run.hardness.shown, rel=1e-12
    )


def test_sweep_row_equals_run(by_run):
    from woundroll.app.sweep import run_sweep

    res = run_sweep(CASE, ["winding.tension=26.7 N"], workers=1)
    col = next(c for c in res.columns if c.startswith("hardness.reading"))
    assert res.column(col)[0] == pytest.approx(by_run.hardness.shown, rel=1e-12)


def test_profile_refuses_a_model_too_slow_per_sector():
    # the layered 3D roll (tens of CPU s a sector) is refused on every sector, before the
    # winding; the message names the models that may run there, 3D among them (about 82x
    # the yardstick on Table 3's 61 sectors, docs/performance.md)
    with pytest.raises(InputError, match="once per CMD sector") as exc:
        woundroll.run(woundroll.load_case("pet3-2.3MPa", ["contact.model='layered-3d'"]))
    assert exc.value.field == "contact.model"
    assert "'3d'" in str(exc.value) and "'layered'" not in str(exc.value)


def test_cli_bad_model_is_one_line_exit_2():
    out = subprocess.run(
        [sys.executable, "-m", "woundroll.app.cli", "run", CASE, "--set", "contact.model=auto"],
        capture_output=True,
        text=True,
    )
    assert out.returncode == 2
    lines = [ln for ln in out.stderr.splitlines() if ln.strip()]
    assert (
        len(lines) == 1 and lines[0].startswith("error: contact.model:") and "retired" in lines[0]
    )
