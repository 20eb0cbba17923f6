"""The Rho-meter head's end rounding (unpublished): ``head_edge_radius`` in the instrument
file reaches the 3D head, defaults to sharp ends, and rounding can only soften the contact.
docs/instruments.md has the sensitivity (Rho for 0 / 1 / 2 mm on PET2 53.4 N)."""

from __future__ import annotations

import numpy as np
import pytest

from woundroll.case import load_case
from woundroll.contact.heads import Head
from woundroll.contact.solid3d.solver import Contact3DOptions, indent3d
from woundroll.instruments import get_instrument
from woundroll.winding.hakiel import wind


def test_default_is_sharp_and_the_case_key_reaches_the_head() -> None:
    rho = get_instrument("rho-meter")
    assert rho.head_edge_radius is None
    assert Head.from_instrument(rho).edge_radius == 0.0
    ins = rho.with_overrides("tester", head_edge_radius="1 mm")
    head = Head.from_instrument(ins)
    assert head.edge_radius == pytest.approx(1e-3)
    # the rounded head lies above the sharp one: lift >= lift everywhere, equal mid-head
    sharp = Head.from_instrument(rho)
    z = np.linspace(0, 12.7e-3, 50)
    y = np.full_like(z, 0.5e-3)
    assert np.all(head.lift(y, z) >= sharp.lift(y, z))
    assert head.lift(0.5e-3, 0.0) == sharp.lift(0.5e-3, 0.0)
    with pytest.raises(Exception) as e:  # larger than the head radius: refused, named
        Head.from_instrument(rho.with_overrides("tester", head_edge_radius="9 mm"))
    assert getattr(e.value, "field", None) == "tester.instrument"


@pytest.mark.slow
def test_rounded_ends_never_stiffen_the_roll() -> None:
    """A head inside the sharp one (lift >= lift) touches less of the roll: F(d) with
    rounded ends <= F(d) with sharp ends at every depth (frictionless contact, same mesh).
    Coarse mesh, CMD size 0.5 mm so that a 2 mm rounding spans four elements (~1 min on
    the loaded machine: slow)."""
    case = load_case("pet2-53.4N")
    web, core = case.web.build(), case.core.build()
    w = wind(web, core, case.winding.final_radius(web, core), case.winding.schedule(web))
    opts = Contact3DOptions(
        n_steps=6,
        n_fine=4,
        radial_growth=1.6,
        tangential_growth=1.6,
        axial_growth=1.6,
        axial_size=5e-4,
        locality_cut=True,
    )
    f = {}
    for e in (0.0, 2e-3):
        head = Head("cylinder", 6.565e-3, 25.4e-3, edge_radius=e)
        res = indent3d(web, core, w.radius, w.sigma_r, head=head, depth_max=1e-3, options=opts)
        f[e] = res.force
    assert np.all(f[2e-3][1:] <= f[0.0][1:] * (1 + 1e-9))
    assert f[2e-3][-1] < f[0.0][-1]
