"""Issue 12: how much the absorbing end zones reflect, per 100 Hz band and per frequency.

1. Pulse (tests/test_long_track.py's method): a 0.3 ms Hann force pulse at mid-rail between two
   end zones 2.25 m away, on the paper's rail and supports (0.5 m bays, undamped); the reflected
   wave is the difference from the same pulse on a rail 80 m longer. Per 100 Hz band, the
   reflected over the incident energy of the 25 ms record, per end [dB], with the record cut off
   bluntly (as the test did before) and with its second half tapered (cosine, as the test does
   now), for plain ends and 10 m and 20 m zones.
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

import numpy as np
from _common import write_csv
from scipy.signal.windows import tukey
from scipy.sparse import coo_matrix
from scipy.sparse.linalg import splu, spsolve

import trackwheel as tw
from trackwheel.eigen import vertical_matrices

KATO = tw.Scene.kato2005()
H, DT, TAU, WINDOW = 0.0625, 1e-5, 3e-4, 0.025  # element [m], step [s], pulse [s], record [s]
GAP, EXTRA, BAY = 2.25, 40.0, 0.5  # source to zone, reference extension, support spacing [m]
EDGES = np.arange(100.0, 3001.0, 100.0)  # band edges [Hz]


def rail_scene(length, zone=None):
    rail = dataclasses.replace(KATO.rail, length=length, n_elements=round(length / H),
                               absorbing_ends=tw.AbsorbingEnds(zone) if zone else None)
    return dataclasses.replace(KATO, rail=rail, gravity=0.0, rail_gravity=False)


def pulse_response(scene, x_source, n_steps):
    """Displacement [m] at x_source under a unit Hann force pulse there (trapezoidal rule)."""
    M, C, K, dofs = vertical_matrices(scene)
    i = int(np.flatnonzero(dofs == 4 * round(x_source / H) + 1)[0])
    lu = splu((K + 2 / DT * C + 4 / DT**2 * M).tocsc())
    u, ud, udd = (np.zeros(M.shape[0]) for _ in range(3))
    out = np.zeros(n_steps + 1)
    for k in range(1, n_steps + 1):
        f = np.zeros_like(u)
        f[i] = 0.5 * (1 - np.cos(2 * np.pi * k * DT / TAU)) if k * DT < TAU else 0.0
        un = lu.solve(f + M @ (4 / DT**2 * u + 4 / DT * ud + udd) + C @ (2 / DT * u + ud))
        udn = 2 / DT * (un - u) - ud
        udd = 4 / DT**2 * (un - u) - 4 / DT * ud - udd
        u, ud = un, udn
        out[k] = u[i]
    return out


def band_energy(x):
    """Energy of x per band of EDGES (4x zero-padded spectrum) [m^2 s^2]."""
    f = np.fft.rfftfreq(4 * x.size, DT)
    e = np.abs(np.fft.rfft(x, 4 * x.size)) ** 2
    return np.array([e[(f >= a) & (f < b)].sum() for a, b in zip(EDGES[:-1], EDGES[1:])])


def pulses(zone):
    """(reference, zoned) records for zones of length ``zone`` (None: plain pinned ends)."""
    n, length = round(WINDOW / DT), 2 * ((zone or 10.0) + GAP)
    ref = pulse_response(rail_scene(length + 2 * EXTRA, zone or 10.0), EXTRA + length / 2, n)
    return ref, pulse_response(rail_scene(length, zone), length / 2, n)


def reflection_db(ref, zoned, taper):
    """Reflected over incident energy per band and end [dB] (the two ends reflect alike)."""
    w = tukey(2 * ref.size, 0.5)[ref.size:] if taper else 1.0
    return 10 * np.log10(band_energy(w * (zoned - ref)) / band_energy(w * ref) / 4)


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


def zone_reflection(freqs, zone, at_supports=False):
    """|R| of one end zone per frequency, and the decomposition's relative residual."""
    scene = rail_scene(2 * (zone + GAP), zone)
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


def main():
    rows = []
    ref10, z10 = pulses(10.0)
    ref20, z20 = pulses(20.0)
    _, plain = pulses(None)
    cols = {"reference energy [dB re max]": 10 * np.log10(band_energy(ref10) / band_energy(ref10).max()),
            "plain, blunt": reflection_db(ref10, plain, False),
            "plain, tapered": reflection_db(ref10, plain, True),
            "10 m, blunt": reflection_db(ref10, z10, False),
            "10 m, tapered": reflection_db(ref10, z10, True),
            "20 m, tapered": reflection_db(ref20, z20, True)}
    print("reflected / incident energy per 100 Hz band and end [dB]")
    print("band [Hz]   " + " | ".join(cols))
    for k, a in enumerate(EDGES[:-1]):
        vals = {name: round(float(c[k]), 1) for name, c in cols.items()}
        rows.append({"band_low_hz": a, "band_high_hz": a + 100} | vals)
        print(f"{a:4.0f}-{a + 100:4.0f}  " + "  ".join(f"{x:6.1f}" for x in vals.values()))
    write_csv("absorbing_reflection.csv", rows)

    freqs = np.array([1000, 1500, 1800, 1900, 1950, 2000, 2050, 2100, 2125, 2140, 2160, 2180,
                      2200, 2220, 2250, 2300, 2350, 2400, 2500, 2600, 2800, 3000.0])
    cases = {f"rail {z:.0f} m": zone_reflection(freqs, z) for z in (10.0, 20.0, 40.0, 80.0)}
    cases["supports 10 m"] = zone_reflection(freqs, 10.0, at_supports=True)
    print("\none zone's reflection |R| per frequency [dB] (Bloch decomposition; max residual "
          f"{max(c[:, 1].max() for c in cases.values()):.0e}); stop band: decay per bay > 1e-3")
    print("f [Hz]  " + "  ".join(f"{n:>13s}" for n in cases) + "  decay/bay")
    brows = []
    for k, f in enumerate(freqs):
        vals = {n: round(float(20 * np.log10(c[k, 0])), 1) for n, c in cases.items()}
        decay = cases["rail 10 m"][k, 2]
        brows.append({"f_hz": f} | vals | {"bloch_decay_per_bay": round(float(decay), 4)})
        print(f"{f:6.0f}  " + "  ".join(f"{x:13.1f}" for x in vals.values())
              + f"  {decay:9.4f}{'  stop band' if decay > 1e-3 else ''}")
    write_csv("absorbing_reflection_bloch.csv", brows)


if __name__ == "__main__":
    main()
