"""The JSON vocabulary (docs/nomenclature.md, :mod:`woundroll.pipeline.vocabulary`): every key
of a real result.json is described and validates against the JSON Schema the ``woundroll
schema`` command prints; the suffix rule catches a dimensional key without its unit; the
nomenclature page and the sweep read the same description.

jsonschema is not a dependency (not in the venv): :func:`validate` below checks the subset of
draft 2020-12 the generated schema uses ($ref, anyOf, type, const, properties,
additionalProperties, items, required) and fails on any other keyword, so a schema the
validator does not understand cannot pass by being ignored.
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

import pytest
from typer.testing import CliRunner

from woundroll.app.cli import app
from woundroll.app.sweep import result_columns
from woundroll.pipeline import vocabulary as vocab

ROOT = Path(__file__).resolve().parent.parent
runner = CliRunner()

_TYPES = {
    "object": lambda v: isinstance(v, dict),
    "array": lambda v: isinstance(v, list),
    "string": lambda v: isinstance(v, str),
    "boolean": lambda v: isinstance(v, bool),
    "null": lambda v: v is None,
    "integer": lambda v: isinstance(v, int) and not isinstance(v, bool),
    "number": lambda v: isinstance(v, int | float) and not isinstance(v, bool),
}
_KNOWN = {"$ref", "anyOf", "type", "const", "properties", "additionalProperties", "items"}
_ANNOTATIONS = {"description", "x-unit", "x-scale", "required", "$schema", "$id", "title"}


def validate(value: Any, schema: dict[str, Any], root: dict[str, Any], path: str = "") -> list[str]:
    """Errors of ``value`` against ``schema`` (the subset of draft 2020-12 named above)."""
    unknown = set(schema) - _KNOWN - _ANNOTATIONS - {"$defs"}
    if unknown:
        return [f"{path}: validator does not know {sorted(unknown)}"]
    errors: list[str] = []
    if "$ref" in schema:
        name = schema["$ref"].removeprefix("#/$defs/")
        errors += validate(value, root["$defs"][name], root, path)
    if "anyOf" in schema:
        branches = [validate(value, s, root, path) for s in schema["anyOf"]]
        if all(branches):  # none matches: the errors of a branch of the value's own type
            typed = [b for b in branches if not b[0].startswith(f"{path}: wrong type")]
            errors += [f"{path}: matches none of anyOf"] + min(typed or branches, key=len)
    if "const" in schema and value != schema["const"]:
        errors.append(f"{path}: {value!r} != const {schema['const']!r}")
    if "type" in schema:
        types = schema["type"] if isinstance(schema["type"], list) else [schema["type"]]
        if not any(_TYPES[t](value) for t in types):
            errors.append(f"{path}: wrong type: {type(value).__name__} is not {types}")
            return errors
    if isinstance(value, dict):
        for req in schema.get("required", []):
            if req not in value:
                errors.append(f"{path}: required key {req!r} missing")
        props = schema.get("properties")
        if props is not None:
            for k, v in value.items():
                if k in props:
                    errors += validate(v, props[k], root, f"{path}.{k}")
                elif schema.get("additionalProperties") is False:
                    errors.append(f"{path}.{k}: not in the vocabulary")
    if isinstance(value, list) and "items" in schema:
        for i, v in enumerate(value):
            errors += validate(v, schema["items"], root, f"{path}[{i}]")
    return errors


def check_document(doc: dict[str, Any], document: str) -> None:
    """Every key described, the document valid against its schema."""
    assert vocab.undescribed_keys(doc) == []
    schema = vocab.json_schema(document)
    errors = validate(doc, schema, schema)
    assert errors == [], errors[:10]


@pytest.fixture(scope="module")
def pet1_json() -> dict[str, Any]:
    """result.json of the reference paper's PET1 at 26.7 N, through the CLI's --json."""
    res = runner.invoke(app, ["run", "pet1-26.7N", "--json", "--no-update"])
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout)


def test_pet1_result_json_is_described_and_valid(pet1_json):
    assert pet1_json["schema_version"] == vocab.SCHEMA_VERSION
    for part in ("winding", "contact", "hardness", "no_update", "flags"):
        assert part in pet1_json
    check_document(pet1_json, "result")


def test_profile_result_json_is_described_and_valid(tmp_path):
    # a small CMD profile run (3 sectors, 6 cm roll, as tests/test_pipeline.py): profile.*
    (tmp_path / "prof.csv").write_text(
        "position [cm],thickness [um]\n0,100\n7.62,101\n15.24,100\n", encoding="utf-8"
    )
    case = tmp_path / "case.toml"
    case.write_text(
        '[web]\npreset = "PET1"\n[core]\nouter_radius = "4.45 cm"\nrigid = true\n'
        '[winding]\nouter_radius = "6 cm"\ntension = "26.7 N"\nthickness_profile = "prof.csv"\n'
        '[tester]\ninstrument = "rho-meter"\n[profile]\nsectors = 3\nworkers = 1\n',
        encoding="utf-8",
    )
    out = tmp_path / "o"
    res = runner.invoke(app, ["run", str(case), "--out", str(out), "-q"])
    assert res.exit_code == 0, res.output
    doc = json.loads((out / "result.json").read_text(encoding="utf-8"))
    assert {"profile", "files", "schema_version"} <= set(doc)
    assert "thickness_m" in doc["profile"]["stats"]
    check_document(doc, "result")


def test_readings_and_defects_json_are_described_and_valid():
    res = runner.invoke(
        app, ["readings", str(ROOT / "examples/data/readings_rho_3passes.csv"), "--json"]
    )
    assert res.exit_code == 0, res.output
    check_document(json.loads(res.stdout), "readings")
    res = runner.invoke(app, ["defects", "pet1-26.7N", "--json"])
    assert res.exit_code == 0, res.output
    doc = json.loads(res.stdout)
    assert "core_strength_Pa" in doc["defects"]["limits"]
    check_document(doc, "defects")


def test_validator_and_schema_reject_what_they_must(pet1_json):
    # the check can fail: an undescribed key, a wrong type, a wrong version
    schema = vocab.json_schema("result")
    bad = json.loads(json.dumps(pet1_json))
    bad["hardness"]["delta_max_m"] = 1e-3  # a schema-1 name
    bad["winding"]["n_layers"] = "many"
    bad["schema_version"] = 1
    errors = validate(bad, schema, schema)
    assert any("delta_max_m: not in the vocabulary" in e for e in errors)
    assert any(".winding.n_layers" in e for e in errors)
    assert any("const" in e for e in errors)
    assert vocab.undescribed_keys(bad) == ["hardness.delta_max_m"]


def test_every_term_follows_the_suffix_rule():
    assert vocab.check_terms() == []


@pytest.mark.parametrize(
    ("term", "needle"),
    [
        (vocab.Term("impulse", "N s", "impulse"), "does not end in '_N_s'"),  # unit, no suffix
        (vocab.Term("impulse_Ns", "N s", "impulse"), "does not end in '_N_s'"),  # wrong suffix
        (vocab.Term("peak_force_kN", "kN", "force"), "has no key suffix"),  # not SI
        (vocab.Term("reading_m", "", "a reading"), "dimensionless but ends in '_m'"),
    ],
)
def test_a_dimensional_key_without_its_suffix_fails_the_check(term, needle):
    problems = vocab.check_terms([term])
    assert problems and needle in problems[0]


def test_schema_cli_prints_the_json_schema():
    res = runner.invoke(app, ["schema", "result"])
    assert res.exit_code == 0, res.output
    schema = json.loads(res.stdout)
    assert schema["$schema"] == "https://json-schema.org/draft/2020-12/schema"
    assert schema == json.loads(json.dumps(vocab.json_schema("result")))
    assert schema["$defs"]["impulse_N_s"]["x-unit"] == "N s"
    assert schema["$defs"]["schema_version"]["const"] == vocab.SCHEMA_VERSION
    res = runner.invoke(app, ["schema", "diagnosis"])
    assert res.exit_code == 0 and "diagnosis" in json.loads(res.stdout)["title"]
    res = runner.invoke(app, ["schema", "bogus"])
    assert res.exit_code == 2
    assert "unknown document 'bogus'" in res.output


def test_nomenclature_page_is_the_vocabulary():
    page = (ROOT / "docs" / "nomenclature.md").read_text(encoding="utf-8")
    assert vocab.nomenclature_table() in page, "regenerate: python -m woundroll.pipeline.vocabulary"


def test_sweep_units_come_from_the_vocabulary(pet1_json):
    cols = result_columns(pet1_json)
    assert cols["hardness.impulse [N s]"] == pet1_json["hardness"]["impulse_N_s"]
    assert "hardness.rho_fd [rho]" in cols and "hardness.reading [rho]" in cols
    assert "contact.friction [-]" in cols
    assert not any(c.startswith("schema_version") for c in cols)
    # keys the old suffix parser labelled dimensionless
    assert vocab.column_name("hardness.dynamic.energy_in_J") == "hardness.dynamic.energy_in [J]"
    assert vocab.column_name("a.density_kg_per_m3") == "a.density [kg/m^3]"
    assert vocab.unit_of("profile.stats.thickness_m.mean") == "m"
    assert vocab.unit_of("uncertainty.core_pressure_Pa.p50") == "Pa"
    assert vocab.unit_of("profile.stats.reading.mean", "R") == "R"
    for col, v in cols.items():
        assert col.endswith("]") and (isinstance(v, bool) or math.isfinite(v)), col
