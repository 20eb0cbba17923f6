"""A report an engineer can send (issue 22, item 8): roll/lot/customer in the header (options
or the readings file), the verdict first, inputs before results, the profiler's view and the
trend, equation references explained once, and a PDF printed by headless Chromium whose pages
keep every heading with its content."""

import re
import shutil
import subprocess
from pathlib import Path

import pytest
from typer.testing import CliRunner

from woundroll.app.cli import app

DATA = Path(__file__).resolve().parents[2] / "examples" / "data"
# explicit roll spring: the report's content is under test, not the physics (milliseconds)
FAST = [
    "tester.roll_spring={alpha='2.6e8 N/m^2', beta='1.05e5 N/m'}",
    "winding.outer_radius='6 cm'",
]
SETS = [a for s in FAST for a in ("--set", s)]


def _readings(tmp_path: Path) -> Path:
    body = (DATA / "readings_rho_3passes.csv").read_text().splitlines()
    rows = [ln for ln in body if not ln.startswith("#")]
    p = tmp_path / "roll_2611-07A.csv"
    p.write_text(
        "# Roll: 2611-07A\n# Lot: L-2611\n# Customer: Nordfilm AB\n" + "\n".join(rows) + "\n"
    )
    return p


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("rep")
    sheet = _readings(tmp)
    # with readings the report runs the diagnosis through the contact model (no explicit
    # roll spring): a 6 cm roll keeps it to about 15 s
    res = CliRunner().invoke(
        app,
        [
            "report",
            "pet1-26.7N",
            "--set",
            FAST[1],
            "--readings",
            str(sheet),
            "--lot",
            "L-2611-B",
            "--trend",
            str(DATA / "tappi_t834_sheet.csv"),
            "--out",
            str(tmp / "out"),
            "-q",
        ],
    )
    assert res.exit_code == 0, res.output
    return tmp / "out" / "report.html"


def _order(html: str, *needles: str) -> list[int]:
    return [html.index(n) for n in needles]


def test_header_ids_from_file_and_options(report):
    html = report.read_text(encoding="utf-8")
    ids = re.search(r'<table class="ids" id="ids">(.*?)</table>', html, re.S).group(1)
    # the file's roll and customer; the option's lot wins over the file's, and says so
    assert "<th>Roll ID</th><td>2611-07A</td>" in ids and "from roll_2611-07A.csv" in ids
    assert "<th>Lot</th><td>L-2611-B</td>" in ids
    assert "<th>Customer</th><td>Nordfilm AB</td>" in ids
    assert "lot given as &#39;L-2611-B&#39; on the command line" in html
    # the title names the override the report was run with, then the roll
    title = re.search(r"<title>(.*?)</title>", html, re.S).group(1)
    assert title.startswith("PET1 wound at 26.7 N (reference paper, Table 2)")
    assert "by --set" in title and title.endswith(" - roll 2611-07A - woundroll report")


def test_verdict_first_inputs_before_results(report):
    html = report.read_text(encoding="utf-8")
    pos = _order(
        html,
        'id="summary"',
        'id="inputs"',
        'id="readings"',
        'id="trend"',
        'id="numbers"',
        'id="defects"',
        'id="diagnosis"',
        'id="assumptions"',
    )
    assert pos == sorted(pos)
    summary = re.search(r'<section id="summary".*?</section>', html, re.S).group(0)
    assert 'class="level-watch"><span class="label">defect risk</span>' in summary
    assert 'measured profile</span><span class="value">very good (CoV 2.3 %)' in summary
    assert "Trend over 4 rolls: in control." in summary


def test_profilers_view_and_trend_in_the_report(report):
    html = report.read_text(encoding="utf-8")
    assert 'id="profile-check"' in html and "+-5 % of the roll mean" in html
    # the trend: three sheet rolls, then this report's roll, X-mR limits stated with a source
    rows = re.findall(r"<tr><td class=\"num\">(\d)</td><td class=\"\">([^<]+)</td>", html)
    assert rows == [("1", "2611-01"), ("2", "2611-02"), ("3", "2611-03"), ("4", "2611-07A")]
    assert "centre +- 2.66 mR-bar (Montgomery" in html and "Provisional: 4 rolls" in html


def test_equation_references_explained_once(report):
    html = report.read_text(encoding="utf-8")
    assert html.count("Numbers in braces") == 1
    first_ref = re.search(r"\{\d+\}", html.split("<body>", 1)[1]).start()
    note = html.split("<body>", 1)[1].index("Numbers in braces")
    assert note < first_ref  # explained before the first use


def test_print_css_keeps_headings_with_content(report):
    html = report.read_text(encoding="utf-8")
    css = re.search(r"@media print\s*{(.*?)\n  }", html, re.S).group(1)
    assert re.search(r"h1, h2, h3 \{ break-after: avoid", css)
    assert re.search(r"\.lead, figure, table, \.keep.*break-inside: avoid", css)
    # every h2 opens a block kept whole (a .lead or .keep unit), or is the summary's own
    body = html.split("<body>", 1)[1]
    for m in re.finditer(r"<h2>", body):
        before = body[: m.start()].rstrip()
        assert before.endswith(('<div class="lead">', '<div class="keep">')) or before.endswith(
            '<section id="summary" class="keep">'
        ), body[m.start() - 80 : m.start() + 40]


def print_to_pdf(html: Path, pdf: Path) -> int:
    """Print ``html`` to ``pdf`` with headless Chromium (the printer's default page: Letter
    here) and return the page count (docs/report.md's generated count uses it too)."""
    subprocess.run(
        [
            "chromium",
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--no-pdf-header-footer",
            f"--print-to-pdf={pdf}",
            html.as_uri(),
        ],
        capture_output=True,
        timeout=180,
        check=False,
    )
    assert pdf.is_file() and pdf.read_bytes().startswith(b"%PDF")
    return _pages_of(pdf)


def _pages_of(pdf: Path) -> int:
    if shutil.which("pdfinfo"):
        out = subprocess.run(["pdfinfo", str(pdf)], capture_output=True, text=True).stdout
        return int(re.search(r"Pages:\s+(\d+)", out).group(1))
    return len(re.findall(rb"/Type\s*/Page(?!s)", pdf.read_bytes()))


@pytest.mark.skipif(shutil.which("chromium") is None, reason="chromium not installed")
def test_prints_to_pdf_without_orphan_headings(report, tmp_path):
    pdf = tmp_path / "report.pdf"
    pages = print_to_pdf(report, pdf)
    # the fast case with readings, diagnosis and trend: about 9-12 pages on Letter; a broken
    # layout (a figure per page, or nothing printed) lands outside this range
    assert 5 <= pages <= 16, pages
    if not shutil.which("pdftotext"):
        return
    text = subprocess.run(
        ["pdftotext", "-layout", str(pdf), "-"], capture_output=True, text=True
    ).stdout
    headings = set(re.findall(r"<h[23][^>]*>([^<]+)<", report.read_text(encoding="utf-8")))
    headings = {h.strip() for h in headings}
    for i, page in enumerate(text.split("\f")[:-1], start=1):
        lines = [ln.strip() for ln in page.splitlines() if ln.strip()]
        if lines:
            assert lines[-1] not in headings, f"page {i} ends with the heading {lines[-1]!r}"


@pytest.mark.parametrize(
    "args, field",
    [
        (["--roll-id", ""], "--roll-id"),
        (["--customer", "x" * 201], "--customer"),
        (["--trend", "no/such.csv"], "--trend"),
    ],
)
def test_bad_report_options_one_line_exit_2(tmp_path, args, field):
    res = CliRunner().invoke(
        app, ["report", "pet1-26.7N", *SETS, *args, "--out", str(tmp_path / "o"), "-q"]
    )
    assert res.exit_code == 2, res.output
    lines = [ln for ln in res.output.splitlines() if ln.strip()]
    assert len(lines) == 1 and f"{field}:" in lines[0], res.output
