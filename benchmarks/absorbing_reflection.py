"""Issue 12: how much the absorbing end zones reflect, per 100 Hz band and per frequency.

1. Pulse (tests/test_long_track.py's method): a 0.3 ms Hann force pulse 2.25 m from one end
   zone and 10 m from the other, on the paper's rail and supports (0.5 m bays, undamped),
   recorded 1 m from the source towards the near zone; the reflected wave is the difference from
   the same pulse on a rail 40 m longer on the near side, the incident wave that rail's record.
   Per 100 Hz band, reflected over incident energy of the 25 ms record [dB], the record's second
   half tapered (cosine). Besides, the former test's measurement ("before": source midway between
   two zones, recorded at the source, the record cut off bluntly, a quarter of the energy ratio
   per end) on the former default zones (30 dB design, ABSORBING_ATTENUATION = 30).
2. Bloch waves: the zone's own reflection coefficient, frequency by frequency. The steady-state
   response to a harmonic force (the kernel's M, C, K) at four consecutive supports between source
   and zone is split into the four Bloch waves of one undamped bay (textbook Hermite beam
   elements, 8 per bay, the support at the bay's left node); R = |left-going / right-going| of
   the propagating pair. Rail dashpots (the model's zones) of 10-80 m, and the same damping put
   at the supports instead (in parallel to the springs).

Writes benchmarks/absorbing_reflection.csv (1) and absorbing_reflection_bloch.csv (2).

    python benchmarks/absorbing_reflection.py
"""

from __future__ import annotations

import dataclasses
import sys

import numpy as np
from _common import HERE, write_csv
from scipy.signal.windows import tukey
from scipy.sparse import coo_matrix
from scipy.sparse.linalg import spsolve

import trackwheel as tw
from trackwheel.eigen import vertical_matrices
from trackwheel.scene import ABSORBING_ATTENUATION

# the pulse measurement of the test, with its element, step, pulse, record and distances
sys.path.insert(0, str(HERE.parent / "tests"))
from test_long_track import (  # noqa: E402
    DT, EXTRA, FAR, GAP, H, RECEIVER, WINDOW, pulse_response)

KATO = tw.Scene.kato2005()
BAY = 0.5  # support spacing [m]
EDGES = np.arange(100.0, 3001.0, 100.0)  # band edges [Hz]


def rail_scene(length, zone=None, design=ABSORBING_ATTENUATION):
    """The paper's rail and supports, ``length`` long, with end zones designed for ``design`` dB
    (c_max scales with it: Rail.absorbing_damping)."""
    rail = dataclasses.replace(KATO.rail, length=length, n_elements=round(length / H),
                               absorbing_ends=tw.AbsorbingEnds(zone) if zone else None)
    if zone:
        c = rail.absorbing_damping * design / ABSORBING_ATTENUATION
        rail = dataclasses.replace(rail, absorbing_ends=tw.AbsorbingEnds(zone, c))
    return dataclasses.replace(KATO, rail=rail, gravity=0.0, rail_gravity=False)


def band_energy(x):
    """Energy of x per band of EDGES (4x zero-padded spectrum) [m^2 s^2]."""
    f = np.fft.rfftfreq(4 * x.size, DT)
    e = np.abs(np.fft.rfft(x, 4 * x.size)) ** 2
    return np.array([e[(f >= a) & (f < b)].sum() for a, b in zip(EDGES[:-1], EDGES[1:])])


def one_zone(zone, design=ABSORBING_ATTENUATION, ends=True):
    """(reference, response) records of the test's one-near-zone measurement."""
    n, length, x = round(WINDOW / DT), 2 * zone + GAP + FAR, zone + GAP
    ref = pulse_response(rail_scene(length + EXTRA, zone, design), EXTRA + x, EXTRA + x - RECEIVER,
                         n)
    return ref, pulse_response(rail_scene(length, zone if ends else None, design), x,
                               x - RECEIVER, n)


def former_measurement(zone, design):
    """The former test's: two zones GAP from the source, recorded there, a blunt record, per
    end a quarter of the energy ratio [dB]."""
    n, length = round(WINDOW / DT), 2 * (zone + GAP)
    ref = pulse_response(rail_scene(length + 2 * EXTRA, zone, design), EXTRA + length / 2,
                         EXTRA + length / 2, n)
    zoned = pulse_response(rail_scene(length, zone, design), length / 2, length / 2, n)
    return 10 * np.log10(band_energy(zoned - ref) / band_energy(ref) / 4)


def reflection_db(ref, response):
    """Reflected over incident energy per band [dB], the records' second half tapered."""
    w = tukey(2 * ref.size, 0.5)[ref.size:]
    return 10 * np.log10(band_energy(w * (response - ref)) / band_energy(w * ref))


# ------------------------------------------------------------------------------- Bloch waves
def bay_matrices(n=8):
    """K, M of one bay of the paper's rail (Hermite elements, w and w' per node), the support
    spring at its left node."""
    r = KATO.rail
    ei, m, le = r.bending_stiffness, r.mass_per_length, BAY / n
    ke = ei / le**3 * np.array([[12, 6 * le, -12, 6 * le], [6 * le, 4 * le**2, -6 * le, 2 * le**2],
                                [-12, -6 * le, 12, -6 * le], [6 * le, 2 * le**2, -6 * le, 4 * le**2]])
    me = m * le / 420 * np.array([[156, 22 * le, 54, -13 * le], [22 * le, 4 * le**2, 13 * le, -3 * le**2],
                                  [54, 13 * le, 156, -22 * le], [-13 * le, -3 * le**2, -22 * le, 4 * le**2]])
    K, M = np.zeros((2 * n + 2, 2 * n + 2)), np.zeros((2 * n + 2, 2 * n + 2))
    for e in range(n):
        K[2 * e:2 * e + 4, 2 * e:2 * e + 4] += ke
        M[2 * e:2 * e + 4, 2 * e:2 * e + 4] += me
    K[0, 0] += KATO.supports.stiffness
    return K, M


def bloch_waves(omega, K, M, loss=1e-7):
    """Multipliers lambda per bay and displacement parts (w, w') of the 4 Bloch waves; a
    ``loss`` factor makes the right-going waves the ones with |lambda| < 1."""
    D = K - omega**2 * (1 - 1j * loss) * M
    b, i = [0, 1, len(D) - 2, len(D) - 1], list(range(2, len(D) - 2))
    Dc = D[np.ix_(b, b)] - D[np.ix_(b, i)] @ np.linalg.solve(D[np.ix_(i, i)], D[np.ix_(i, b)])
    inv = np.linalg.inv(Dc[:2, 2:])
    # state (u, -f) at a bay's left node -> the next bay's left node
    T = np.block([[-inv @ Dc[:2, :2], -inv],
                  [Dc[2:, :2] - Dc[2:, 2:] @ inv @ Dc[:2, :2], -Dc[2:, 2:] @ inv]])
    lam, V = np.linalg.eig(T)
    return lam, V[:2]


def support_dampers(scene, dofs, zone, cmax):
    """The zone's c(d) * BAY as dampers at the supports, instead of the rail's dashpot."""
    L = scene.rail.length
    xs = [x for x in np.arange(BAY, L - BAY / 2, BAY) if min(x, L - x) < zone]
    rows = [int(np.flatnonzero(dofs == 4 * round(x / H) + 1)[0]) for x in xs]
    c = [cmax * (1 - min(x, L - x) / zone) ** 2 * BAY for x in xs]
    return coo_matrix((c, (rows, rows)), shape=(dofs.size, dofs.size)).tocsr()


def zone_reflection(freqs, zone, at_supports=False, design=ABSORBING_ATTENUATION):
    """|R| of one end zone per frequency, the decomposition's relative residual, and the
    least-decaying right-going wave's decay per bay [Np] (0 where a wave travels)."""
    scene = rail_scene(2 * (zone + GAP), zone, design)
    cmax = scene.rail.absorbing_damping
    if at_supports:
        scene = rail_scene(scene.rail.length)
    M, C, K, dofs = vertical_matrices(scene)
    if at_supports:
        C = C + support_dampers(scene, dofs, zone, cmax)
    L = scene.rail.length
    src = int(np.flatnonzero(dofs == 4 * round(L / 2 / H) + 1)[0])
    nodes = [round((L / 2 + BAY / 2 + j * BAY) / H) for j in range(4)]  # supports past the source
    rows = [int(np.flatnonzero(dofs == 4 * k + a)[0]) for k in nodes for a in (1, 3)]
    Kb, Mb = bay_matrices()
    out = []
    for f in freqs:
        w = 2 * np.pi * f
        F = np.zeros(M.shape[0], complex)
        F[src] = 1.0
        u = spsolve((K + 1j * w * C - w * w * M).tocsc(), F)[rows]
        lam, phi = bloch_waves(w, Kb, Mb)
        A = np.vstack([phi * lam**j for j in range(4)])
        a = np.linalg.lstsq(A, u, rcond=None)[0]
        right = np.abs(lam) < 1
        ir = np.flatnonzero(right)[np.argmax(np.abs(lam[right]))]
        il = np.flatnonzero(~right)[np.argmin(np.abs(lam[~right]))]
        out.append((abs(a[il] / a[ir]), np.linalg.norm(A @ a - u) / np.linalg.norm(u),
                    abs(np.log(abs(lam[ir])))))
    return np.array(out)


def pulse_table():
    ref10, z10 = one_zone(10.0)
    ref30, z30 = one_zone(10.0, design=30.0)
    ref20, z20 = one_zone(20.0)
    plain = one_zone(10.0, ends=False)[1]
    e = band_energy(ref10)
    cols = {"incident [dB re max]": 10 * np.log10(e / e.max()),
            "before: 10 m 30 dB, former measure": former_measurement(10.0, 30.0),
            "10 m 30 dB": reflection_db(ref30, z30),
            f"after: 10 m {ABSORBING_ATTENUATION:.0f} dB": reflection_db(ref10, z10),
            f"20 m {ABSORBING_ATTENUATION:.0f} dB": reflection_db(ref20, z20),
            "plain ends": reflection_db(ref10, plain)}
    print("reflected / incident energy per 100 Hz band [dB] (zone length, design attenuation)")
    print("band [Hz]  " + " | ".join(cols))
    rows = []
    for k, a in enumerate(EDGES[:-1]):
        vals = {name: round(float(c[k]), 1) for name, c in cols.items()}
        rows.append({"band_low_hz": a, "band_high_hz": a + 100} | vals)
        print(f"{a:4.0f}-{a + 100:4.0f}  " + "  ".join(f"{x:6.1f}" for x in vals.values()))
    write_csv("absorbing_reflection.csv", rows)


def bloch_table():
    freqs = np.array([1000, 1500, 1800, 1900, 1950, 2000, 2050, 2100, 2125, 2140, 2160, 2180,
                      2200, 2220, 2250, 2300, 2350, 2400, 2500, 2600, 2800, 3000.0])
    cases = {"rail 10 m 30 dB": zone_reflection(freqs, 10.0, design=30.0)}
    cases |= {f"rail {z:.0f} m": zone_reflection(freqs, z) for z in (10.0, 20.0, 40.0, 80.0)}
    cases["supports 10 m"] = zone_reflection(freqs, 10.0, at_supports=True)
    print(f"\none zone's reflection |R| per frequency [dB], design {ABSORBING_ATTENUATION:.0f} dB "
          "unless said (Bloch decomposition; largest residual "
          f"{max(c[:, 1].max() for c in cases.values()):.0e})")
    print("f [Hz]  " + "  ".join(f"{n:>15s}" for n in cases) + "  decay/bay [Np]")
    rows = []
    for k, f in enumerate(freqs):
        vals = {n: round(float(20 * np.log10(c[k, 0])), 1) for n, c in cases.items()}
        decay = cases["rail 10 m"][k, 2]
        rows.append({"f_hz": f} | vals | {"bloch_decay_per_bay": round(float(decay), 4)})
        print(f"{f:6.0f}  " + "  ".join(f"{x:15.1f}" for x in vals.values())
              + f"  {decay:9.4f}{'  stop band' if decay > 1e-3 else ''}")
    write_csv("absorbing_reflection_bloch.csv", rows)


if __name__ == "__main__":
    pulse_table()
    bloch_table()
