"""The time-loop room (cpp/time_loop.cpp, issue 8): output decimation bounds the kept samples,
the output limit refuses oversized requests before allocating, and Ctrl-C interrupts a long run
within about a second. Sweep-level robustness (worker-count independence, Ctrl-C keeping
finished cases) is tested with the sweeps. (Split from test_robustness.py by room.)
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

import trackwheel as tw
from trackwheel import _core

SIM = sys.modules["trackwheel.simulate"]
KATO = tw.Scene.kato2005()


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
