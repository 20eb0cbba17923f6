"""The web page's API (FastAPI test client): the same numbers and one-line errors as the CLI,
no file paths, size limits, progress, cancellation; the server keeps serving."""

import json
import time

import pytest

pytest.importorskip("fastapi")
pytest.importorskip("httpx2")

from fastapi.testclient import TestClient  # noqa: E402

import woundroll  # noqa: E402
from woundroll.web import MAX_CASE_BYTES, MAX_READINGS_BYTES, create_app  # noqa: E402

# the fast roll of tests/report (explicit roll spring: milliseconds)
FAST_TOML = """title = "fast"
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


@pytest.fixture(scope="module")
def client():
    with TestClient(create_app()) as c:
        yield c


def wait(client, job, timeout=120):
    t0 = time.time()
    while time.time() - t0 < timeout:
        s = client.get(f"/api/jobs/{job}").json()
        if s["state"] not in ("queued", "running"):
            return s
        time.sleep(0.05)
    raise AssertionError("run did not finish")


def test_page_and_cases(client):
    page = client.get("/")
    assert page.status_code == 200 and "pet1-26.7N" in page.text
    assert "<script src" not in page.text and "http://" not in page.text.replace(
        'xmlns="http://www.w3.org/2000/svg"', ""
    ).replace('"http://www.w3.org/2000/svg"', "")
    text = client.get("/api/cases/pet1-26.7N").text
    assert 'tension = "26.7 N"' in text
    assert client.get("/api/cases/..%2Fetc").status_code == 404


def test_run_equals_cli_json(client):
    r = client.post("/api/run", json={"case": FAST_TOML, "overrides": {"winding.tension": "2 pli"}})
    assert r.status_code == 200, r.text
    s = wait(client, r.json()["job"])
    assert s["state"] == "done", s.get("error")
    ref = woundroll.run(_fast_case("2 pli"))
    want = json.loads(ref.to_json())
    got = s["result"]["numbers"]
    assert got["hardness.reading"] == want["hardness"]["reading"]
    assert got["winding.core_pressure_Pa"] == want["winding"]["core_pressure_Pa"]
    assert client.get(s["report_url"]).text.startswith("<!DOCTYPE html>")


def _fast_case(tension):
    import tomllib

    data = tomllib.loads(FAST_TOML)
    data["winding"]["tension"] = tension
    return woundroll.load_case(data)


@pytest.mark.parametrize(
    ("body", "field", "text"),
    [
        ({"case": "title = "}, "case", "not valid TOML"),
        (
            {"case": FAST_TOML.replace("rigid = true", "rigid = true\nrigidity = 1")},
            "core.rigidity",
            "unknown key",
        ),
        ({"case": FAST_TOML, "overrides": {"winding.tension": "3 furlong"}}, "winding.tension", ""),
        ({"case": FAST_TOML, "overrides": {"web.thickness": "1 psi"}}, "web.thickness", ""),
        (
            {"case": FAST_TOML + '[profile]\nmeasured = "/etc/passwd"\n'},
            "profile.measured",
            "no file paths",
        ),
        (
            {
                "case": FAST_TOML.replace(
                    'tension = "26.7 N"', 'tension = "26.7 N"\nthickness_profile = "/etc/hosts"'
                )
            },
            "winding.thickness_profile",
            "no file paths",
        ),
        ({"case": FAST_TOML, "readings": "position [in],rho\n3,abc\n"}, "readings", ""),
        ({"case": FAST_TOML, "readings": "x" * (MAX_READINGS_BYTES + 1)}, "readings", "at most"),
        ({"case": "#" * (MAX_CASE_BYTES + 1)}, "case", "at most"),
        ({"case": "x" * (2 * MAX_CASE_BYTES + 1)}, "case", "at most"),
        ({"case": FAST_TOML, "overrides": {"core.rigid": "false"}}, "core.rigid", "not a field"),
    ],
)
def test_bad_input_one_line_like_cli(client, body, field, text):
    r = client.post("/api/run", json=body)
    assert r.status_code == 422, r.text
    err = r.json()["error"]
    assert err["field"] == field and err["line"].startswith(f"{field}: ")
    assert "\n" not in err["line"] and text in err["line"]
    assert "/tmp" not in err["line"] and "Traceback" not in err["line"]
    assert client.get("/").status_code == 200  # still serving


def test_cli_message_is_the_same(client):
    from typer.testing import CliRunner

    from woundroll.cli import app

    res = CliRunner().invoke(app, ["run", "pet1-26.7N", "--set", "winding.tension='3 furlong'"])
    r = client.post(
        "/api/run",
        json={
            "case": client.get("/api/cases/pet1-26.7N").text,
            "overrides": {"winding.tension": "3 furlong"},
        },
    )
    assert r.json()["error"]["line"] in " ".join(res.output.split())


def test_bundled_profile_case_accepted_and_cancellable(client):
    text = client.get("/api/cases/pet3-2.3MPa").text
    r = client.post("/api/run", json={"case": text})
    assert r.status_code == 200, r.text
    job = r.json()["job"]
    assert client.post(f"/api/jobs/{job}/cancel").json()["cancel_requested"]
    s = wait(client, job)
    assert s["state"] == "cancelled"
    assert client.get(f"/jobs/{job}/report").status_code == 404


def test_readings_shown_with_prediction(client):
    readings = "position [in],rho\n0.5,52\n1.5,54\n2.5,53\n"
    r = client.post("/api/run", json={"case": FAST_TOML, "readings": readings})
    assert r.status_code == 200, r.text
    s = wait(client, r.json()["job"])
    m = s["result"]["measured"]
    assert m["n"] == 3 and m["mean"] == pytest.approx(53.0, abs=1e-12)
    pred = s["result"]["numbers"]["hardness.reading"]
    assert m["predicted_minus_measured"] == pytest.approx(pred - 53.0, abs=1e-12)
    assert any(p["id"] == "plot-profile" for p in s["result"]["plots"])
    report = client.get(s["report_url"]).text
    assert 'id="readings"' in report and "readings pasted on the web page" in report


def test_serve_port_in_use_is_one_line():
    import socket
    import subprocess
    import sys
    from pathlib import Path

    with socket.create_server(("127.0.0.1", 0)) as s:
        port = s.getsockname()[1]
        exe = Path(sys.executable).with_name("woundroll")
        r = subprocess.run(
            [str(exe), "serve", "--port", str(port)], capture_output=True, text=True, timeout=60
        )
    lines = [ln for ln in (r.stdout + r.stderr).splitlines() if ln.strip()]
    assert r.returncode == 2 and len(lines) == 1 and "--port: cannot listen" in lines[0]


def test_defects_always_and_diagnosis_on_request(client):
    r = client.post("/api/run", json={"case": FAST_TOML})
    s = wait(client, r.json()["job"])
    assert s["result"]["defects"]["risk"] in ("low", "watch", "high", "n/a")
    names = [row["name"] for row in s["result"]["defects"]["rows"]]
    assert "starring" in names and s["result"]["diagnosis"] is None
    r = client.post("/api/run", json={"case": FAST_TOML, "diagnose": True})
    assert r.status_code == 422 and r.json()["error"]["field"] == "readings"
    r = client.post(
        "/api/run",
        json={"case": FAST_TOML, "readings": "lane,rho\n1,50\n", "lane_width": "6 psi"},
    )
    assert r.json()["error"]["field"] == "readings.lane_width"


@pytest.mark.slow
def test_diagnosis_on_the_page_and_in_the_report(client):
    """Readings -> diagnosis (full forward runs through the contact model: about a minute)."""
    text = client.get("/api/cases/pet1-26.7N").text
    readings = "position [in],rho\n1,50\n3,52\n5,51\n1,51\n3,53\n"
    r = client.post("/api/run", json={"case": text, "readings": readings, "diagnose": True})
    s = wait(client, r.json()["job"], 600)
    assert s["state"] == "done", s.get("error")
    g = s["result"]["diagnosis"]
    assert len(g["rows"]) == 3 and all(row[-1] == "ok" for row in g["rows"])
    assert any(p["id"] == "plot-diagnosis" for p in s["result"]["plots"])
    rep = client.get(s["report_url"]).text
    assert 'id="diagnosis"' in rep and 'id="defects"' in rep


def test_tappi_sheet_pasted_needs_a_roll(client):
    sheet = "roll,pass,lane 1,lane 2\nA,1,50,52\nB,1,55,57\n"
    body = {"case": FAST_TOML, "readings": sheet, "lane_width": "2 in"}
    r = client.post("/api/run", json=body)
    err = r.json()["error"]
    assert err["field"] == "readings" and "holds 2 rolls (A, B): pick one" in err["line"]
    # T 834's 6 in lanes do not fit on the 6 in wide web: lane 2 lies outside
    r = client.post("/api/run", json={**body, "lane_width": "", "roll": "B"})
    assert r.json()["error"]["field"] == "readings" and "outside the roll" in r.text
    s = wait(client, client.post("/api/run", json={**body, "roll": "B"}).json()["job"])
    assert s["result"]["measured"]["mean"] == 56.0


def test_server_draws_headless():
    # report figures are drawn from the server's worker threads, where a desktop's GUI
    # backend must not be driven: the app switches matplotlib to Agg when it is created
    # (the svg backend stands in here for whatever the user's default would be)
    import matplotlib

    matplotlib.use("svg")
    create_app()
    assert matplotlib.get_backend().lower() == "agg"
