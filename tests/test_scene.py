"""Scene description (docs: Model § Scene): the paper's preset and input validation."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
import trackwheel as tw


def test_kato2005_is_model_md_section_1():
    s = tw.Scene.kato2005()
    r, sup, w, c = s.rail, s.supports, s.wheel, s.contact
    assert r.length == 5.0
    assert r.youngs_modulus == 2.058e11 and r.poisson_ratio == 0.30
    assert r.density == 7850.0
    assert r.area == 6.936e-3 and r.second_moment == 3.08961e-5
    assert r.n_elements == 20
    assert r.curvature == "exact"  # the simplified curvature is an option, not the default
    assert r.far_end == "roller"
    assert sup.stiffness == 140e6 and sup.spacing == 0.5 and sup.damping == 0.0
    np.testing.assert_allclose(s.support_positions, 0.5 * np.arange(1, 10), rtol=0, atol=1e-12)
    assert w.mass == 10.0 and w.radius == 0.1 and w.load == 47040.0
    assert w.polar_inertia == pytest.approx(10.0 * 0.1**2 / 2, rel=1e-15)  # J = M rho0^2 / 2
    assert w.youngs_modulus == 2.058e11 and w.poisson_ratio == 0.30
    assert c.law == "linear" and c.friction == 0.3 and c.damping == 0.0
    assert s.gravity == 9.8 and s.rail_gravity
    assert s.static_load == pytest.approx(47040.0 + 10.0 * 9.8, rel=1e-15)  # P = F + M g


def test_kato2005_contact_stiffness_is_linearised_hertz():
    """docs: Model § Contact, recomputed here: E* = E / (2 (1 - nu^2)) for the same steel on both sides,
    C_H = 4/3 E* sqrt(rho0), k = 1.5 C_H^(2/3) P^(1/3) at P = F + M g."""
    E, nu, rho0 = 2.058e11, 0.30, 0.1
    P = 47040.0 + 10.0 * 9.8
    e_star = E / (2.0 * (1.0 - nu**2))
    c_h = 4.0 / 3.0 * e_star * math.sqrt(rho0)
    k = 1.5 * c_h ** (2.0 / 3.0) * P ** (1.0 / 3.0)
    s = tw.Scene.kato2005()
    assert s.hertz_constant == pytest.approx(c_h, rel=1e-13)
    assert s.contact_stiffness == pytest.approx(k, rel=1e-13)
    assert s.contact_stiffness == pytest.approx(7.1e8, rel=0.01)  # "about 7.1e8 N/m"
    # k is the tangent dN/d delta of the Hertz law at the static load
    delta = (P / c_h) ** (2.0 / 3.0)
    assert s.contact_stiffness == pytest.approx(1.5 * c_h * math.sqrt(delta), rel=1e-12)


def test_scene_derived_quantities():
    s = tw.Scene.kato2005()
    assert s.winkler_modulus == pytest.approx(140e6 / 0.5)
    assert s.rail.mass_per_length == pytest.approx(7850.0 * 6.936e-3)
    assert s.rail.bending_stiffness == pytest.approx(2.058e11 * 3.08961e-5)
    assert tw.kmh(300) == pytest.approx(300 / 3.6)
    explicit = dataclasses.replace(s, contact=tw.Contact(stiffness=1e9))
    assert explicit.contact_stiffness == 1e9
    hertz = dataclasses.replace(s, contact=tw.Contact(law="hertz"))
    assert hertz.contact_stiffness == pytest.approx(s.contact_stiffness, rel=1e-15)


def test_scene_is_frozen():
    s = tw.Scene.kato2005()
    with pytest.raises(dataclasses.FrozenInstanceError):
        s.gravity = 0.0
    with pytest.raises(dataclasses.FrozenInstanceError):
        s.rail.length = 1.0


NAN = float("nan")

BAD_VALUES = [
    # (constructor, field named in the message)
    (lambda: tw.Rail(length=0.0), "Rail.length"),
    (lambda: tw.Rail(length=-5.0), "Rail.length"),
    (lambda: tw.Rail(length=NAN), "Rail.length"),
    (lambda: tw.Rail(length=math.inf), "Rail.length"),
    (lambda: tw.Rail(youngs_modulus=0.0), "Rail.youngs_modulus"),
    (lambda: tw.Rail(density=-1.0), "Rail.density"),
    (lambda: tw.Rail(area=0.0), "Rail.area"),
    (lambda: tw.Rail(second_moment=NAN), "Rail.second_moment"),
    (lambda: tw.Rail(poisson_ratio=0.5), "Rail.poisson_ratio"),
    (lambda: tw.Rail(n_elements=0), "Rail.n_elements"),
    (lambda: tw.Rail(n_gauss=11), "Rail.n_gauss"),
    (lambda: tw.Rail(curvature="approx"), "Rail.curvature"),
    (lambda: tw.Rail(far_end="clamped"), "Rail.far_end"),
    (lambda: tw.Supports(stiffness=0.0), "Supports.stiffness"),
    (lambda: tw.Supports(stiffness=-140e6), "Supports.stiffness"),
    (lambda: tw.Supports(stiffness=NAN), "Supports.stiffness"),
    (lambda: tw.Supports(spacing=0.0), "Supports.spacing"),
    (lambda: tw.Supports(spacing=-0.5), "Supports.spacing"),
    (lambda: tw.Supports(damping=-1.0), "Supports.damping"),
    (lambda: tw.Scene(supports=tw.Supports(spacing=4.0)), "Supports.spacing"),  # none inside
    (lambda: tw.Supports(positions=(1.0, NAN)), "Supports.positions"),
    (lambda: tw.Scene(supports=tw.Supports(positions=(1.0, 6.0))), "Supports.positions"),
    (lambda: tw.Scene(supports=tw.Supports(positions=(-0.5,))), "Supports.positions"),
    (lambda: tw.Scene(supports=tw.Supports(positions=(0.0,))), "Supports.positions"),
    (lambda: tw.Wheel(mass=0.0), "Wheel.mass"),
    (lambda: tw.Wheel(mass=-10.0), "Wheel.mass"),
    (lambda: tw.Wheel(radius=0.0), "Wheel.radius"),
    (lambda: tw.Wheel(load=-1.0), "Wheel.load"),
    (lambda: tw.Wheel(load=NAN), "Wheel.load"),
    (lambda: tw.Wheel(inertia=0.0), "Wheel.inertia"),
    (lambda: tw.Contact(law="coulomb"), "Contact.law"),
    (lambda: tw.Contact(stiffness=0.0), "Contact.stiffness"),
    (lambda: tw.Contact(damping=-1.0), "Contact.damping"),
    (lambda: tw.Contact(friction=-0.1), "Contact.friction"),
    (lambda: tw.Scene(gravity=-9.8), "Scene.gravity"),
    (lambda: tw.Scene(gravity=NAN), "Scene.gravity"),
]


@pytest.mark.parametrize("make, field", BAD_VALUES, ids=[f for _, f in BAD_VALUES])
def test_bad_scene_values_raise_value_error_naming_the_field(make, field):
    with pytest.raises(ValueError, match=field.replace(".", r"\.")):
        make()


def test_replace_validates_too():
    s = tw.Scene.kato2005()
    with pytest.raises(ValueError, match=r"Supports\.stiffness"):
        dataclasses.replace(s, supports=dataclasses.replace(s.supports, stiffness=-1.0))
    shorter = dataclasses.replace(s.rail, length=2.0)  # supports up to 4.5 m stay outside
    with pytest.raises(ValueError, match=r"Supports\.positions"):
        dataclasses.replace(s, rail=shorter, supports=tw.Supports(positions=(1.0, 4.5)))


BAD_TYPES = [
    (lambda: tw.Rail(length="5"), "Rail.length"),
    (lambda: tw.Rail(length=None), "Rail.length"),
    (lambda: tw.Rail(n_elements=20.0), "Rail.n_elements"),
    (lambda: tw.Rail(n_elements=True), "Rail.n_elements"),
    (lambda: tw.Supports(stiffness="stiff"), "Supports.stiffness"),
    (lambda: tw.Supports(positions=("a", "b")), "Supports.positions"),
    (lambda: tw.Wheel(mass=[10.0]), "Wheel.mass"),
    (lambda: tw.Scene(rail=tw.Wheel()), "Scene.rail"),
    (lambda: tw.Scene(supports=None), "Scene.supports"),
    (lambda: tw.Scene(wheel={"mass": 10.0}), "Scene.wheel"),
]


@pytest.mark.parametrize("make, field", BAD_TYPES, ids=[f for _, f in BAD_TYPES])
def test_wrong_types_raise_type_error_naming_the_field(make, field):
    with pytest.raises(TypeError, match=field.replace(".", r"\.")):
        make()


def test_public_functions_validate_their_arguments():
    s = tw.Scene.kato2005()
    with pytest.raises(ValueError, match="x_wheel"):
        tw.static(s, 6.0)
    with pytest.raises(ValueError, match="x_wheel"):
        tw.static(s, NAN)
    with pytest.raises(TypeError, match="scene"):
        tw.static("kato2005", 1.0)
    with pytest.raises(ValueError, match="positions"):
        tw.quasi_static(s, [1.0, -0.1])
    with pytest.raises(ValueError, match="positions"):
        tw.eigen(s, [NAN])
    with pytest.raises(ValueError, match="n_modes"):
        tw.eigen(s, [2.5], n_modes=0)
    with pytest.raises(TypeError, match="n_modes"):
        tw.eigen(s, [2.5], n_modes=2.5)
    with pytest.raises(ValueError, match="n_elements"):
        tw.eigen(s, [2.5], n_elements=0)
    with pytest.raises(TypeError, match="scene"):
        tw.eigen(None, [2.5])
    with pytest.raises(TypeError, match="speed_kmh"):
        tw.kmh("300")


def test_empty_positions_give_a_bare_beam():
    """positions=() is the simply supported rail without intermediate supports (the moving-force
    validation case of docs: Model § Validation)."""
    s = tw.Scene(supports=tw.Supports(positions=()))
    assert s.support_positions == ()
