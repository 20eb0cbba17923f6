"""End to end in a real browser: headless Chromium from the Debian package (/usr/bin/chromium,
/usr/bin/chromedriver) driven by selenium against `woundroll serve`'s app under uvicorn.

Skipped, with the reason printed by ``pytest -ra``, where Chromium is not installed
(``apt-get install chromium chromium-driver``; .ci/run installs it).
"""

import json
import os
import shutil
import socket
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

import numpy as np
import pytest

CHROMIUM = shutil.which("chromium") or "/usr/bin/chromium"
CHROMEDRIVER = shutil.which("chromedriver") or "/usr/bin/chromedriver"
if not (os.path.exists(CHROMIUM) and os.path.exists(CHROMEDRIVER)):
    pytest.skip(
        "browser tests skipped: Chromium not installed (apt-get install chromium chromium-driver)",
        allow_module_level=True,
    )
selenium = pytest.importorskip("selenium", reason="browser tests skipped: selenium missing")
uvicorn = pytest.importorskip("uvicorn", reason="browser tests skipped: uvicorn missing")

from selenium import webdriver  # noqa: E402
from selenium.webdriver.chrome.service import Service  # noqa: E402
from selenium.webdriver.common.by import By  # noqa: E402
from selenium.webdriver.common.print_page_options import PrintOptions  # noqa: E402
from selenium.webdriver.support.ui import Select, WebDriverWait  # noqa: E402

from woundroll.app.web import MAX_CASE_BYTES, create_app  # noqa: E402

TENSION = "2 pli"


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@pytest.fixture(scope="module")
def server():
    port = _free_port()
    config = uvicorn.Config(create_app(), host="127.0.0.1", port=port, log_level="warning")
    srv = uvicorn.Server(config)
    th = threading.Thread(target=srv.run, daemon=True)
    th.start()
    t0 = time.time()
    while not srv.started:
        assert time.time() - t0 < 30, "uvicorn did not start"
        time.sleep(0.05)
    yield f"http://127.0.0.1:{port}"
    srv.should_exit = True
    th.join(10)


@pytest.fixture(scope="module")
def browser():
    opts = webdriver.ChromeOptions()
    opts.binary_location = CHROMIUM
    profile = tempfile.mkdtemp(prefix="woundroll-chromium-")
    for flag in (
        "--headless",
        "--no-sandbox",
        "--disable-gpu",
        "--disable-quic",
        "--no-first-run",
        "--disable-background-networking",
        "--disable-component-update",
        "--disable-sync",
        "--disable-dev-shm-usage",
        "--window-size=1300,1400",
        f"--user-data-dir={profile}",
    ):
        opts.add_argument(flag)
    # the Debian chromedriver, never a downloaded one
    drv = webdriver.Chrome(service=Service(executable_path=CHROMEDRIVER), options=opts)
    drv.set_page_load_timeout(60)
    yield drv
    drv.quit()
    shutil.rmtree(profile, ignore_errors=True)


@pytest.fixture(scope="module")
def cli_json():
    """The CLI's JSON for the case the browser runs (a real process, as a user would)."""
    exe = Path(sys.executable).with_name("woundroll")
    out = subprocess.run(
        [str(exe), "run", "pet1-26.7N", "--set", f"winding.tension='{TENSION}'", "--json"],
        capture_output=True,
        text=True,
        check=True,
        timeout=300,
    )
    return json.loads(out.stdout)


def _wait(drv, cond, timeout=180):
    return WebDriverWait(drv, timeout, poll_frequency=0.1).until(cond)


def _pick(drv, name):
    Select(drv.find_element(By.ID, "case-pick")).select_by_value(name)
    _wait(
        drv,
        lambda d: (
            f"{name.split('-')[0].upper()}"
            in d.find_element(By.ID, "case-text").get_property("value")
        ),
        30,
    )


def _run(drv):
    drv.find_element(By.ID, "run").click()


def _set(drv, elem_id, text):
    e = drv.find_element(By.ID, elem_id)
    drv.execute_script("arguments[0].value = arguments[1];", e, text)


def test_run_matches_cli_and_renders(server, browser, cli_json, tmp_path):
    drv = browser
    drv.get(server + "/")
    assert drv.title == "woundroll"
    _pick(drv, "pet1-26.7N")
    drv.find_element(By.ID, "f-winding.tension").send_keys(TENSION)
    _set(drv, "readings-text", "position [in],rho\n1,50\n3,52\n5,51\n")
    _run(drv)
    _wait(drv, lambda d: d.find_elements(By.ID, "summary"))
    # every number on the page equals the CLI's JSON (full precision in data-value)
    flat = {}

    def walk(node, prefix):
        for k, v in node.items():
            if isinstance(v, dict):
                walk(v, f"{prefix}{k}.")
            elif isinstance(v, int | float) and not isinstance(v, bool):
                flat[f"{prefix}{k}"] = v

    walk({k: v for k, v in cli_json.items() if k not in ("case", "schema_version")}, "")
    cells = drv.find_elements(By.CSS_SELECTOR, "#numbers td[data-key]")
    shown = {c.get_attribute("data-key"): float(c.get_attribute("data-value")) for c in cells}
    for key in (
        "hardness.reading",
        "hardness.rho_fd",
        "hardness.rho_energy",
        "winding.core_pressure_Pa",
        "contact.alpha_N_per_m2",
    ):
        assert shown[key] == flat[key], key
    timing = {k for k in flat if "solve_time" in k}  # wall-clock: differs run to run
    assert {k: shown[k] for k in flat if k not in timing} == {
        k: float(flat[k]) for k in flat if k not in timing
    }
    summary = drv.find_element(By.ID, "summary").text
    assert f"{cli_json['hardness']['reading']:.1f}" in summary
    # defect-risk flags on every run
    assert "starring" in drv.find_element(By.ID, "defects").text
    assert drv.find_element(By.ID, "defect-risk").text.startswith("defect risk: ")
    # measured readings beside the prediction
    assert drv.find_element(By.CSS_SELECTOR, '[data-key="measured.n"]').text == "3"
    # the profiler's view of the measured profile (issue 22 item 9)
    from woundroll.app.web import readings_from_text
    from woundroll.assess.profile_check import check_profile
    from woundroll.case import load_case

    pet1 = load_case("pet1-26.7N")
    want = check_profile(readings_from_text("position [in],rho\n1,50\n3,52\n5,51\n", pet1))
    assert drv.find_element(By.ID, "profile-verdict").text == want.verdict
    # the inputs used and where each came from (issue 22 item 2)
    src = {
        tr.get_attribute("data-key"): tr.find_elements(By.TAG_NAME, "td")
        for tr in drv.find_elements(By.CSS_SELECTOR, "#inputs tr[data-key]")
    }
    assert [c.text for c in src["winding.tension"]][2:] == [TENSION, "350.254 N/m", "web form"]
    assert src["winding.outer_radius"][4].text == "case file"
    assert src["winding.outer_radius"][2].text == "13.34 cm"
    assert src["web.thickness"][4].text == "preset PET1"
    # the hoop stress is the smooth layer mean; the impact's clock starts at first contact
    cap = drv.find_element(By.CSS_SELECTOR, "#plot-sigma-t .cap").text
    assert cap.startswith("hoop stress (mean over each layer)")
    imp = drv.find_element(By.ID, "plot-impact")
    labels = [t.text for t in imp.find_elements(By.TAG_NAME, "text")]
    assert "time since first contact [ms]" in labels and "0" in labels
    for pid in ("plot-sigma-r", "plot-profile", "plot-impact"):
        assert drv.find_element(By.ID, pid).find_elements(By.TAG_NAME, "polyline")
    # zoom into a lane: a wheel event narrows the x axis of the profile plot
    svg = drv.find_element(By.CSS_SELECTOR, "#plot-sigma-r svg")
    before = svg.get_attribute("innerHTML")
    drv.execute_script(
        "const s = arguments[0], r = s.getBoundingClientRect();"
        "s.dispatchEvent(new WheelEvent('wheel', {deltaY: -100, clientX: r.left + r.width / 2,"
        " clientY: r.top + r.height / 2, bubbles: true, cancelable: true}));",
        svg,
    )
    assert svg.get_attribute("innerHTML") != before
    # screenshot, not blank: many distinct colours and contrast
    shot = Path(os.environ.get("WOUNDROLL_SCREENSHOT_DIR", tmp_path)) / "page.png"
    assert drv.save_screenshot(str(shot))
    import matplotlib.image as mpimg

    img = mpimg.imread(shot)[..., :3]
    assert img.shape[0] > 500 and img.shape[1] > 800
    assert img.std() > 0.05
    assert len(np.unique((img * 255).astype(np.uint8).reshape(-1, 3), axis=0)) > 100
    # the report: a link to a self-contained page that prints on A4 and Letter
    href = drv.find_element(By.ID, "report-link").get_attribute("href")
    drv.get(href)
    assert "case hash" in drv.find_element(By.TAG_NAME, "body").text
    for w, h in ((21.0, 29.7), (21.59, 27.94)):
        po = PrintOptions()
        po.page_width, po.page_height = w, h
        import base64

        pdf = base64.b64decode(drv.print_page(po))
        assert pdf.startswith(b"%PDF") and pdf.count(b"/Type /Page") >= 3


BAD = [
    # (how to make it bad, error box id, text expected in the one-line message)
    ("case-text", "title = ", "err-case", "case: not valid TOML"),
    ("f-winding.tension", "3 furlong", "err-winding.tension", "winding.tension: "),
    ("f-web.thickness", "1 psi", "err-web.thickness", "web.thickness: "),
    ("f-winding.outer_radius", "2 cm", "err-winding.outer_radius", "winding.outer_radius: "),
    ("readings-text", "position [in],rho\n3,abc\n", "err-readings", "readings: "),
    ("case-text", "PATH", "err-case", "winding.thickness_profile: the web page takes no file"),
    ("case-text", "BIG", "err-case", f"at most {MAX_CASE_BYTES} bytes"),
    ("case-text", "UNKNOWN", "err-case", "core.rigidity: unknown key"),
    ("f-winding.friction", "lots", "err-winding.friction", "expects a number (e.g. '0.3')"),
    # outside the Rho scale 0-100: the line and value named (issue 22 item 3)
    (
        "readings-text",
        "position [in],rho\n1,-50\n2,5000\n",
        "err-readings",
        "readings: readings.csv line 2, column 'rho': -50 Rho is off the Rho-meter's scale",
    ),
]


@pytest.mark.parametrize(("elem", "value", "box", "text"), BAD)
def test_bad_input_beside_the_field(server, browser, elem, value, box, text):
    drv = browser
    drv.get(server + "/")
    _pick(drv, "pet1-26.7N")
    case = drv.find_element(By.ID, "case-text").get_property("value")
    if value == "PATH":
        value = case.replace(
            'tension = "26.7 N"', 'tension = "26.7 N"\nthickness_profile = "/etc/hosts"'
        )
    elif value == "BIG":
        value = case + "#" * MAX_CASE_BYTES
    elif value == "UNKNOWN":
        value = case.replace('E = "200 GPa"', 'E = "200 GPa"\nrigidity = 1')
    _set(drv, elem, value)
    _run(drv)
    msg = _wait(drv, lambda d: d.find_element(By.ID, box).text, 60)
    assert text in msg and "\n" not in msg and "Traceback" not in msg
    # the server keeps serving: a good run right after
    _set(drv, elem, case if elem == "case-text" else "")
    _run(drv)
    _wait(drv, lambda d: d.find_elements(By.ID, "summary"))
    assert drv.find_element(By.ID, box).text == ""


def test_long_run_shows_progress_and_cancels(server, browser):
    drv = browser
    drv.get(server + "/")
    _pick(drv, "pet3-2.3MPa")
    _run(drv)
    _wait(drv, lambda d: d.find_element(By.ID, "cancel").is_enabled(), 30)
    drv.find_element(By.ID, "cancel").click()
    _wait(drv, lambda d: d.find_element(By.ID, "stage").text == "cancelled", 120)
    assert drv.find_element(By.ID, "run").is_enabled()


def _results_count(drv):
    return len(drv.find_elements(By.ID, "summary"))


def test_every_field_error_shown_at_once(server, browser):
    drv = browser
    drv.get(server + "/")
    _pick(drv, "pet1-26.7N")
    _set(drv, "f-winding.tension", "3 furlong")
    _set(drv, "f-winding.friction", "lots")
    _set(drv, "f-web.thickness", "1 psi")
    _set(drv, "readings-text", "position [in],rho\n1,abc\n")
    _run(drv)
    _wait(drv, lambda d: d.find_element(By.ID, "err-readings").text, 60)
    for box, text in (
        ("err-winding.tension", "winding.tension: '3 furlong'"),
        ("err-winding.friction", "winding.friction: expects a number"),
        ("err-web.thickness", "web.thickness: '1 psi'"),
        ("err-readings", "readings: "),
    ):
        msg = drv.find_element(By.ID, box).text
        assert msg.startswith(text) and "\n" not in msg, (box, msg)
    assert drv.find_element(By.ID, "err-web.width").text == ""
    assert "bad" in drv.find_element(By.ID, "f-winding.friction").get_attribute("class")


def test_oversize_upload_stops_the_run(server, browser, tmp_path):
    from woundroll.app.web import MAX_READINGS_BYTES

    drv = browser
    drv.get(server + "/")
    _pick(drv, "pet1-26.7N")
    big = tmp_path / "big.csv"
    big.write_text("position [in],rho\n" + "1,50\n" * (MAX_READINGS_BYTES // 5), encoding="utf-8")
    drv.find_element(By.ID, "readings-file").send_keys(str(big))
    msg = _wait(drv, lambda d: d.find_element(By.ID, "err-readings").text, 30)
    assert "big.csv" in msg and f"at most {MAX_READINGS_BYTES} bytes" in msg
    # Run does not go on without the readings the user chose
    _run(drv)
    time.sleep(1.0)
    assert drv.find_element(By.ID, "err-readings").text == msg
    assert drv.find_element(By.ID, "stage").text == "idle" and _results_count(drv) == 0
    # a file that fits replaces it; the run goes on with its readings
    small = tmp_path / "small.csv"
    small.write_text("position [in],rho\n1,50\n3,52\n", encoding="utf-8")
    drv.find_element(By.ID, "readings-file").send_keys(str(small))
    _wait(drv, lambda d: "3,52" in d.find_element(By.ID, "readings-text").get_property("value"))
    assert drv.find_element(By.ID, "err-readings").text == ""
    _run(drv)
    _wait(drv, lambda d: d.find_elements(By.CSS_SELECTOR, '[data-key="measured.n"]'))
    assert drv.find_element(By.CSS_SELECTOR, '[data-key="measured.n"]').text == "2"


def _slow_fake_evaluate(self, web_stress):
    # the stand-in forward chain of tests/test_diagnosis.py, 0.3 s a run: the page has
    # time to show each stage
    import math

    from woundroll.inverse.diagnosis import ForwardPoint

    time.sleep(0.3)
    r = 50.0 + 10.0 * math.log(web_stress / 1e6)
    return ForwardPoint(float(web_stress), float(web_stress), 0.01 * web_stress, r, r, False)


def test_diagnosis_progress_sentence_and_caveat(server, browser, monkeypatch):
    from woundroll.app.web import readings_from_text
    from woundroll.case import load_case
    from woundroll.inverse.diagnosis import RollModel, diagnose

    # the server runs in this process: its jobs use the stand-in chain
    monkeypatch.setattr(RollModel, "evaluate", _slow_fake_evaluate)
    drv = browser
    drv.get(server + "/")
    _pick(drv, "pet1-26.7N")
    drv.find_element(By.ID, "f-winding.tension").send_keys("2 pli")
    readings = "position [in],rho\n1,50\n3,52\n5,51\n"
    _set(drv, "readings-text", readings)
    drv.find_element(By.ID, "diagnose").click()
    _run(drv)
    samples = []
    t0 = time.time()
    while not _results_count(drv):
        assert time.time() - t0 < 180, "the diagnosis did not finish"
        # both read in one script: the page's poll cannot run between them (two separate
        # reads once caught the text of one poll and the bar of the next)
        samples.append(
            tuple(
                drv.execute_script(
                    "return [document.getElementById('stage').textContent,"
                    " document.getElementById('progress').getAttribute('value')];"
                )
            )
        )
        time.sleep(0.05)
    running = [(t, v) for t, v in samples if t.startswith("running")]
    # never 100 % while the work goes on; after a stage is done the bar moves without a
    # value (indeterminate) and the stage says what runs now
    assert running and not any("100 %" in t for t, _ in running)
    fwd = [t for t, v in running if "diagnosis: full forward runs over tension" in t and v]
    assert fwd and all(" %" in t for t in fwd)
    check = [v for t, v in running if "diagnosis: checking the result with a full forward run" in t]
    assert check and all(v is None for v in check)
    # the sentence in the user's units (pli typed on the form), first on the page
    case = load_case("pet1-26.7N", ["winding.tension='2 pli'"])
    want = diagnose(case, readings_from_text(readings, case)).sentence("us")
    assert drv.find_element(By.ID, "diagnosis-summary").text == want
    assert "the 2 pli set point" in want
    # positions with their unit; the single-reading caveat on the page
    head = drv.find_elements(By.CSS_SELECTOR, "#diagnosis th")[0].text
    assert head == "position [in]"
    cells = drv.find_elements(By.CSS_SELECTOR, "#diagnosis tr td:first-child")
    assert [c.text for c in cells] == ["1.00", "3.00", "5.00"]
    cav = drv.find_element(By.ID, "diagnosis-caveats").text
    assert "zero-width interval at 3 of 3 positions" in cav
    assert "no repeated readings" in drv.find_element(By.ID, "diagnosis-notes").text
