"""Robustness (issue 8): bad input, hostile kernel calls, determinism, threads, memory, Ctrl-C.

- Every public function rejects bad arguments with ``ValueError``/``TypeError`` whose message names
  the parameter, the offending value and the allowed range (or choices).
- The C++ kernel never takes Python down: wrong-size arrays and hostile values at the
  ``trackwheel._core`` level become Python exceptions (run under ASan/UBSan by
  ``scripts/sanitize.sh``).
- The same call twice gives bit-identical arrays; two threads simulating at once give the serial
  results bit for bit, and ``simulate`` releases the GIL.
- Output decimation bounds the kept samples; Ctrl-C interrupts a long run within about a second.

Sweep-level robustness (worker-count independence, Ctrl-C keeping finished cases) is tested with
the sweeps.
"""

from __future__ import annotations

import dataclasses as dc
import math
import os
import signal
import subprocess
import sys
import threading
import time
import warnings
from pathlib import Path

import numpy as np
import pytest
import trackwheel as tw
from trackwheel import _core, _kernel, cli, plots

SIM = sys.modules["trackwheel.simulate"]
EIGEN = sys.modules["trackwheel.eigen"]
KATO = tw.Scene.kato2005()
NAN, INF = float("nan"), float("inf")


def _eigen_result():
    return tw.eigen(KATO, [1.0, 2.5], n_modes=4)


# --------------------------------------------------------------------------------------------
# 1. input validation at the Python boundary
# --------------------------------------------------------------------------------------------
# (call, exception, fragments the message must contain: the parameter, the value and the range)
BAD_CALLS = [
    # scene dataclasses
    (lambda: tw.Rail(length=0.0), ValueError, ["Rail.length", "0.0", "(0.0, inf]"]),
    (lambda: tw.Rail(length=-5.0), ValueError, ["Rail.length", "-5.0", "allowed range"]),
    (lambda: tw.Rail(length=NAN), ValueError, ["Rail.length", "nan", "not finite"]),
    (lambda: tw.Rail(length="5"), TypeError, ["Rail.length", "real number", "str"]),
    (lambda: tw.Rail(youngs_modulus=INF), ValueError, ["Rail.youngs_modulus", "inf"]),
    (lambda: tw.Rail(poisson_ratio=0.5), ValueError, ["Rail.poisson_ratio", "0.5", "0.5)"]),
    (lambda: tw.Rail(density=-1.0), ValueError, ["Rail.density", "-1.0", "allowed range"]),
    (lambda: tw.Rail(area=0.0), ValueError, ["Rail.area", "0.0", "allowed range"]),
    (lambda: tw.Rail(second_moment=None), TypeError, ["Rail.second_moment", "NoneType"]),
    (lambda: tw.Rail(n_elements=0), ValueError, ["Rail.n_elements", "0", "[1, 2000]"]),
    (lambda: tw.Rail(n_elements=20.0), TypeError, ["Rail.n_elements", "integer", "float"]),
    (lambda: tw.Rail(n_elements=True), TypeError, ["Rail.n_elements", "integer", "bool"]),
    (lambda: tw.Rail(curvature="linear"), ValueError, ["Rail.curvature", "'linear'", "exact"]),
    (lambda: tw.Rail(curvature=["exact"]), ValueError, ["Rail.curvature", "['exact']", "exact"]),
    (lambda: tw.Rail(far_end=None), ValueError, ["Rail.far_end", "None", "roller"]),
    (lambda: tw.Rail(n_gauss=11), ValueError, ["Rail.n_gauss", "11", "[2, 10]"]),
    # one Gauss point under-integrates bending: singular stiffness, silent 0 Hz modes
    (lambda: tw.Rail(n_gauss=1), ValueError, ["Rail.n_gauss", "1", "[2, 10]"]),
    (lambda: tw.Supports(stiffness=0.0), ValueError, ["Supports.stiffness", "0.0", "(0.0, inf]"]),
    (lambda: tw.Supports(spacing=-0.5), ValueError, ["Supports.spacing", "-0.5"]),
    (lambda: tw.Supports(damping=-1.0), ValueError, ["Supports.damping", "-1.0", "[0.0, inf]"]),
    (lambda: tw.Supports(positions=(1.0, NAN)), ValueError, ["Supports.positions", "NaN"]),
    (lambda: tw.Supports(positions=("a",)), TypeError, ["Supports.positions", "real numbers"]),
    (lambda: tw.Supports(positions=[[1.0, 2.0]]), ValueError, ["Supports.positions", "1-d"]),
    (lambda: tw.Scene(supports=tw.Supports(positions=(1.0, 5.0))), ValueError,
     ["Supports.positions", "5.0", "(0, 5.0)"]),
    (lambda: tw.Scene(supports=tw.Supports(spacing=4.0)), ValueError,
     ["Supports.spacing", "4.0", "allowed range"]),
    # a tiny spacing used to try to build 5e9 supports and exhaust memory
    (lambda: tw.Scene(supports=tw.Supports(spacing=1e-9)), ValueError,
     ["Supports.spacing", "1e-09", "allowed range"]),
    (lambda: tw.Wheel(mass=0.0), ValueError, ["Wheel.mass", "0.0", "(0.0, inf]"]),
    (lambda: tw.Wheel(radius=-0.1), ValueError, ["Wheel.radius", "-0.1"]),
    (lambda: tw.Wheel(load=-1.0), ValueError, ["Wheel.load", "-1.0", "[0.0, inf]"]),
    (lambda: tw.Wheel(inertia=0.0), ValueError, ["Wheel.inertia", "0.0"]),
    (lambda: tw.Wheel(torque=NAN), ValueError, ["Wheel.torque", "nan"]),
    (lambda: tw.Contact(law="quadratic"), ValueError, ["Contact.law", "'quadratic'", "hertz"]),
    (lambda: tw.Contact(stiffness=-1.0), ValueError, ["Contact.stiffness", "-1.0"]),
    (lambda: tw.Contact(friction=INF), ValueError, ["Contact.friction", "inf"]),
    (lambda: tw.Contact(damping=-2.0), ValueError, ["Contact.damping", "-2.0"]),
    (lambda: tw.Scene(gravity=-9.8), ValueError, ["Scene.gravity", "-9.8", "[0.0, inf]"]),
    (lambda: tw.Scene(rail_gravity="yes"), TypeError, ["Scene.rail_gravity", "str"]),
    (lambda: tw.Scene(wheel=tw.Rail()), TypeError, ["Scene.wheel", "Wheel", "Rail"]),
    (lambda: tw.kmh(-300), ValueError, ["speed_kmh", "-300", "[0.0, inf]"]),
    (lambda: tw.kmh("300"), TypeError, ["speed_kmh", "str"]),
    # statics
    (lambda: tw.static(KATO, 5.5), ValueError, ["x_wheel", "5.5", "[0.0, 5.0]"]),
    (lambda: tw.static(KATO, -0.1), ValueError, ["x_wheel", "-0.1", "[0.0, 5.0]"]),
    (lambda: tw.static(KATO, NAN), ValueError, ["x_wheel", "nan"]),
    (lambda: tw.static(KATO, None), TypeError, ["x_wheel", "NoneType"]),
    (lambda: tw.static("kato", 1.0), TypeError, ["scene", "str"]),
    (lambda: tw.static(KATO, 1.0, n_elements=0), ValueError, ["n_elements", "0", "[1, 2000]"]),
    (lambda: tw.static(KATO, 2.5).rail_shape(1), ValueError, ["n_points", "1"]),
    (lambda: tw.quasi_static(KATO, []), ValueError, ["positions", "non-empty"]),
    (lambda: tw.quasi_static(KATO, [1.0, 6.0]), ValueError, ["positions", "6.0", "[0.0, 5.0]"]),
    (lambda: tw.quasi_static(KATO, [1.0, INF]), ValueError, ["positions", "inf"]),
    (lambda: tw.quasi_static(KATO, None), TypeError, ["positions", "NoneType"]),
    (lambda: tw.quasi_static(KATO, [True, False]), TypeError, ["positions", "bool"]),
    # eigen
    (lambda: tw.eigen(KATO, [7.0]), ValueError, ["positions", "7.0", "[0.0, 5.0]"]),
    (lambda: tw.eigen(KATO, "2.5"), TypeError, ["positions", "str"]),
    (lambda: tw.eigen(KATO, [2.5], n_modes=0), ValueError, ["n_modes", "0", "[1, 41]"]),
    (lambda: tw.eigen(KATO, [2.5], n_modes=42), ValueError, ["n_modes", "42", "[1, 41]"]),
    (lambda: tw.eigen(KATO, [2.5], n_axial=-1), ValueError, ["n_axial", "-1"]),
    (lambda: tw.eigen(KATO, [2.5], n_elements=2.5), TypeError, ["n_elements", "float"]),
    (lambda: tw.eigen(None, [2.5]), TypeError, ["scene", "NoneType"]),
    (lambda: _eigen_result().rail_mode_shape(2, 0), ValueError, ["i_pos", "2", "[-2, 1]"]),
    (lambda: _eigen_result().rail_mode_shape(0, 4), ValueError, ["mode", "4", "[0, 3]"]),
    (lambda: _eigen_result().rail_mode_shape(0.0, 0), TypeError, ["i_pos", "float"]),
    (lambda: EIGEN.rail_frequencies(None), TypeError, ["scene", "NoneType"]),
    # simulate
    (lambda: tw.simulate(KATO, -1.0), ValueError, ["speed", "-1.0", "[0.0, 300.0]"]),
    (lambda: tw.simulate(KATO, NAN), ValueError, ["speed", "nan"]),
    (lambda: tw.simulate(KATO, "fast"), TypeError, ["speed", "str"]),
    (lambda: tw.simulate(KATO, 0.0), ValueError, ["speed = 0", "duration"]),
    (lambda: tw.simulate(KATO, 10.0, dt=0.0), ValueError, ["dt", "0.0", "(0.0, 1.0]"]),
    (lambda: tw.simulate(KATO, 10.0, dt=-1e-5), ValueError, ["dt", "-1e-05", "(0.0, 1.0]"]),
    (lambda: tw.simulate(KATO, 10.0, dt=INF), ValueError, ["dt", "inf"]),
    # a step longer than the run, and a step so short the run could never finish
    (lambda: tw.simulate(KATO, 10.0, duration=1e-6, dt=1e-5), ValueError,
     ["dt", "1e-05", "allowed range"]),
    (lambda: tw.simulate(KATO, 10.0, dt=1e-20), ValueError, ["dt", "1e-20", "allowed range"]),
    (lambda: tw.simulate(KATO, 10.0, x_start=1.0, x_end=0.5), ValueError,
     ["x_end", "0.5", "x_start", "1.0"]),
    (lambda: tw.simulate(KATO, 10.0, x_start=1.0, x_end=1.0), ValueError, ["x_end", "1.0"]),
    (lambda: tw.simulate(KATO, 10.0, x_start=-0.1), ValueError, ["x_start", "-0.1", "[0.0, 5.0]"]),
    (lambda: tw.simulate(KATO, 10.0, x_end=5.1), ValueError, ["x_end", "5.1", "[0.0, 5.0]"]),
    (lambda: tw.simulate(KATO, 10.0, duration=1.0), ValueError, ["duration", "1.0", "beyond"]),
    (lambda: tw.simulate(KATO, 10.0, duration=0.0), ValueError, ["duration", "0.0"]),
    (lambda: tw.simulate(KATO, 10.0, integrator="rk4"), ValueError,
     ["integrator", "'rk4'", "generalized_alpha"]),
    (lambda: tw.simulate(KATO, 10.0, integrator=["explicit"]), ValueError, ["integrator"]),
    (lambda: tw.simulate(KATO, 10.0, start="moving"), ValueError, ["start", "'moving'", "static"]),
    (lambda: tw.simulate(KATO, 10.0, n_elements=0), ValueError, ["n_elements", "0"]),
    (lambda: tw.simulate(KATO, 10.0, output_every=0), ValueError, ["output_every", "0"]),
    (lambda: tw.simulate(KATO, 10.0, output_every=2**31), ValueError, ["output_every"]),
    (lambda: tw.simulate(KATO, 10.0, output_every=2.0), TypeError, ["output_every", "float"]),
    (lambda: tw.simulate(KATO, 10.0, rho_inf=1.5), ValueError, ["rho_inf", "1.5", "[0.0, 1.0]"]),
    (lambda: tw.simulate(KATO, 10.0, baumgarte=-1.0), ValueError, ["baumgarte", "-1.0"]),
    (lambda: tw.simulate(KATO, 10.0, drop_height=0.2), ValueError,
     ["drop_height", "0.2", "[0.0, 0.1]"]),
    (lambda: tw.simulate(KATO, 10.0, max_newton=0), ValueError, ["max_newton", "0"]),
    (lambda: tw.simulate(KATO, 10.0, newton_tol=0.0), ValueError, ["newton_tol", "0.0"]),
    (lambda: tw.simulate(KATO, 10.0, rolling=1), TypeError, ["rolling", "True or False"]),
    (lambda: tw.simulate(KATO, 10.0, energy="yes"), TypeError, ["energy", "str"]),
    (lambda: tw.simulate(KATO, 10.0, progress="yes"), TypeError, ["progress", "str"]),
    (lambda: tw.simulate([], 10.0), TypeError, ["scene", "list"]),
    # plots
    (lambda: plots.eigen(KATO), TypeError, ["result", "EigenResult", "Scene"]),
    (lambda: plots.eigen(_eigen_result(), n_modes=5), ValueError, ["n_modes", "5", "[1, 4]"]),
    (lambda: plots.eigen(_eigen_result(), ax="axes"), TypeError, ["ax", "str"]),
    (lambda: plots.mode_shapes(_eigen_result(), 3), ValueError, ["i_pos", "3", "[-2, 1]"]),
    (lambda: plots.mode_shapes(_eigen_result(), 0, modes=None), TypeError, ["modes", "NoneType"]),
    (lambda: plots.mode_shapes(_eigen_result(), 0, modes=[4]), ValueError,
     ["modes", "4", "[0, 3]"]),
    (lambda: plots.mode_shapes(_eigen_result(), 0, modes=[]), ValueError, ["modes"]),
]


@pytest.mark.parametrize("call,exc,fragments", BAD_CALLS,
                         ids=[f"bad{i:03d}" for i in range(len(BAD_CALLS))])
def test_bad_argument_names_parameter_value_and_range(call, exc, fragments):
    with pytest.raises(exc) as info:
        call()
    assert type(info.value) is exc  # not a subclass such as DivergenceError
    msg = str(info.value)
    for frag in fragments:
        assert frag in msg, f"{frag!r} missing from the message {msg!r}"


@pytest.mark.parametrize("argv,fragment", [
    (["eigen", "--position", "nan"], "--position"),
    (["eigen", "--position", "7"], "allowed range [0, 5] m"),
    (["eigen", "--n-modes", "0"], "--n-modes"),
    (["eigen", "--n-modes", "500"], "--n-modes = 500 is outside the allowed range [1, 41]"),
    (["reproduce"], "--out"),
    (["reproduce", "--out", "/proc/no/such/folder"], "cannot create the folder"),
    (["no-such-command"], "invalid choice"),
])
def test_cli_bad_arguments_exit_2_with_a_message(argv, fragment, capsys):
    assert cli.main(argv) == 2
    assert fragment in capsys.readouterr().err


def test_eigen_default_axial_modes_on_a_one_element_rail():
    """The default n_axial = 3 is capped at the axial modes a coarse mesh has (it raised)."""
    one = dc.replace(KATO, rail=dc.replace(KATO.rail, n_elements=1, far_end="pinned"),
                     supports=tw.Supports(positions=()))
    r = tw.eigen(one, [2.5], n_modes=1)
    # pinned at both ends, the only free axial coordinates are the two end slopes x_s
    assert r.axial_frequencies.shape == (2,)
    # the lower is the bar's fixed-fixed fundamental c/(2L), c = sqrt(EA/(rho A)); one cubic
    # element carries the half sine with a 0.7 % (Rayleigh-Ritz, from above) error
    c = math.sqrt(KATO.rail.axial_stiffness / KATO.rail.mass_per_length)
    assert c / (2 * 5.0) < r.axial_frequencies[0] < 1.02 * c / (2 * 5.0)


def test_supports_explicit_positions_accept_a_scalar_and_the_empty_tuple():
    assert tw.Supports(positions=2.5).positions == (2.5,)
    assert tw.Supports(positions=[]).positions == ()
    assert tw.Scene(supports=tw.Supports(positions=())).support_positions == ()


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
    lambda e: _core.rolling_eval(MODEL, e, 2.5, 0.1, 2.5, np.zeros(10), 1.0),
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
        _core.gauss_points(0)
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
                                ("rho_inf", NAN, "rho_inf")]:
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


# --------------------------------------------------------------------------------------------
# 3. determinism
# --------------------------------------------------------------------------------------------
_ARRAYS = ("t", "x_wheel", "y_wheel", "ydot_wheel", "theta", "thetadot", "contact_s",
           "y_contact", "normal_force", "tangential_force", "slip", "slip_state", "v_error",
           "phi", "acc_contact", "acc_A", "acc_B", "acc_C", "acc_D", "acc_E", "reaction",
           "penetration")


def assert_bit_identical(a, b):
    for name in _ARRAYS:
        x, y = getattr(a, name), getattr(b, name)
        assert x.dtype == y.dtype and x.shape == y.shape, name
        assert x.tobytes() == y.tobytes(), f"{name} differs"
    assert a.steps == b.steps and a.newton_iterations == b.newton_iterations
    assert a.state_changes == b.state_changes


# short runs through a support (element and contact transitions), both integrators
RUNS = {
    "generalized_alpha": dict(integrator="generalized_alpha", x_start=0.4, x_end=0.62, dt=1e-5),
    "explicit": dict(integrator="explicit", x_start=0.45, x_end=0.52, dt=5e-7),
}


@pytest.mark.parametrize("kind", sorted(RUNS))
def test_simulate_twice_is_bit_identical(kind):
    a = tw.simulate(KATO, tw.kmh(300), **RUNS[kind])
    _kernel.rail_model.cache_clear()  # a freshly built kernel model, too
    b = tw.simulate(KATO, tw.kmh(300), **RUNS[kind])
    assert a.steps > 100
    assert_bit_identical(a, b)


def test_static_and_eigen_twice_are_bit_identical():
    a, b = tw.static(KATO, 1.3), tw.static(KATO, 1.3)
    assert a.rail_coordinates.tobytes() == b.rail_coordinates.tobytes()
    assert (a.y_wheel, a.y_contact, a.contact_s) == (b.y_wheel, b.y_contact, b.contact_s)
    x = np.linspace(0.0, 5.0, 11)
    qa, qb = tw.quasi_static(KATO, x), tw.quasi_static(KATO, x)
    assert qa.y_contact.tobytes() == qb.y_contact.tobytes()
    ea, eb = tw.eigen(KATO, x), tw.eigen(KATO, x)
    assert ea.frequencies.tobytes() == eb.frequencies.tobytes()
    assert ea.shapes.tobytes() == eb.shapes.tobytes()


# --------------------------------------------------------------------------------------------
# 4. threads
# --------------------------------------------------------------------------------------------
def _threaded(fns):
    out = [None] * len(fns)
    errors = []

    def run(i):
        try:
            out[i] = fns[i]()
        except BaseException as exc:  # re-raised in the main thread
            errors.append(exc)

    threads = [threading.Thread(target=run, args=(i,)) for i in range(len(fns))]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    if errors:
        raise errors[0]
    return out


def test_concurrent_threads_equal_serial_runs_bit_for_bit():
    soft = dc.replace(KATO, supports=dc.replace(KATO.supports, stiffness=40e6))
    jobs = [
        lambda: tw.simulate(KATO, tw.kmh(300), **RUNS["generalized_alpha"]),
        lambda: tw.simulate(soft, tw.kmh(200), **RUNS["generalized_alpha"]),
        lambda: tw.simulate(KATO, tw.kmh(300), **RUNS["explicit"]),
        lambda: tw.simulate(KATO, tw.kmh(300), **RUNS["generalized_alpha"]),  # same as job 0
    ]
    serial = [job() for job in jobs]
    parallel = _threaded(jobs)
    for a, b in zip(serial, parallel):
        assert_bit_identical(a, b)


def test_simulate_releases_the_gil():
    """While a simulation runs in a thread, the main thread keeps running Python code.

    If the kernel held the GIL, the main thread could not execute a single bytecode until the
    call returned: one gap as long as the run. With it released (the kernel takes it only for
    microseconds at each progress callback), the main thread ticks throughout; the longest gap
    is a scheduling hiccup, far below half the run even on a loaded machine."""
    result = []
    worker = threading.Thread(target=lambda: result.append(
        tw.simulate(KATO, tw.kmh(100), x_start=0.25, x_end=4.75, dt=1e-5)))
    stamps = []
    worker.start()
    while worker.is_alive():
        stamps.append(time.perf_counter())
        time.sleep(0.001)
    worker.join()
    assert result and result[0].steps == round(4.5 / tw.kmh(100) / 1e-5)
    wall = stamps[-1] - stamps[0]
    assert wall > 0.1  # the run is long enough to tell (~0.3 s)
    assert len(stamps) > 20 and max(np.diff(stamps)) < 0.5 * wall


# --------------------------------------------------------------------------------------------
# 5. memory: decimation and the output limit
# --------------------------------------------------------------------------------------------
def test_default_decimation_bounds_the_kept_samples():
    """250 000 steps keep at most DEFAULT_MAX_SAMPLES + 1 samples, evenly spaced. (The
    decimation is the same for every model level; the linear moving-force level makes the
    250 000 steps cheap. benchmarks/memory.py measures the peak memory of 10^6 full steps.)"""
    r = tw.simulate(KATO, 0.0, x_start=2.5, duration=0.25, dt=1e-6,
                    fidelity="linear/moving_force")
    assert r.steps == 250_000
    assert r.settings["output_every"] == 3
    assert len(r.t) == 83_334 <= SIM.DEFAULT_MAX_SAMPLES + 1
    np.testing.assert_allclose(np.diff(r.t), 3e-6, rtol=1e-9)


def test_output_request_above_the_limit_raises_before_allocating():
    """10^9 samples x 172 bytes (the output table without energy: 21 float64 fields and the
    int32 slip state) = 160 GiB: refused at once (well before any run); output_every must be at
    least ceil(10^9 x 172 / 2^31) = 81."""
    assert sum(4 if f[4] == "int32" else 8 for f in _core.OUTPUT_FIELDS if f[0] != "energy") == 172
    t0 = time.perf_counter()
    with pytest.raises(ValueError, match=r"GiB\), above the limit of 2 GiB: increase "
                                         r"output_every to at least 81"):
        tw.simulate(KATO, 0.0, x_start=2.5, duration=1000.0, dt=1e-6, output_every=1)
    assert time.perf_counter() - t0 < 1.0


# --------------------------------------------------------------------------------------------
# 6. Ctrl-C
# --------------------------------------------------------------------------------------------
_INTERRUPT_SCRIPT = """
import signal, sys, time
import trackwheel as tw
# a process started in the background by a non-interactive shell (as CI may be) inherits SIGINT
# ignored, and Python then leaves it ignored: restore Ctrl-C's KeyboardInterrupt
signal.signal(signal.SIGINT, signal.default_int_handler)
scene = tw.Scene.kato2005()
kw = dict(integrator=sys.argv[1], n_elements=int(sys.argv[2]), dt=float(sys.argv[3]),
          x_start=0.25, x_end=4.75, progress=False)
tw.simulate(scene, tw.kmh(300), **dict(kw, x_end=0.2501))  # warm up (imports, caches)
print("running", flush=True)
tw.simulate(scene, tw.kmh(300), **kw)
print("finished", flush=True)
"""


@pytest.mark.parametrize("integrator,n_elements,dt", [
    ("explicit", 80, 1e-8),  # the slowest step: RK4 on the fine mesh (~0.3 ms per step)
    ("generalized_alpha", 20, 1e-7),  # the fastest: many steps between callbacks
])
def test_ctrl_c_interrupts_a_long_simulation_within_a_second(integrator, n_elements, dt):
    env = dict(os.environ, PYTHONPATH=str(Path(tw.__file__).resolve().parent.parent))
    with subprocess.Popen([sys.executable, "-c", _INTERRUPT_SCRIPT, integrator,
                           str(n_elements), str(dt)],
                          stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                          env=env) as proc:
        try:
            assert proc.stdout.readline().strip() == "running"
            time.sleep(0.5)  # well inside the run (minutes long)
            t0 = time.perf_counter()
            proc.send_signal(signal.SIGINT)
            out, err = proc.communicate(timeout=10)
            latency = time.perf_counter() - t0
        finally:
            if proc.poll() is None:
                proc.kill()
                proc.communicate()
    assert "finished" not in out
    assert proc.returncode != 0 and "KeyboardInterrupt" in err, err
    assert latency < 2.0, f"Ctrl-C took {latency:.2f} s"
