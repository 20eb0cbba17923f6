"""Fit radial-modulus laws to a stack test and use the fit in a case.

Run: python examples/fit_stack_test.py
"""

from pathlib import Path

from woundroll.materials.radial_modulus import read_stack_csv
from woundroll.materials.stack_fit import fit_stack

HERE = Path(__file__).parent


def main() -> dict[str, float]:
    strain, pressure = read_stack_csv(HERE / "data" / "stack_test_pet1_synthetic.csv")
    fit = fit_stack(strain, pressure, "pfeiffer")
    print(f"K1 = {fit.law.K1 / 1e3:.3f} kPa, K2 = {fit.law.K2:.2f}  "
          f"(R^2 {fit.r2:.5f}, RMS relative error {fit.rms_rel_error:.2%})")
    print("case file: radial_modulus =", fit.toml())
    return {"K1": fit.law.K1, "K2": fit.law.K2}


if __name__ == "__main__":
    main()
