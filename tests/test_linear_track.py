"""The linear-track fast path (cpp/linear_track.cpp, the "linear/..." fidelity levels).

Analytic and structural facts of the constant-matrix Euler-Bernoulli track: the Hermite beam's
exact nodal static deflection, modal superposition with every mode reproducing the full
coordinates, energy conservation of the trapezoidal rule (rho_inf = 1) for a linear system,
and the shared divergence reporting of the time-loop room.
"""

from __future__ import annotations

import dataclasses as dc

import numpy as np
import pytest

import trackwheel as tw

BARE = dc.replace(tw.Scene.kato2005(), supports=tw.Supports(positions=()), rail_gravity=False)


def test_moving_force_starts_from_the_exact_static_deflection():
    """A bare simply supported beam (no supports, no weight) under P at midspan deflects
    P L^3 / (48 EI) there; cubic Hermite elements are exact at the nodes for a point load at a
    node, so the linear path's static start agrees to round-off (1e-12)."""
    P, L, EI = BARE.static_load, BARE.rail.length, BARE.rail.bending_stiffness
    r = tw.simulate(BARE, 1.0, fidelity="linear/moving_force", x_start=L / 2, duration=1e-4,
                    dt=1e-5, progress=False)
    assert r.y_contact[0] == pytest.approx(-P * L**3 / (48 * EI), rel=1e-12)
    np.testing.assert_array_equal(r.normal_force, P)


def test_modal_with_every_mode_equals_the_full_coordinates():
    """q = Phi z with Phi square and M-orthonormal is a change of coordinates: the run matches
    the band solve to 1e-9 of each field's largest magnitude (the eigen solver's round-off,
    ~1e-13 on the modes, is amplified by the condition number of K, ~1e4, and 100 steps)."""
    scene = tw.Scene.kato2005()
    kw = {"fidelity": "linear/hertz", "x_end": 0.5, "dt": 1e-5, "progress": False}
    full = tw.simulate(scene, tw.kmh(200), **kw)
    n_y = 2 * (scene.rail.n_elements + 1) - 2
    modal = tw.simulate(scene, tw.kmh(200), n_modes=n_y, **kw)
    for f in ("y_contact", "y_wheel", "normal_force", "acc_contact"):
        a, b = getattr(modal, f), getattr(full, f)
        assert np.max(np.abs(a - b)) <= 1e-9 * np.max(np.abs(b)), f


def test_trapezoidal_rule_conserves_the_energy_of_the_linear_track(validation):
    """rho_inf = 1 is the trapezoidal rule, which conserves the energy of a linear undamped
    system exactly in exact arithmetic: a standing sprung wheel dropped 20 um onto the rail
    (vibration energy ~3 J) keeps its total energy over 2000 steps to round-off, 1e-12 of |E|
    (|E| ~ 4.7 kJ, dominated by the load's potential P Y_A; measured 3e-15), i.e. ~1e-9 of the
    vibration energy."""
    scene = tw.Scene.kato2005()
    r = tw.simulate(scene, 0.0, fidelity="linear/sprung", x_start=2.5, duration=0.02,
                    dt=1e-5, rho_inf=1.0, start="sudden", drop_height=2e-5, energy=True,
                    progress=False)
    E = r.energy
    assert np.max(0.5 * scene.wheel.mass * r.ydot_wheel**2) > 1.0  # it vibrates [J]
    assert np.max(np.abs(E - E[0])) < 1e-12 * np.max(np.abs(E))
    validation.record(
        "dynamics.linear_energy_conserved", level="time integration", kind="closed form",
        quantity="linear track, trapezoidal rule, sprung wheel dropped onto the rail, 2000 "
                 "steps: total energy drift",
        reference="energy conservation (exact for a linear undamped system)",
        measured=np.max(np.abs(E - E[0])) / np.max(np.abs(E)), tolerance=1e-12,
        metric="of |E|")


def test_divergence_names_the_time_position_and_cause():
    """The linear path reports divergence through the time-loop room like the full path."""
    scene = tw.Scene.kato2005()
    with pytest.raises(tw.DivergenceError) as info:
        tw.simulate(scene, tw.kmh(300), fidelity="linear/hertz", x_end=1.0, max_newton=1,
                    dt=1e-5, n_elements=20, start="sudden", drop_height=1e-4, progress=False)
    msg = str(info.value)
    assert "Newton did not converge in 1 iterations" in msg
    assert "X_A = " in msg and "Likely cause: the time step" in msg
    assert info.value.step >= 1 and info.value.time == pytest.approx(info.value.step * 1e-5)
