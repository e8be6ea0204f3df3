"""The C++ kernel never takes Python down (issue 8): wrong-size arrays and hostile values at the
``trackwheel._core`` level become Python exceptions (run under ASan/UBSan by
``scripts/sanitize.sh``). (Split from test_robustness.py by room: the bindings.)
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

import trackwheel as tw
from trackwheel import _core
from trackwheel.run import kernel as _kernel

KATO = tw.Scene.kato2005()
NAN, INF = float("nan"), float("inf")


# --------------------------------------------------------------------------------------------
# 2. the kernel never takes Python down
# --------------------------------------------------------------------------------------------
MODEL = _kernel.rail_model(KATO, 20)
E0 = np.asarray(MODEL.reference())
WHEEL = _kernel.wheel_params(KATO)
CONTACT = _kernel.contact_params(KATO)


@pytest.mark.parametrize("n", [0, 3, 83, 1000])
@pytest.mark.parametrize("call", [
    lambda e: MODEL.internal_force(e),  # n = 0 used to segfault, n = 3 read out of bounds
    lambda e: MODEL.tangent_dense(e),
    lambda e: MODEL.positions(e, [2.5]),
    lambda e: _core.contact_eval(MODEL, e, 2.5, 0.1, 2.5, CONTACT, np.zeros(10)),
    lambda e: _core.testing.rolling_eval(MODEL, e, 2.5, 0.1, 2.5, np.zeros(10), 1.0),
    lambda e: _core.highest_frequency(MODEL, WHEEL, CONTACT, e, 2.5, 0.1),
], ids=["internal_force", "tangent_dense", "positions", "contact_eval", "rolling_eval",
        "highest_frequency"])
def test_kernel_rejects_wrong_size_coordinates(call, n):
    assert MODEL.n_dof == 84
    with pytest.raises(ValueError, match=f"e has {n} entries; this rail has n_dof = 84"):
        call(np.zeros(n))


def test_kernel_hostile_values_become_exceptions():
    # invalid_argument -> ValueError
    with pytest.raises(ValueError, match="finite"):
        MODEL.positions(E0, [NAN])
    with pytest.raises(ValueError, match="x_wheel = 7 m is outside the rail"):
        _core.static_solve(MODEL, WHEEL, CONTACT, 7.0)
    with pytest.raises(ValueError, match="n_modes must be in"):
        _core.vertical_modes(MODEL, 10.0, 7e8, [2.5], 10**6)
    with pytest.raises(ValueError, match="n_gauss"):
        _core.testing.gauss_points(0)
    p = _core.RailParams()  # no physics defaults: every field 0
    with pytest.raises(ValueError, match="rail length must be > 0 m"):
        _core.RailModel(p, _core.SupportParams())
    p.length, p.n_elements, p.n_gauss = 5.0, 20, 5
    with pytest.raises(ValueError, match="EA must be > 0"):
        _core.RailModel(p, _core.SupportParams())
    s = _core.SupportParams()
    s.position = [1.0, 2.0]
    s.stiffness = [1.0]
    with pytest.raises(ValueError, match="same length"):
        _core.RailModel(MODEL_PARAMS(), s)
    # runtime_error -> RuntimeError, with the reason
    with pytest.raises(RuntimeError, match="contact-point search did not converge"):
        _core.contact_eval(MODEL, E0, NAN, 0.1, 2.5, CONTACT, np.zeros(10))
    with pytest.raises(RuntimeError, match="contact-point search did not converge"):
        _core.contact_eval(MODEL, E0, 2.5, 0.1, NAN, CONTACT, np.zeros(10))
    # wrong fixed-size argument: pybind11's TypeError, not a crash
    with pytest.raises(TypeError):
        _core.contact_eval(MODEL, E0, 2.5, 0.1, 2.5, CONTACT, np.zeros(3))


def MODEL_PARAMS():
    p = _core.RailParams()
    p.length, p.n_elements, p.n_gauss = 5.0, 20, 5
    p.EA, p.EI, p.rhoA = 1.0, 1.0, 1.0
    return p


def test_contact_far_from_the_rail_is_inactive_and_finite():
    """A wheel 1 km away finds the nearest rail point (an end), no contact force."""
    for xa, ya in [(1e3, 1e3), (2.5, -1e3), (-50.0, 0.3)]:
        d = _core.contact_eval(MODEL, E0, xa, ya, 2.5, CONTACT, np.zeros(10))
        assert not d["active"] and d["N"] == 0.0
        assert 0.0 <= d["s"] <= 5.0 and math.isfinite(d["rho"])
        # rho is the distance to the nearest point of the straight rail
        nearest = min(max(xa, 0.0), 5.0)
        assert d["rho"] == pytest.approx(math.hypot(xa - nearest, ya), rel=1e-12)


def _kernel_sim_inputs(**settings):
    st = _core.SimState()
    st.e = E0.copy()
    st.edot = np.zeros_like(E0)
    w = _core.WheelState()
    w.y = 0.1
    w.s = 2.5
    st.wheels = [w]
    s = _core.SimSettings()
    s.speed, s.x_start, s.t_end, s.dt = 10.0, 2.5, 1e-4, 1e-5
    for k, v in settings.items():
        setattr(s, k, v)
    return s, st


def test_kernel_simulate_hostile_settings_and_callbacks():
    s, st = _kernel_sim_inputs()
    st.e = np.zeros(5)
    with pytest.raises(ValueError, match="initial rail state has the wrong size"):
        _core.simulate(MODEL, [WHEEL], CONTACT, s, st, None)
    for field, value, match in [("dt", 0.0, "dt"), ("dt", NAN, "dt"), ("t_end", INF, "t_end"),
                                ("output_every", 0, "output_every"),
                                ("rho_inf", NAN, "rho_inf"),
                                ("speed", _core.MAX_SPEED * 1.01, r"speed must be in \[0, 300\]"),
                                ("speed", -1.0, "speed"), ("speed", NAN, "speed")]:
        s, st = _kernel_sim_inputs(**{field: value})
        with pytest.raises(ValueError, match=match):
            _core.simulate(MODEL, [WHEEL], CONTACT, s, st, None)
    # an exception in the progress callback propagates as itself
    s, st = _kernel_sim_inputs(progress_every=1)

    def boom(step, total):
        raise ZeroDivisionError("from the callback")

    with pytest.raises(ZeroDivisionError, match="from the callback"):
        _core.simulate(MODEL, [WHEEL], CONTACT, s, st, boom)
    with pytest.raises(TypeError):
        _core.simulate(MODEL, [WHEEL], CONTACT, s, st, 5)
    # a non-finite state is a clean error, not NaN output
    s, st = _kernel_sim_inputs()
    w = st.wheels[0]
    w.y = NAN
    st.wheels = [w]
    with pytest.raises(RuntimeError, match="contact-point search"):
        _core.simulate(MODEL, [WHEEL], CONTACT, s, st, None)


def test_divergence_is_a_runtime_error_subclass_with_fields():
    with pytest.raises(tw.DivergenceError) as info, warnings.catch_warnings():
        warnings.simplefilter("ignore")  # a warning that dt is above the stability limit
        tw.simulate(KATO, tw.kmh(300), integrator="explicit", dt=2e-5, x_end=0.5)
    e = info.value
    assert isinstance(e, RuntimeError)
    assert e.step > 0 and e.time == pytest.approx(e.step * 2e-5) and "stability limit" in e.cause
