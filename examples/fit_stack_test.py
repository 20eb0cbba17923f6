"""Fit radial-modulus laws to a stack test and use the fit in a case.

1. Fit the Pfeiffer law (and, for comparison, the polynomial and constant laws) to the
   bundled SYNTHETIC stack test (PET1's Table-2 curve with 1.5 % noise).
2. Put the fitted law's case-file table into a case (PET1 web, the Table-2 steel core and
   roll, 26.7 N) as a dict, run the winding model, and print the core pressure next to the
   one from the Table-2 law.

Run: python examples/fit_stack_test.py
"""

import tomllib
from pathlib import Path

from woundroll.case import load_case
from woundroll.materials.presets import material_preset
from woundroll.materials.radial_modulus import read_stack_csv
from woundroll.materials.stack_fit import FIT_LAWS, fit_stack
from woundroll.pipeline import run

HERE = Path(__file__).parent


def case_with_law(radial_modulus: dict) -> dict:
    """PET1 at 26.7 N (Table 2) as a case dict, with the given ``web.radial_modulus``."""
    web = material_preset("PET1")
    web["radial_modulus"] = radial_modulus  # replace the preset's law, do not merge into it
    return {
        "title": "PET1, 26.7 N, radial modulus fitted to a stack test",
        "web": web,
        "core": {"outer_radius": "4.45 cm", "inner_radius": "3.81 cm", "E": "200 GPa", "nu": 0.3},
        "winding": {"outer_radius": "13.34 cm", "tension": "26.7 N"},
    }


def main() -> dict[str, float]:
    strain, pressure = read_stack_csv(HERE / "data" / "stack_test_pet1_synthetic.csv")
    fits = {law: fit_stack(strain, pressure, law) for law in FIT_LAWS}
    for law, f in fits.items():
        print(f"{law:10s} R^2 {f.r2:.5f}  RMS relative error {f.rms_rel_error:7.2%}  {f.toml()}")
    fit = fits["pfeiffer"]
    print(f"Pfeiffer: K1 = {fit.law.K1 / 1e3:.3f} kPa, K2 = {fit.law.K2:.2f}")

    # the case-file snippet, read back as TOML, is the case's web.radial_modulus
    fitted_law = tomllib.loads(f"radial_modulus = {fit.toml()}")["radial_modulus"]
    fitted = run(load_case(case_with_law(fitted_law))).winding
    table2 = run(load_case(case_with_law(material_preset("PET1")["radial_modulus"]))).winding
    change = fitted.core_pressure / table2.core_pressure - 1
    print(
        f"core pressure, PET1 at 26.7 N: {fitted.core_pressure / 1e3:.2f} kPa with the fitted law, "
        f"{table2.core_pressure / 1e3:.2f} kPa with Table 2's ({change:+.2%})"
    )
    return {
        "K1": fit.law.K1,
        "K2": fit.law.K2,
        "core_pressure_Pa": fitted.core_pressure,
        "core_pressure_table2_Pa": table2.core_pressure,
    }


if __name__ == "__main__":
    main()
