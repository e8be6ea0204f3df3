"""The track in the frequency domain: receptance and decay rate.

Docs: Model § Receptance and decay rate.

The linear track (the rail as an Euler-Bernoulli or, with ``Rail(beam="timoshenko")``, a
Timoshenko beam on the scene's supports with their damping, no wheel) in steady harmonic motion
under a unit force at x: ``Z(w) q = s(x)`` with the dynamic stiffness
``Z(w) = K + i w C - w^2 M`` (plus, for layered supports, the pad-sleeper-ballast correction),
solved in the C++ kernel by one pivoted complex band LU per frequency (O(n), GIL released).
The receptance ``alpha(x_r, x, f) = y(x_r) / F(x)`` [m/N] is complex; its phase is that of the
displacement relative to the force (``exp(+i w t)`` convention).

The track decay rate follows EN 15461:2008+A1:2010 (Railway applications - Noise emission -
Characterisation of the dynamic properties of track sections for pass by noise measurements):
from the transfer receptances A(x_n) at the standard's positions x_n = x_0 + n_k d (d the
support spacing, x_0 a mid-span),

    DR = 10 log10(e) / sum_n |A(x_n)|^2 / |A(x_0)|^2 dx_n  [dB/m],  10 log10(e) = 4.343,

dx_n the length of rail each position stands for (half-way to its neighbours). For a single
wave |A| ~ exp(-delta x) the sum is 1/(2 delta) and DR = 8.686 delta, the wave's decay in dB/m.
"""

from __future__ import annotations

import math

import numpy as np

from .. import _core
from ..base import validate as v
from ..base.limits import MAX_FREQUENCY
from ..scene import Scene
from . import kernel
from .defaults import frequency_mesh, mesh

__all__ = ["EN15461_SPANS", "ISO3095_BANDS", "ISO3095_VERTICAL_LIMIT", "band_decay_rates",
           "decay_rate", "decay_rate_limit", "decay_rate_positions", "en15461_decay",
           "iso3095_band_edges", "receptance", "receptance_points"]

#: The EN 15461 measurement positions as distances from the excitation point (the middle of a
#: sleeper bay), in support spacings (EN 15461:2008+A1:2010, 6.7 and Figure 2): every quarter
#: bay to 2.5, every half bay to 4, every bay to 8, then 10, 12, 16, 20, 24, 30, 36, 42, 48, 54
#: and 66; 29 points (the grid as reproduced from BS EN 15461:2008+A1:2010 in the phonometry
#: package, J. M. Requena Plens, environment/sources/track_decay.py).
EN15461_SPANS = (0.0, 0.25, 0.5, 0.75, 1.0, 1.25, 1.5, 1.75, 2.0, 2.25, 2.5, 3.0, 3.5, 4.0, 5.0,
                 6.0, 7.0, 8.0, 10.0, 12.0, 16.0, 20.0, 24.0, 30.0, 36.0, 42.0, 48.0, 54.0, 66.0)

#: One-third-octave band centre frequencies [Hz] of the ISO 3095:2013 decay-rate limit (no
#: limit below 250 Hz).
ISO3095_BANDS = (250.0, 315.0, 400.0, 500.0, 630.0, 800.0, 1000.0, 1250.0, 1600.0, 2000.0,
                 2500.0, 3150.0, 4000.0, 5000.0)
#: ISO 3095:2013 (6.2.6, Figure 3, the table beside the curves) lower limit of the vertical track
#: decay rate [dB/m] in ``ISO3095_BANDS``: a test track for pass-by noise must decay at least
#: this fast. Values as reproduced in the phonometry package (J. M. Requena Plens,
#: environment/sources/rolling_stock_noise.py, REFERENCE_TRACK_DECAY_LIMITS_DB_PER_M).
ISO3095_VERTICAL_LIMIT = (2.0, 2.0, 6.0, 6.0, 6.0, 2.19, 0.8, 0.8, 0.8, 0.8, 0.8, 0.8, 0.8, 0.8)


def _check_scene(scene) -> Scene:
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a trackwheel.Scene, got {type(scene).__name__}")
    return scene


def _freqs(freqs) -> np.ndarray:
    f = np.atleast_1d(np.asarray(freqs, dtype=float))
    if f.ndim != 1 or f.size == 0:
        raise ValueError("freqs must be a non-empty 1-D sequence of frequencies [Hz]")
    bad = ~np.isfinite(f) | (f < 0) | (f > MAX_FREQUENCY)
    if bad.any():
        raise ValueError(f"freqs = {f[bad][0]:.6g} Hz is outside the allowed range "
                         f"[0, {MAX_FREQUENCY:g}] Hz (the rail's beam models hold to a few kHz)")
    return f


def receptance(scene: Scene, x, freqs, x_response=None, *,
               n_elements: int | None = None) -> np.ndarray:
    """Receptance of the track [m/N]: rail displacement at ``x_response`` [m] per unit vertical
    force at ``x`` [m], at each of ``freqs`` [Hz] in [0, ``MAX_FREQUENCY``] (100 kHz).

    ``x`` (the excitation) and ``x_response`` are each a number or a 1-D sequence of positions
    in [0, L]; ``x_response=None`` is the point receptance at each ``x``. The result's axes
    are the frequencies, then the responses if ``x_response`` is a sequence, then the
    excitations if ``x`` is a sequence:

    ==================  ==================  ==============================
    ``x``               ``x_response``      shape
    ==================  ==================  ==============================
    number              None or number      ``(n_freq,)``
    number              sequence            ``(n_freq, n_response)``
    sequence            None                ``(n_freq, n_x)`` (point receptances)
    sequence            number              ``(n_freq, n_x)``
    sequence            sequence            ``(n_freq, n_response, n_x)``
    ==================  ==================  ==============================

    One factorisation of the dynamic stiffness per frequency serves every excitation. The
    track is the linear track of the scene's beam theory with its support damping, meshed with
    ``n_elements`` (default :func:`trackwheel.run.defaults.frequency_mesh` at the highest
    frequency: whole elements per support bay, enough per bending wavelength to put the track's
    resonances within 0.1 % of a refined mesh). At f = 0 it is the static flexibility.

    >>> a = receptance(Scene.kato2005(), 2.25, [0.0, 500.0])
    >>> a.shape
    (2,)
    """
    scene = _check_scene(scene)
    L = scene.rail.length
    f = _freqs(freqs)
    x_many = np.ndim(x) != 0
    xe = v.positions("x", x, 0.0, L) if x_many else np.array(
        [v.number("x", x, low=0.0, high=L, unit="m")])
    r_many = x_response is not None and np.ndim(x_response) != 0
    if x_response is None:
        xr = xe
    elif r_many:
        xr = v.positions("x_response", x_response, 0.0, L)
    else:
        xr = np.array([v.number("x_response", x_response, low=0.0, high=L, unit="m")])
    ne = frequency_mesh(scene, float(f.max())) if n_elements is None else mesh(scene, n_elements)
    model = kernel.rail_model(scene, ne)
    a = np.asarray(_core.receptance(model, kernel.beam_params(scene), xe.tolist(), xr.tolist(),
                                    f.tolist())).reshape(f.size, xe.size, xr.size)
    if x_response is None:  # the point receptances: the diagonal
        a = a[:, np.arange(xe.size), np.arange(xe.size)]
        return a if x_many else a[:, 0]
    a = np.transpose(a, (0, 2, 1))  # (n_freq, n_response, n_x)
    if not r_many:
        a = a[:, 0]
    return a if x_many else a[..., 0]


def receptance_points(scene: Scene) -> dict[str, float]:
    """The excitation points [m] near the rail's middle where a track's receptance is usually
    shown: ``"mid-span"`` (the middle of the bay nearest the rail's middle) and ``"above a
    support"`` (the support nearest the middle; left out on a rail without supports)."""
    pos = np.asarray(_check_scene(scene).support_positions)
    if pos.size == 0:
        return {"mid-span": 0.5 * scene.rail.length}
    j = int(np.argmin(np.abs(pos - 0.5 * scene.rail.length)))
    nxt = pos[j + 1] if j + 1 < pos.size else scene.rail.length
    return {"mid-span": 0.5 * (pos[j] + nxt), "above a support": float(pos[j])}


def decay_rate_positions(scene: Scene, x0: float | None = None) -> np.ndarray:
    """The EN 15461 response positions x_0 + n_k d [m] (``EN15461_SPANS``, d the support
    spacing). ``x0`` [m], the excitation point, at least d / 4 from the rigid end at 0,
    defaults to the mid-span that centres the 66-spacing line on the rail. Raises ValueError if
    the line does not fit on the rail."""
    scene = _check_scene(scene)
    d, L = scene.supports.spacing, scene.rail.length
    span = EN15461_SPANS[-1] * d
    given = x0 is not None
    if x0 is None:
        x0 = (max(math.floor((L - span) / 2.0 / d), 0) + 0.5) * d
    if span > L or (not given and x0 + span > L):
        # no (default) excitation point fits: say what the rail needs, not an empty range
        raise ValueError(
            f"the EN 15461 positions reach {EN15461_SPANS[-1]:g} support spacings "
            f"({span:.4g} m) beyond the excitation point at mid-span; the rail (Rail.length) "
            f"is {L:.4g} m: allowed a rail of at least {span + 0.5 * d:.4g} m (plus room for "
            "its end reflections)")
    # at least a quarter bay from the rigid end support at 0, where the rail does not move (no
    # response there to divide by)
    x0 = v.number("x0", x0, low=0.25 * d, high=L, unit="m")
    if x0 + span > L:
        raise ValueError(
            f"x0 = {x0:.4g} m puts the last EN 15461 position ({EN15461_SPANS[-1]:g} support "
            f"spacings, {span:.4g} m, beyond it) past the rail end at {L:.4g} m; allowed "
            f"range [{0.25 * d:.4g}, {L - span:.4g}] m")
    return x0 + d * np.asarray(EN15461_SPANS)


def en15461_decay(x: np.ndarray, a: np.ndarray) -> np.ndarray:
    """DR [dB/m] of transfer receptances ``a`` (n_freq, n_pos) at positions ``x`` (n_pos,) [m],
    x[0] the excitation point: 4.343 / sum_n |a_n / a_0|^2 dx_n, dx_n by EN 15461 A.2 (from
    half-way to the previous position to half-way to the next; the first from x_0, the last
    symmetric about itself)."""
    mid = 0.5 * (x[1:] + x[:-1])
    lower = np.concatenate(([x[0]], mid))
    upper = np.concatenate((mid, [x[-1] + 0.5 * (x[-1] - x[-2])]))
    dx = upper - lower
    ratio = np.abs(a) ** 2 / np.abs(a[:, :1]) ** 2
    return 10.0 * math.log10(math.e) / (ratio @ dx)


def decay_rate(scene: Scene, freqs, *, x0: float | None = None,
               n_elements: int | None = None) -> np.ndarray:
    """Vertical track decay rate [dB/m] at each of ``freqs`` [Hz] by the EN 15461 method
    (module docstring) from the transfer receptances of :func:`receptance` at
    :func:`decay_rate_positions` (d = ``Supports.spacing``), meshed with ``n_elements``
    (default :func:`trackwheel.run.defaults.frequency_mesh` at the highest frequency). The rail must be longer than 66
    support spacings, and its ends far enough (or damped enough) that their reflections do not
    reach back to the positions; shape ``(n_freq,)``. As in the standard (Formula 2, clause
    7), a rate below 2 x 4.343 / x_max (x_max = 66 d, 0.22 dB/m for d = 0.6 m) is only an
    upper bound of the true one: the grid is too short to see the decay."""
    x = decay_rate_positions(scene, x0)
    a = receptance(scene, float(x[0]), freqs, x, n_elements=n_elements)
    return en15461_decay(x, a)


def decay_rate_limit(freqs) -> np.ndarray:
    """ISO 3095:2013 lower limit of the vertical decay rate [dB/m] at ``freqs`` [Hz]: the
    one-third-octave band value of the band holding each frequency (:func:`iso3095_band_edges`);
    NaN outside the 250 Hz..5 kHz bands."""
    f = _freqs(freqs)
    edges = iso3095_band_edges()
    i = np.searchsorted(edges, f, side="right") - 1
    inside = (i >= 0) & (i < len(ISO3095_BANDS))
    out = np.full(f.shape, np.nan)
    out[inside] = np.asarray(ISO3095_VERTICAL_LIMIT)[i[inside]]
    return out


def iso3095_band_edges() -> np.ndarray:
    """Edges [Hz] of the ``ISO3095_BANDS`` one-third-octave bands: the exact base-2 centres
    1000 * 2^(n/3) times 2^(-+1/6), so that neighbouring bands share an edge."""
    n = np.round(3.0 * np.log2(np.asarray(ISO3095_BANDS) / 1000.0))
    return 1000.0 * 2.0 ** (np.append(n - 0.5, n[-1] + 0.5) / 3.0)


def band_decay_rates(scene: Scene, per_band: int = 8, n_elements: int | None = None
                     ) -> np.ndarray:
    """Decay rate [dB/m] per ``ISO3095_BANDS`` one-third-octave band: the EN 15461 sum of the
    band averages of |A(x_n)|^2 over ``per_band`` log-spaced frequencies inside each band (the
    standard filters the measured transfer functions in bands, not at the centre frequency;
    what ``trackwheel decay-rate`` prints). ``n_elements`` defaults to
    :func:`trackwheel.run.defaults.frequency_mesh` at the highest band's upper edge, the same
    mesh for every band."""
    x = decay_rate_positions(scene)
    edges = iso3095_band_edges()
    if n_elements is None:
        n_elements = frequency_mesh(scene, float(edges[-1]))
    out = np.empty(edges.size - 1)
    for k, (lo, hi) in enumerate(zip(edges[:-1], edges[1:])):
        f = np.geomspace(lo, hi, per_band + 2)[1:-1]
        a = receptance(scene, float(x[0]), f, x, n_elements=n_elements)
        power = np.mean(np.abs(a) ** 2, axis=0)
        out[k] = en15461_decay(x, np.sqrt(power)[None, :])[0]
    return out
