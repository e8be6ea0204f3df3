"""Two simulations in two threads against the same two run one after the other.

``simulate`` runs its whole time loop in C++ with the GIL released, so on a machine with two
free cores two threads should finish in about the time of one run (speed-up ~2). Each repeat
times the serial pair and the threaded pair back to back (same machine state); the script prints
the medians over the repeats and the 1-minute load average before and after (other jobs on a
shared machine take cores away: a load near or above the core count caps the speed-up), checks
that the threaded results equal the serial ones bit for bit, and writes ``threads.csv`` next to
itself. As a reference for what two threads can gain on this machine at all, the same is timed
for a task that is certainly GIL-free and CPU-bound (hashlib's SHA-256 of 64 MiB, which releases
the GIL): a speed-up below 2 there is the machine's (shared or throttled cores), not the kernel's.

    PYTHONPATH=python python benchmarks/threads.py [--repeats 7]
"""

from __future__ import annotations

import argparse
import dataclasses
import hashlib
import os
import statistics
import threading
import time
from pathlib import Path

from _common import write_csv

import trackwheel as tw

HERE = Path(__file__).resolve().parent
KATO = tw.Scene.kato2005()
SOFT = dataclasses.replace(KATO, supports=dataclasses.replace(KATO.supports, stiffness=40e6))
# a full passage at 100 km/h (16 200 steps of 1e-5 s, ~0.3 s on one core) over the paper's
# track and over softer supports: different work of the same length, so that two threads
# can at best halve the serial time
JOBS = [dict(scene=s, speed=tw.kmh(100), x_start=0.25, x_end=4.75, dt=1e-5, progress=False)
        for s in (KATO, SOFT)]


def run(job):
    job = dict(job)
    return tw.simulate(job.pop("scene"), job.pop("speed"), **job)


def serial():
    return [run(j) for j in JOBS]


def threaded():
    out = [None] * len(JOBS)

    def work(i):
        out[i] = run(JOBS[i])

    threads = [threading.Thread(target=work, args=(i,)) for i in range(len(JOBS))]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    return out


_DATA = b"x" * (64 << 20)


def _sha():
    for _ in range(4):
        hashlib.sha256(_DATA).digest()


def reference():
    """(serial, threaded) times of two GIL-free SHA-256 jobs."""
    ts, _ = timed(lambda: (_sha(), _sha()))
    threads = [threading.Thread(target=_sha) for _ in range(2)]
    t0 = time.perf_counter()
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    return ts, time.perf_counter() - t0


def timed(fn):
    t0 = time.perf_counter()
    res = fn()
    return time.perf_counter() - t0, res


def identical(a, b):
    names = ("t", "y_wheel", "y_contact", "normal_force", "tangential_force", "acc_contact")
    return all(getattr(a, n).tobytes() == getattr(b, n).tobytes() for n in names)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--repeats", type=int, default=7)
    args = ap.parse_args(argv)
    serial()  # warm up: imports, cached rail models
    load0 = os.getloadavg()[0]
    rows = []
    for k in range(args.repeats):
        ts, rs = timed(serial)
        tp, rp = timed(threaded)
        same = all(identical(a, b) for a, b in zip(rs, rp))
        hs, hp = reference()
        rows.append(dict(repeat=k, serial_s=round(ts, 4), threaded_s=round(tp, 4),
                         speedup=round(ts / tp, 3), identical=same,
                         sha256_speedup=round(hs / hp, 3)))
        print(f"repeat {k}: serial {ts:.3f} s, two threads {tp:.3f} s, "
              f"speed-up {ts / tp:.2f}, identical {same}; SHA-256 reference speed-up "
              f"{hs / hp:.2f}", flush=True)
    load1 = os.getloadavg()[0]
    ms = statistics.median(r["serial_s"] for r in rows)
    mp = statistics.median(r["threaded_s"] for r in rows)
    mr = statistics.median(r["speedup"] for r in rows)
    mh = statistics.median(r["sha256_speedup"] for r in rows)
    steps = sum(round((j["x_end"] - j["x_start"]) / j["speed"] / j["dt"]) for j in JOBS)
    print(f"\n{os.cpu_count()} cores, load average {load0:.2f} before, {load1:.2f} after")
    print(f"two runs ({steps} steps in all): serial {ms:.3f} s, two threads {mp:.3f} s "
          f"(medians of {args.repeats}); median speed-up {mr:.2f} (ideal 2.00; a GIL-free "
          f"SHA-256 reference reaches {mh:.2f} on this machine)")
    print("threaded results identical to serial:", all(r["identical"] for r in rows))
    write_csv("threads.csv", rows)


if __name__ == "__main__":
    main()
