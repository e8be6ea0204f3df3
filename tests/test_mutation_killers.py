"""Facts the mutation check (scripts/mutants.py, issue 17) found untested: each test here kills
a kernel mutant that survived the rest of the fast suite, and asserts the documented behaviour
the mutant breaks.
"""

from __future__ import annotations

import re
import warnings

import pytest

import trackwheel as tw

SCENE = tw.Scene.kato2005()
CHECK_EVERY = 16  # the time loop checks the vibration energy every 16 steps (cpp/time_loop.cpp)


def _explicit(dt: float, n_steps: int, **kw):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", tw.StabilityWarning)
        return tw.simulate(SCENE, tw.kmh(200), integrator="explicit", dt=dt, n_elements=20,
                           duration=n_steps * dt, progress=False, **kw)


def test_energy_watchdog_stops_a_runaway_at_its_cap():
    """README: a run stops when its vibration energy exceeds 100 (F + M g) rho0 (4.71e5 J for
    the paper's scene). RK4 at 2 % above its stability limit has one growing mode, and its
    energy is what the run gains. The stop must name the energy runaway with that cap, and the
    last check that passed (16 steps before the stop) must have seen the mode's energy near the
    cap: below 4 cap, since the kinetic part the check sees is on average half the mode's energy
    (factor 2) at a phase that varies from check to check (another 2). A watchdog that fires
    late (a cap 1000x too high) fails this, as does one that never fires (the run then stops,
    if at all, on a non-finite state or a failed contact search)."""
    w = SCENE.wheel
    cap = 100.0 * (w.load + w.mass * SCENE.gravity) * w.radius
    dt = 1.02 * tw.stability_limit(SCENE, n_elements=20)
    with pytest.raises(tw.DivergenceError, match=r"\(energy runaway\)") as err:
        _explicit(dt, 3000, output_every=3000)
    m = re.search(r"vibration energy (\S+) J exceeds 100 \(F \+ M g\) rho0 = (\S+) J", str(err.value))
    assert m, str(err.value)
    assert float(m.group(2)) == pytest.approx(cap, rel=5e-3)  # printed to 3 digits
    assert float(m.group(1)) > cap
    n_stop = err.value.step
    assert n_stop % CHECK_EVERY == 0
    r = _explicit(dt, n_stop - 1, output_every=1, energy=True)  # up to the step before the stop
    gained = r.energy - r.energy[0]
    assert 0.0 < gained[n_stop - CHECK_EVERY] < 4.0 * cap, (gained[n_stop - CHECK_EVERY], cap)
