"""Property-based robustness tests (issue 8): random scenes and settings, within and at the edges
of the valid ranges and beyond them, fed to scene construction, statics, eigen and short
simulations.

Every call must either return a valid result (finite arrays of the documented shapes, and the
physics that holds for any scene: static contact force = F + M g, ascending non-negative
frequencies) or raise a clear exception: ``ValueError``/``TypeError`` naming the parameter,
``trackwheel.DivergenceError``, or -- for scenes whose static equilibrium does not exist in the
model (e.g. a load that pushes the rail metres down) -- the kernel's ``RuntimeError`` saying that
the static solve failed. Nothing may crash or hang: each example runs under a deadline.

Profiles (``TRACKWHEEL_HYPOTHESIS_PROFILE``):

- ``fast`` (default, part of the normal suite): a fixed, derandomised set of examples, no example
  database, about 10-20 s in all;
- ``long``: 10 000 examples per test (``TRACKWHEEL_HYPOTHESIS_EXAMPLES`` overrides), random,
  with the example database in ``.hypothesis/`` (git-ignored) so failures replay::

      TRACKWHEEL_HYPOTHESIS_PROFILE=long python -m pytest tests/test_hypothesis.py

  ``benchmarks/hypothesis_long.py`` runs it property by property under a time budget; the counts
  and rate of the last long run are recorded in benchmarks/README.md (Robustness).
"""

from __future__ import annotations

import math
import os
import sys
import warnings

import numpy as np
import pytest
import trackwheel as tw
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st
from trackwheel.run import kernel as _kernel

SIM = sys.modules["trackwheel.simulate"]
SCENE = sys.modules["trackwheel.scene"]

settings.register_profile(
    "trackwheel-fast", max_examples=100, deadline=10_000, derandomize=True, database=None,
    suppress_health_check=[HealthCheck.too_slow], print_blob=True)
settings.register_profile(
    "trackwheel-long", max_examples=int(os.environ.get("TRACKWHEEL_HYPOTHESIS_EXAMPLES", 10_000)),
    deadline=10_000, suppress_health_check=[HealthCheck.too_slow], print_blob=True)
_PROFILE = os.environ.get("TRACKWHEEL_HYPOTHESIS_PROFILE", "fast")
if _PROFILE not in ("fast", "long"):
    raise ValueError(f"TRACKWHEEL_HYPOTHESIS_PROFILE = {_PROFILE!r} is not one of "
                     f"['fast', 'long']")
PROFILE = settings.get_profile(f"trackwheel-{_PROFILE}")
# fewer examples for the expensive properties in the fast profile
CHEAP = settings(PROFILE, max_examples=PROFILE.max_examples * (3 if _PROFILE == "fast" else 1))

NAN, INF = float("nan"), float("inf")
INVALID_REAL = st.sampled_from([NAN, INF, -INF, -1.0, "1.0", None, True, 1j])
STATIC_FAILURE = ("static solve", "contact-point search did not converge")


def log_uniform(lo, hi):
    """Floats spread evenly in log between lo and hi, plus both edges."""
    return st.one_of(st.sampled_from([lo, hi]),
                     st.floats(math.log10(lo), math.log10(hi)).map(lambda e: 10.0**e))


def maybe_invalid(valid, invalid=INVALID_REAL, p_invalid=0.1):
    """``valid`` most of the time, ``invalid`` with probability about p_invalid; the draw
    reports which (value, is_invalid)."""
    n = round(1 / p_invalid)
    return st.integers(0, n - 1).flatmap(
        lambda k: invalid.map(lambda x: (x, True)) if k == 0 else valid.map(lambda x: (x, False)))


# scene fields: (dataclass, field, valid strategy, invalid strategy)
#: 1e300: far above every parameter's plausible range (trackwheel.base.limits.RANGES)
POSITIVE_OR_ZERO_BAD = st.sampled_from([0.0, -0.0, -1e-9, NAN, INF, "x", None, 1e300])
FIELDS = {
    "Rail.length": log_uniform(0.5, 50.0),
    "Rail.youngs_modulus": log_uniform(1e9, 1e12),
    "Rail.poisson_ratio": st.floats(0.0, 0.49),
    "Rail.density": log_uniform(1e3, 2e4),
    "Rail.area": log_uniform(1e-3, 5e-2),
    "Rail.second_moment": log_uniform(1e-6, 1e-4),
    "Rail.n_elements": st.integers(1, 40),
    "Rail.curvature": st.sampled_from(["exact", "simplified"]),
    "Rail.far_end": st.sampled_from(["roller", "pinned"]),
    "Rail.n_gauss": st.integers(2, 10),
    "Supports.stiffness": log_uniform(1e6, 1e10),
    "Supports.damping": st.one_of(st.just(0.0), log_uniform(1e2, 1e6)),
    "Wheel.mass": log_uniform(0.1, 1e3),
    "Wheel.radius": log_uniform(0.02, 1.0),
    "Wheel.load": st.one_of(st.just(0.0), log_uniform(1.0, 1e5)),
    "Wheel.inertia": st.one_of(st.none(), log_uniform(1e-3, 1e2)),
    "Wheel.torque": st.floats(-1e3, 1e3),
    "Contact.law": st.sampled_from(["linear", "hertz"]),
    "Contact.stiffness": st.one_of(st.none(), log_uniform(1e7, 1e10)),
    "Contact.damping": st.one_of(st.just(0.0), log_uniform(1.0, 1e4)),
    "Contact.friction": st.floats(0.0, 1.0),
    "Scene.gravity": st.floats(0.0, 20.0),
    "Scene.rail_gravity": st.booleans(),
}
INVALID = {
    "Rail.poisson_ratio": st.sampled_from([0.5, -0.1, NAN, "0.3"]),
    "Rail.n_elements": st.sampled_from([0, -3, 5001, 2.0, "20", True]),
    "Rail.curvature": st.sampled_from(["", "EXACT", 1, None, ["exact"]]),
    "Rail.far_end": st.sampled_from(["free", None, 0]),
    "Rail.n_gauss": st.sampled_from([0, 1, 11, 3.0]),
    "Supports.damping": st.sampled_from([-1.0, NAN, INF, "0", 1e300]),
    "Wheel.load": st.sampled_from([-1.0, NAN, INF, None, 1e300]),
    "Wheel.inertia": POSITIVE_OR_ZERO_BAD.filter(lambda x: x is not None),
    "Wheel.torque": st.sampled_from([NAN, INF, "1", -1e300]),
    "Contact.law": st.sampled_from(["hooke", None, 3]),
    "Contact.stiffness": POSITIVE_OR_ZERO_BAD.filter(lambda x: x is not None),
    "Contact.damping": st.sampled_from([-1.0, NAN, INF, 1e300]),
    "Contact.friction": st.sampled_from([-0.1, NAN, INF, 1e300]),
    "Scene.gravity": st.sampled_from([-9.8, NAN, INF, "9.8", 1e300]),
    "Scene.rail_gravity": st.sampled_from(["yes", 1, None]),
}


@st.composite
def scene_kwargs(draw, p_invalid=0.1):
    """(constructor kwargs per class, names of the fields given invalid values)."""
    kw = {"Rail": {}, "Supports": {}, "Wheel": {}, "Contact": {}, "Scene": {}}
    bad = set()
    for name, valid in FIELDS.items():
        invalid = INVALID.get(name, POSITIVE_OR_ZERO_BAD)
        value, is_bad = draw(maybe_invalid(valid, invalid, p_invalid) if p_invalid else
                             valid.map(lambda x: (x, False)))
        cls, field = name.split(".")
        kw[cls][field] = value
        if is_bad:
            bad.add(name)
    # supports: by spacing (valid when round(L / spacing) >= 2), or explicit positions
    length = kw["Rail"]["length"]
    length = length if isinstance(length, float) and math.isfinite(length) and length > 0 else 5.0
    how = draw(st.sampled_from(["spacing", "spacing", "positions", "bare"]))
    if how == "spacing":
        if p_invalid and draw(st.integers(0, 9)) == 0:
            kw["Supports"]["spacing"] = draw(st.sampled_from(
                [0.0, -0.5, NAN, length, 10 * length, 1e-12, "0.5"]))
            bad.add("Supports.spacing")
        else:
            kw["Supports"]["spacing"] = length / draw(st.integers(2, 60))
    elif how == "positions":
        pos = draw(st.lists(st.floats(0.001, 0.999), min_size=1, max_size=12))
        kw["Supports"]["positions"] = tuple(length * p for p in pos)
        if p_invalid and draw(st.integers(0, 9)) == 0:
            kw["Supports"]["positions"] += (draw(st.sampled_from(
                [0.0, length, -1.0, 2 * length, NAN, "a"])),)
            bad.add("Supports.positions")
    else:
        kw["Supports"]["positions"] = ()
    return kw, bad


#: Scene's conditioning check: the track's static sag (Scene.static_sag) at most 1 m
SAGS = "the track sags about"


def build(kw):
    return tw.Scene(rail=tw.Rail(**kw["Rail"]), supports=tw.Supports(**kw["Supports"]),
                    wheel=tw.Wheel(**kw["Wheel"]), contact=tw.Contact(**kw["Contact"]),
                    **kw["Scene"])


@st.composite
def valid_scenes(draw, max_elements=40):
    kw, _ = draw(scene_kwargs(p_invalid=0.0))
    kw["Rail"]["n_elements"] = draw(st.integers(1, max_elements))
    if kw["Wheel"]["load"] == 0.0 and kw["Scene"]["gravity"] == 0.0:
        kw["Scene"]["gravity"] = 9.8  # an unloaded wheel is rejected by Scene
    try:
        return build(kw)
    except ValueError as exc:  # a valid draw: only the sag check may refuse it
        assume(SAGS not in str(exc))
        raise


def finite(*arrays):
    return all(np.all(np.isfinite(np.asarray(a, dtype=float))) for a in arrays)


def check_static_failure(exc):
    """RuntimeError from the kernel is acceptable only as a clear static-solve failure."""
    assert type(exc) is RuntimeError and str(exc).startswith(STATIC_FAILURE), repr(exc)


# --------------------------------------------------------------------------------------------
@CHEAP
@given(scene_kwargs())
def test_scene_construction(args):
    kw, bad = args
    try:
        scene = build(kw)
    except (ValueError, TypeError) as exc:
        msg = str(exc)
        named = [b for b in bad if b in msg]
        # with no invalid field, only the relations between valid fields may fail: supports on
        # the rail, a loaded wheel (F + M g > 0) and a track that does not sag metres
        unloaded = kw["Wheel"]["load"] == 0.0 and kw["Scene"]["gravity"] == 0.0
        assert named or "Supports.spacing" in msg or "Supports.positions" in msg or (
            unloaded and "Wheel.load" in msg) or SAGS in msg, (msg, bad)
        return
    assert not bad, f"accepted invalid {bad}"
    pos = scene.support_positions
    assert all(0.0 < x < scene.rail.length for x in pos)
    assert scene.static_load >= 0.0 and math.isfinite(scene.static_load)
    assert scene.contact_stiffness > 0.0 and math.isfinite(scene.contact_stiffness)
    assert scene.hertz_constant > 0.0 and math.isfinite(scene.hertz_constant)
    assert scene.wheel.polar_inertia > 0.0


@PROFILE
@given(valid_scenes(), st.one_of(st.floats(-0.2, 1.2), st.sampled_from([0.0, 1.0, NAN, INF])))
def test_static(scene, frac):
    """static(scene, X) at X = frac L: finite state, N = F + M g, or a clear error."""
    length = scene.rail.length
    x = frac * length if math.isfinite(frac) else frac
    try:
        r = tw.static(scene, x)
    except ValueError as exc:
        assert not 0.0 <= x <= length and "x_wheel" in str(exc)
        return
    except RuntimeError as exc:
        check_static_failure(exc)
        return
    assert 0.0 <= x <= length
    assert finite(r.rail_coordinates, r.y_wheel, r.y_contact, r.contact_s, r.normal_force)
    assert r.rail_coordinates.shape == (4 * (scene.rail.n_elements + 1),)
    # vertical equilibrium of the wheel: N n_y = F + M g, n the unit contact normal from the
    # contact point to the wheel centre (the rail may be steep: a long bare rail sags metres),
    # to the force resolution of the contact spring: positions near |Y| carry round-off
    # eps |Y|, i.e. a force k eps |Y| (k = the contact stiffness at the static load)
    xc, yc = _kernel.rail_model(scene, scene.rail.n_elements).positions(
        r.rail_coordinates, [r.contact_s])[0]
    n_y = (r.y_wheel - yc) / math.hypot(r.x_wheel - xc, r.y_wheel - yc)
    resolution = 10 * np.finfo(float).eps * (abs(r.y_wheel) + length) * scene.contact_stiffness
    assert r.normal_force * n_y == pytest.approx(scene.static_load, rel=1e-6, abs=resolution)
    assert 0.0 <= r.contact_s <= length


@PROFILE
@given(valid_scenes(max_elements=30),
       st.lists(st.one_of(st.floats(-0.1, 1.1), st.sampled_from([0.0, 1.0])), min_size=1,
                max_size=5),
       st.one_of(st.integers(-1, 70), st.sampled_from([2.0, "3", None])))
def test_eigen(scene, fracs, n_modes):
    length = scene.rail.length
    x = [f * length for f in fracs]
    try:
        r = tw.eigen(scene, x, n_modes=n_modes)
    except (ValueError, TypeError) as exc:
        msg = str(exc)
        bad_x = any(not 0.0 <= xi <= length for xi in x)
        assert (bad_x and "positions" in msg) or "n_modes" in msg, msg
        return
    assert all(0.0 <= xi <= length for xi in x)
    assert r.frequencies.shape == (len(x), n_modes)
    assert r.shapes.shape == (len(x), 4 * (r.n_elements + 1) + 1, n_modes)
    assert finite(r.frequencies, r.shapes, r.axial_frequencies)
    assert np.all(r.frequencies >= 0.0)
    assert np.all(np.diff(r.frequencies, axis=1) >= -1e-9 * r.frequencies[:, 1:])


#: model levels whose wheel is held on the rail (their contact force may be negative)
BILATERAL = {"linear/moving_mass", "linear/sprung"}
#: a fidelity level's contact law rewriting a stiff linear contact under a tiny load into a
#: Hertz constant beyond the range of Contact.stiffness
FIDELITY_LAW = "the fidelity level's hertz contact law"
#: MeshWarning: a drawn mesh with fewer elements than support bays; PlausibilityWarning: a
#: speed above the wheel-on-rail record (574.8 km/h, 160 m/s)
EXPECTED_WARNINGS = {"StabilityWarning", "ConvergenceWarning", "MeshWarning",
                     "PlausibilityWarning"}
INTEGRATORS = st.sampled_from(["generalized_alpha", "explicit"])
#: the time-domain levels (the periodic level has no time history: simulate refuses it)
FIDELITY = st.sampled_from(getattr(SIM, "TIME_DOMAIN_LEVELS", ("full",)))


@st.composite
def sim_settings(draw):
    """(kwargs for simulate, names given invalid values)."""
    kw, bad = {}, set()
    speed, b = draw(maybe_invalid(st.one_of(st.just(0.0), st.floats(0.1, 300.0)),
                                  st.sampled_from([-1.0, 301.0, NAN, INF, "100"])))
    kw["speed"] = speed
    if b:
        bad.add("speed")
    kw["integrator"], b = draw(maybe_invalid(INTEGRATORS, st.sampled_from(["rk4", None])))
    if b:
        bad.add("integrator")
    dt, b = draw(maybe_invalid(log_uniform(1e-7, 1e-4), st.sampled_from([0.0, -1e-5, NAN, INF])))
    kw["dt"] = dt
    if b:
        bad.add("dt")
    kw["n_steps"] = draw(st.integers(1, 12))
    kw["x_frac"] = draw(st.one_of(st.floats(0.0, 0.9), st.just(0.0)))
    kw["output_every"] = draw(st.one_of(st.none(), st.integers(1, 5)))
    kw["start"] = draw(st.sampled_from(["static", "static", "sudden"]))
    kw["rolling"] = draw(st.booleans())
    kw["rho_inf"] = draw(st.floats(0.0, 1.0))
    kw["baumgarte"] = draw(st.one_of(st.just(0.0), log_uniform(1.0, 1e4)))
    # the linear levels run generalized-alpha only (asking for explicit is a ValueError of its
    # own, tested with the fidelity levels)
    kw["fidelity"] = draw(FIDELITY) if kw["integrator"] == "generalized_alpha" else "full"
    return kw, bad


@PROFILE
@given(valid_scenes(max_elements=24), sim_settings())
def test_short_simulation(scene, args):
    kw, bad = args
    length = scene.rail.length
    speed, dt = kw["speed"], kw["dt"]
    x0 = kw["x_frac"] * length
    call = dict(integrator=kw["integrator"], dt=dt, x_start=x0, output_every=kw["output_every"],
                start=kw["start"], rolling=kw["rolling"], rho_inf=kw["rho_inf"],
                baumgarte=kw["baumgarte"], progress=False)
    if kw["fidelity"] != "full":
        call["fidelity"] = kw["fidelity"]
    if not bad:
        # a few steps that stay on the rail
        duration = kw["n_steps"] * dt
        assume(x0 + speed * duration <= length)
        call["duration"] = duration
    else:
        call["duration"] = 1e-4
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            r = tw.simulate(scene, speed, **call)
        # the only warnings expected: dt above the explicit stability limit, or accuracy
        assert {type(w.message).__name__ for w in caught} <= EXPECTED_WARNINGS, caught
    except (ValueError, TypeError) as exc:
        msg = str(exc)
        if bad:  # a bad value named, or the scene's rewrite, checked before the step
            assert any(b in msg for b in bad) or FIDELITY_LAW in msg, (msg, bad)
        else:  # combinations the valid ranges above can reach
            assert ("integrator" in msg and "fidelity" in msg) or "duration" in msg \
                or ("dt" in msg and "allowed range" in msg) or FIDELITY_LAW in msg, msg
        return
    except tw.DivergenceError as exc:
        assert exc.step >= 0 and exc.cause, repr(exc)
        return
    except RuntimeError as exc:
        check_static_failure(exc)
        return
    assert not bad, f"accepted invalid {bad}"
    n = len(r.t)
    assert r.steps == kw["n_steps"] and n == r.steps // r.settings["output_every"] + 1
    arrays = [getattr(r, name) for name in (
        "t", "x_wheel", "y_wheel", "ydot_wheel", "theta", "thetadot", "contact_s", "y_contact",
        "normal_force", "tangential_force", "slip", "v_error", "phi", "acc_contact", "reaction",
        "penetration")]
    assert all(a.shape == (n,) for a in arrays) and r.slip_state.shape == (n,)
    assert finite(*arrays)
    if kw["fidelity"] not in BILATERAL:
        assert np.all(r.normal_force >= 0.0)  # unilateral contact: it cannot pull
    np.testing.assert_allclose(r.x_wheel, x0 + speed * r.t, rtol=0, atol=1e-12 * (1 + length))


@CHEAP
@given(st.one_of(st.floats(allow_nan=True, allow_infinity=True), st.integers(-10**6, 10**6),
                 st.sampled_from(["300", None, True, [300]])))
def test_kmh(value):
    try:
        v = tw.kmh(value)
    except (ValueError, TypeError) as exc:
        assert "speed_kmh" in str(exc)
        assert isinstance(value, (str, bool, list, type(None))) or not (
            math.isfinite(value) and value >= 0)
        return
    assert math.isfinite(v) and v >= 0 and v == pytest.approx(value / 3.6)
