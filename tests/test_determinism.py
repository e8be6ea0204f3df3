"""Determinism and threads (issue 8): the same call twice gives bit-identical arrays; two threads
simulating at once give the serial results bit for bit, and ``simulate`` releases the GIL.
(Split from test_robustness.py by room.)
"""

from __future__ import annotations

import dataclasses as dc
import threading
import time

import numpy as np
import pytest

import trackwheel as tw
from trackwheel.run import kernel as _kernel

KATO = tw.Scene.kato2005()


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
    "generalized_alpha": {"integrator": "generalized_alpha", "x_start": 0.4, "x_end": 0.62,
                          "dt": 1e-5},
    "explicit": {"integrator": "explicit", "x_start": 0.45, "x_end": 0.52, "dt": 5e-7},
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
        except BaseException as exc:  # noqa: BLE001 -- re-raised in the main thread
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
