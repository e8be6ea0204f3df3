"""Property-based tests of the newer APIs: layered supports, the travelling window, rail
profiles, wheel defects, vehicles, receptance and decay rate.

Each property draws values across and beyond the documented ranges (the plausible ranges of
``trackwheel.base.limits.RANGES``: inside them log-uniformly, at both ends, and outside: zero,
negative, NaN, inf, 1e300, wrong types) and asks of every call one thing: **a clean ValueError
or TypeError naming the parameter, or a finite result** (no NaN, no OverflowError, no kernel
RuntimeError, no DivergenceError). Where the scene's own conditioning check refuses a
combination of valid values (its static sag above 1 m), the message says so.

Profiles (as in ``tests/test_hypothesis.py``): ``fast`` (default) runs 25-60 derandomised
examples per property, a few seconds in all; ``pytest -m slow tests/test_hypothesis_newer.py``
runs the long variants (``LONG_EXAMPLES`` each, random, deadline 20 s per example), whose
counts and time are recorded in benchmarks/README.md (Robustness).
"""

from __future__ import annotations

import math
import os
import warnings

import numpy as np
import pytest
import trackwheel as tw
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from trackwheel.base.limits import RANGES
from trackwheel.scene.vehicle import rigid_track_frequencies

FAST = settings(max_examples=40, deadline=10_000, derandomize=True, database=None,
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much],
                print_blob=True)
#: examples per property of the long run (``-m slow``)
LONG_EXAMPLES = int(os.environ.get("TRACKWHEEL_HYPOTHESIS_EXAMPLES", 2000))
LONG = settings(max_examples=LONG_EXAMPLES, deadline=20_000, database=None,
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much],
                print_blob=True)

NAN, INF = float("nan"), float("inf")
#: warnings a call may give: a likely slip of units, a coarse mesh, an explicit step
ALLOWED_WARNINGS = {"PlausibilityWarning", "MeshWarning", "StabilityWarning"}
#: Scene's conditioning check: the track's static sag at most 1 m
SAGS = "the track sags about"
BALLASTED = tw.Scene.ballasted_track(6.0)
KATO = tw.Scene.kato2005()


def log_uniform(lo, hi):
    """Floats spread evenly in log between lo and hi, plus both ends."""
    return st.one_of(st.sampled_from([lo, hi]),
                     st.floats(math.log10(lo), math.log10(hi)).map(lambda e: 10.0**e))


def field_values(name: str):
    """Values of the parameter ``name``: inside its range (log-uniform over it, or uniform
    where it holds zero or negatives), its ends, and beyond them."""
    r = RANGES[name]
    if r.low > 0.0:
        inside = log_uniform(r.low, r.high)
    elif r.low == 0.0:
        inside = st.one_of(st.just(0.0), log_uniform(max(r.high * 1e-12, 1e-12), r.high))
    else:
        inside = st.floats(r.low, r.high)
    outside = st.sampled_from([-1.0, NAN, INF, -INF, 1e300, r.high * 10.0, -r.high,
                               "1.0", None, True])
    return st.one_of(inside, inside, inside, outside)


def finite(*arrays) -> bool:
    return all(np.all(np.isfinite(np.asarray(a, dtype=complex))) for a in arrays)


def clean_or_finite(call, names, check=None):
    """Run ``call()``: a ValueError/TypeError must name one of ``names``; a result must pass
    ``check`` (default: finite). Returns the result, or None after a clean error."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            out = call()
        except (ValueError, TypeError) as exc:
            msg = str(exc)
            assert any(n in msg for n in names), (type(exc).__name__, msg, names)
            return None
    assert {type(w.message).__name__ for w in caught} <= ALLOWED_WARNINGS, [
        str(w.message) for w in caught]
    assert (check or finite)(out), out
    return out


def both(body, strategies: dict, fast_examples: int | None = None):
    """The fast property (``FAST``, or ``fast_examples`` examples) and its long variant
    (``-m slow``, ``LONG``) of one body over the same strategies."""
    fast = FAST if fast_examples is None else settings(FAST, max_examples=fast_examples)
    return (fast(given(**strategies)(body)),
            pytest.mark.slow(LONG(given(**strategies)(body))))


# --------------------------------------------------------------------------------------------
# layered supports: built on the ballasted preset, then a few steps on a linear and the full
# path
SUPPORT_FIELDS = ("stiffness", "damping", "sleeper_mass", "ballast_stiffness",
                  "ballast_damping")


def _layered(values, fidelity):
    names = [f"Supports.{k}" for k in values] + [SAGS]

    def build():
        return tw.Scene(rail=BALLASTED.rail, supports=tw.Supports(
            spacing=BALLASTED.supports.spacing, **values), wheel=BALLASTED.wheel,
            gravity=BALLASTED.gravity)

    scene = clean_or_finite(build, names, check=lambda s: math.isfinite(s.static_sag))
    if scene is None:
        return
    r = clean_or_finite(lambda: tw.simulate(scene, 50.0, x_start=3.0, duration=5e-4,
                                            fidelity=fidelity, progress=False),
                        ["never: a built scene runs"],
                        check=lambda r: finite(r.normal_force, r.y_contact, r.y_wheel))
    assert r.steps > 0


test_layered_supports, test_layered_supports_long = both(
    _layered, {"values": st.fixed_dictionaries(
        {k: field_values(f"Supports.{k}") for k in SUPPORT_FIELDS}),
        "fidelity": st.sampled_from(["linear/hertz", "full"])})


# --------------------------------------------------------------------------------------------
# the travelling window: a few bays' run on the ballasted track
def _window(behind, ahead, absorbing):
    names = ["Window.bays_behind", "Window.bays_ahead", "Window.absorbing_length"]
    window = clean_or_finite(lambda: tw.Window(behind, ahead, absorbing), names,
                             check=lambda w: True)
    if window is None:
        return
    scene = tw.Scene.ballasted_track(window=window)
    r = clean_or_finite(lambda: tw.simulate(scene, 50.0, distance=1.2, fidelity="linear/hertz",
                                            progress=False),
                        ["never: a window runs"], check=lambda r: finite(r.normal_force))
    assert r.x_wheel[-1] - r.x_wheel[0] == pytest.approx(1.2, abs=50.0 * r.settings.dt)


test_window, test_window_long = both(_window, {
    "behind": st.one_of(st.integers(1, 60), st.sampled_from([0, -1, 1001, 2.0, "3", None])),
    "ahead": st.one_of(st.integers(1, 60), st.sampled_from([0, -1, 1001, 2.0, "3", None])),
    "absorbing": field_values("Window.absorbing_length")}, fast_examples=25)


# --------------------------------------------------------------------------------------------
# rail profiles: sines, dipped joints, samples; evaluated anywhere
X = st.one_of(st.floats(-1e3, 1e3), st.sampled_from([0.0, 1e9, -1e9]))


def _profile(kind, a, b, c, x):
    if kind == "sine":
        make, names = (lambda: tw.Irregularity.sine(a, b, c)), ["Irregularity.sine", "phase"]
    elif kind == "joint":
        make, names = (lambda: tw.Irregularity.dipped_joint(a, b, c)), [
            "Irregularity.dipped_joint"]
    else:  # four samples a apart, r alternating +-b
        def make():
            return tw.Irregularity.samples(
                [c + i * a if isinstance(a, float) else a for i in range(4)],
                [b * (-1) ** i if isinstance(b, float) else b for i in range(4)])

        names = ["Irregularity.samples"]
    irr = clean_or_finite(make, names, check=lambda i: True)
    if irr is None:
        return
    if kind == "samples":
        x = min(max(x, irr.parts[0].x[0]), irr.parts[0].x[-1])  # inside the samples
    clean_or_finite(lambda: (irr(x), irr.slope(x), irr.curvature(x)), ["never"])


_LENGTH = st.one_of(log_uniform(1e-320, 1e300), st.sampled_from([0.0, -1.0, NAN, INF, "1"]))
test_profiles, test_profiles_long = both(_profile, {
    "kind": st.sampled_from(["sine", "joint", "samples"]), "a": _LENGTH,
    "b": st.one_of(log_uniform(1e-320, 1e300), st.sampled_from([0.0, -1e-3, NAN, INF, None])),
    "c": st.one_of(st.floats(-1e3, 1e3), st.sampled_from([NAN, INF, 1e300])), "x": X},
    fast_examples=60)


# --------------------------------------------------------------------------------------------
# wheel defects: on a wheel of the drawn radius, evaluated around the wheel
PSI = st.one_of(st.floats(-10.0, 10.0), st.sampled_from([0.0, 1e-300, -1e-300, 1e6]))


def _defect(kind, a, b, rounded, radius, psi):
    if kind == "flat":
        depth = b if rounded else None
        make, names = (lambda: tw.WheelFlat(a, rounded=rounded, depth=depth)), ["WheelFlat"]
    else:
        make, names = (lambda: tw.Polygon(int(b) if isinstance(b, float) and math.isfinite(b)
                                          and 1 <= b <= 1e6 else b, a)), ["Polygon"]
    d = clean_or_finite(make, names, check=lambda d: True)
    if d is None:
        return
    wheel = clean_or_finite(lambda: tw.Wheel(radius=radius, defects=(d,)),
                            names + ["Wheel.radius", "radius"], check=lambda w: True)
    if wheel is None:
        return
    clean_or_finite(lambda: (d.delta_rho(psi, radius), d.delta_rho_dpsi(psi, radius),
                             d.delta_rho_dpsi2(psi, radius)), ["never"])


test_wheel_defects, test_wheel_defects_long = both(_defect, {
    "kind": st.sampled_from(["flat", "polygon"]), "a": _LENGTH,
    "b": st.one_of(log_uniform(1e-320, 1e300), st.sampled_from([1.0, 7.0, 0.0, NAN, None])),
    "rounded": st.booleans(), "radius": field_values("Wheel.radius"), "psi": PSI},
    fast_examples=60)


# --------------------------------------------------------------------------------------------
# vehicles: the bogie preset, and a half car with drawn bodies
BOGIE_FIELDS = ("mass", "pitch_inertia", "primary_stiffness", "primary_damping")
CAR_FIELDS = ("mass", "pitch_inertia", "secondary_stiffness", "secondary_damping")


def _vehicle(wheelbase, load, bogie, car):
    names = ["wheelbase", "load", "Vehicle.", "Bogie.", "CarBody.", SAGS]

    def build():
        half = tw.Vehicle.half_car()
        bogies = tuple(tw.Bogie(wheels=b.wheels, centre=b.centre, **bogie)
                       for b in half.bogies)
        veh = tw.Vehicle(wheels=half.wheels, positions=half.positions, bogies=bogies,
                         car=tw.CarBody(centre=half.car.centre, **car))
        pair = tw.Vehicle.bogie(wheelbase=wheelbase, load=load)
        scenes = [tw.Scene(vehicle=v, rail=tw.Rail(length=30.0, n_elements=60))
                  for v in (veh, pair)]
        return [(v, s) for v, s in zip((veh, pair), scenes)]

    def check(built):
        for v, s in built:
            loads = v.static_loads(s.gravity)
            freqs = rigid_track_frequencies(v)
            assert finite(loads, list(freqs.values()), s.static_sag) and min(loads) > 0.0
        return True

    clean_or_finite(build, names, check=check)


test_vehicles, test_vehicles_long = both(_vehicle, {
    "wheelbase": st.one_of(log_uniform(1e-300, 1e300), st.sampled_from([0.0, NAN, -2.5])),
    "load": st.one_of(st.none(), field_values("Bogie.load")),
    "bogie": st.fixed_dictionaries({k: field_values(f"Bogie.{k}") for k in BOGIE_FIELDS}),
    "car": st.fixed_dictionaries({k: field_values(f"CarBody.{k}") for k in CAR_FIELDS})})


# --------------------------------------------------------------------------------------------
# receptance and decay rate
FREQS = st.lists(st.one_of(st.floats(0.0, 2e5), st.sampled_from([0.0, 1e5, -1.0, NAN, INF,
                                                                 1e155])),
                 min_size=1, max_size=4)


def _receptance(x_frac, freqs, damping, response):
    scene = tw.Scene(supports=tw.Supports(damping=damping)) if damping else KATO
    L = scene.rail.length
    x = x_frac * L if isinstance(x_frac, float) else x_frac
    xr = None if response is None else [f * L for f in response]
    clean_or_finite(lambda: tw.receptance(scene, x, freqs, xr),
                    ["x =", "x must", "x_response", "freqs"])


test_receptance, test_receptance_long = both(_receptance, {
    "x_frac": st.one_of(st.floats(-0.2, 1.2), st.sampled_from([NAN, "1", None])),
    "freqs": FREQS, "damping": st.one_of(st.just(0.0), log_uniform(1e2, 1e6)),
    "response": st.one_of(st.none(), st.lists(st.floats(-0.1, 1.1), min_size=1, max_size=3))})


def _decay(n_bays, x0, freqs):
    scene = tw.Scene.ballasted_track(0.6 * n_bays, elements_per_bay=2)
    out = clean_or_finite(lambda: tw.decay_rate(scene, freqs, x0=x0),
                          ["EN 15461 positions", "x0", "freqs"],
                          check=lambda d: finite(d) and np.all(np.asarray(d) > 0.0))
    if out is not None:
        assert scene.rail.length >= tw.frequency.EN15461_SPANS[-1] * 0.6


test_decay_rate, test_decay_rate_long = both(_decay, {
    "n_bays": st.integers(3, 120),
    "x0": st.one_of(st.none(), st.floats(-1.0, 80.0), st.sampled_from([0.0, NAN, "1"])),
    "freqs": FREQS}, fast_examples=25)

