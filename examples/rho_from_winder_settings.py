"""From winder settings to a Rho-meter reading, step by step, in Python (notebook style).

1. the whole chain in one call: ``woundroll.run`` on a bundled case, with overrides;
2. a small tension sweep, the way a process engineer would set up a trial;
3. the same chain by hand, one physical step per call:
   winder settings -> stresses in the roll -> roll stiffness under the striker ->
   striker motion -> reading.

Run: ``python examples/rho_from_winder_settings.py`` (a few seconds).
"""

import os
from pathlib import Path

import woundroll
from woundroll.contact import fit_roll_spring, indent
from woundroll.instruments import get_instrument, impact_energy, impact_fd
from woundroll.instruments.roll_side import RollSpring
from woundroll.winding.hakiel import wind

# 1. the whole chain
case = woundroll.load_case("pet1-26.7N", ["contact.no_update=false"])
result = woundroll.run(case)
h = result.hardness.to_dict()
print(
    f"{case.title}: Rho {h['rho_fd']:.1f} (FD), {h['rho_energy']:.1f} (energy), "
    f"impulse {h['impulse_N_s']:.3f} N s"
)

# 2. a tension sweep (US units welcome: the case parses them)
for tension in ("0.8 pli", "1 pli", "1.2 pli"):
    r = woundroll.run(
        woundroll.load_case(
            "pet1-26.7N", [f"winding.tension='{tension}'", "contact.no_update=false"]
        )
    )
    print(
        f"  {tension:>6}: core pressure {r.winding.core_pressure / 1e3:6.1f} kPa, "
        f"Rho {r.hardness.to_dict()['rho_fd']:.1f}"
    )

# 3. the same chain by hand
web, core = case.web.build(), case.core.build()
roll = wind(web, core, case.winding.final_radius(web, core), case.winding.schedule(web))
rho_meter = get_instrument("rho-meter")
contact = indent(
    web,
    core,
    roll.radius,
    roll.sigma_r,
    head_radius=rho_meter.head_radius,
    head_length=rho_meter.head_length,
    depth_max=1e-3,
)
# plane strain, the default roll model for the Rho-meter's cylindrical head (docs/contact.md)
spring = fit_roll_spring(contact.delta, contact.force, rho_meter)
print(
    f"roll spring {{3}}: alpha {spring.alpha:.3g} N/m^2, beta {spring.beta:.3g} N/m "
    f"(fit over 0-{spring.fit_depth * 1e3:.2f} mm, R^2 {spring.r2:.4f})"
)
fd = impact_fd(rho_meter, RollSpring.quadratic(spring.alpha, spring.beta, 0.0))
en = impact_energy(rho_meter, RollSpring.quadratic(spring.alpha, spring.beta, 0.0))
print(f"no roll mass: Rho {fd.rho:.1f} (FD), {en.rho:.1f} (energy)")

out = Path(os.environ.get("WOUNDROLL_EXAMPLE_OUT", "out/example"))
print("wrote", *result.write(out))
