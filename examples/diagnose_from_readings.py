"""From readings on a roll back to the stresses inside, and the defect risk.

A process engineer took three passes of Rho-meter readings across a PET1 roll
(examples/data/readings_rho_3passes.csv, wound like the bundled case pet1-26.7N). What
wound-on tension and interlayer pressure do they mean, and is the roll at risk?
"""

import os
from pathlib import Path

from woundroll.assess.defects import defect_report
from woundroll.case import load_case
from woundroll.inverse.diagnosis import diagnose
from woundroll.io.readings import read_readings

HERE = Path(__file__).resolve().parent


def main() -> None:
    case = load_case("pet1-26.7N", ["defects.core_strength='500 kPa'"])
    readings = read_readings(HERE / "data" / "readings_rho_3passes.csv", width=case.web.width)
    print(readings.to_table())
    d = diagnose(case, readings)
    print("position [in] | reading | wound-on tension [MPa] | pressure [kPa] | status")
    for row in d.summary():
        print(" | ".join(row))
    v = d.verification
    print(f"check: full run reads {v['full_forward_reading']:.2f} for {v['target_reading']:.2f}")
    for name, risk, sentence in defect_report(case, d).summary():
        print(f"{name:18s} {risk:6s} {sentence}")
    out = os.environ.get("WOUNDROLL_EXAMPLE_OUT")
    if out:
        import matplotlib

        matplotlib.use("Agg")
        d.plot(Path(out) / "diagnosis")


if __name__ == "__main__":
    main()
