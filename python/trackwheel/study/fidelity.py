"""Model no more than a scene needs: fidelity levels side by side.

:func:`adequacy` runs each level of :data:`trackwheel.simulate.FIDELITY_LEVELS` on the same scene
and speeds -- the time-domain levels through ``simulate``, the periodic level through
``periodic_response`` -- compares its headline outputs with the full model (nonlinear ANCF
rail, the scene's contact law, contact-point search with obliquity, rolling constraint with
slip) and recommends the cheapest level whose outputs stay within ``tol`` of it at every speed.
"""

from __future__ import annotations

import dataclasses
import math
import time
from typing import TYPE_CHECKING

import numpy as np

from ..base import validate as v
from .analysis import analyse
from .columns import ADEQUACY_COLUMNS, HEADLINE, SPEED, SPEED_KMH
from ..run.defaults import MAX_SPEED, default_settings, pinned_pinned_frequencies
from ..excitation import contact_half_width, filter_attenuation, filter_matters
from ..scene import Scene, Vehicle
from ..run.periodic import PeriodicResponse, periodic_response
from ..run.simulate import FIDELITY_LEVELS, PERIODIC_LEVEL, TIME_DOMAIN_LEVELS, simulate

if TYPE_CHECKING:  # pandas is imported when a table is built: keeps `import trackwheel` light
    import pandas as pd

__all__ = ["VEHICLE_LEVELS", "adequacy", "pinned_pinned_frequencies", "recommend",
           "shear_judgement", "vehicle_adequacy", "vehicle_levels"]

_SPEED, _SPEED_KMH = SPEED.label, SPEED_KMH.label
_HEAD = {q.name: q.label for q in HEADLINE}  # amplitude -> amplitude_m, ...
_WALL, _LOST = ({q.name: q.label for q in ADEQUACY_COLUMNS}[n] for n in ("wall_time",
                                                                         "lost_contact"))


def adequacy(scene: Scene, speeds=(100 / 3.6, 300 / 3.6), *, tol: float = 0.005,
             levels=FIDELITY_LEVELS, reference: str = "full", n_modes: int | None = None,
             shear: bool = True, steady: bool = False, **simulate_kwargs) -> pd.DataFrame:
    """Run the fidelity ``levels`` side by side at each of ``speeds`` [m/s].

    Returns a DataFrame, one row per (speed, level), with the headline outputs ``amplitude_m``
    (max |d|, docs: Model § Outputs), ``main_frequency_hz`` and ``peak_contact_force_N``, their
    relative differences from the ``reference`` level (``d_amplitude``, ``d_main_frequency``,
    ``d_peak_contact_force``), ``wall_time_s``, ``adequate`` (all three differences <= tol)
    and ``error`` (message if the level failed): the columns of
    :data:`trackwheel.study.columns.ADEQUACY_COLUMNS`. ``df.attrs["recommended"]`` is the least
    detailed level adequate at every speed (:func:`recommend`); ``df.attrs["tol"]`` the tolerance.
    ``n_modes`` applies to the linear levels (None: all coordinates). All levels run on the same
    mesh and time step: ``simulate_kwargs``' ``dt``/``n_elements``, or else
    :func:`trackwheel.default_settings` (the derived defaults of the full model).

    The main frequency is compared relative to itself; the frequency resolution of a run is
    1/T (T the run's duration), so frequency differences below it are not meaningful.

    The periodic level ("periodic/linear", :func:`trackwheel.periodic_response`) is the steady
    state of the linear levels' model on the infinite periodic track: its row holds the steady
    state's max |d|, the frequency of d's largest line and the largest contact force over all
    phases, and its ``wall_time_s`` that of the periodic call. Against a passage of the time
    domain (default) it is adequate where the passage is its steady state: the start-up and the
    rail's ends do not reach the headline outputs. With ``steady=True`` every time-domain run is
    measured over its steady part only (``analyse(..., steady=True)``: from the bay where its
    contact force has settled, :func:`trackwheel.steady_state`), which compares the periodic
    level like for like; a run that never settles (an irregularity that is not bay-periodic, a
    short rail) is then an error row. Where the periodic level does not apply (contact loss, a
    non-periodic or undamped track, several wheels, a profile that is not a sum of sines, the
    Hertz law beyond its linearisation) its row holds the reason in ``error``. The reference
    must be a time-domain level.

    With a rail profile, ``df.attrs["contact_filter"]`` says whether the contact filter
    (``Contact(patch_filter=True)``, the profile averaged over the static Hertz patch of
    half-length a) matters for it: ``{"half_width": a [m], "shortest_wavelength": [m],
    "attenuation_db": [dB], "matters": bool}``, where it matters when the patch average takes
    more than 1 dB off the profile's shortest wavelength
    (:func:`trackwheel.irregularity.filter_matters`).

    The levels run on the scene's beam theory (``Rail(beam="timoshenko")``: the shear-deformable
    ANCF rail on the full and "ancf/..." levels, the linear Timoshenko beam on the "linear/..."
    ones). With ``shear`` (default),
    ``df.attrs["shear"]`` says whether the rail's shear deformation matters for the scene
    (:func:`shear_judgement`): the pinned-pinned frequencies of both beam theories and the
    largest relative differences of the headline outputs between the "linear/hertz" level run
    with the Timoshenko and with the Euler-Bernoulli rail at ``speeds``; it matters where one
    exceeds ``tol`` (typically when the wheel/rail force has content near the pinned-pinned
    frequency).
    """
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a trackwheel.Scene, got {type(scene).__name__}")
    speeds = v.positions("speeds", speeds, 0.0, MAX_SPEED, unit="m/s")
    if np.any(speeds <= 0):
        raise ValueError("speeds must be > 0 m/s")
    tol = v.number("tol", tol, low=0.0, low_open=True)
    levels = tuple(levels)
    if not levels:
        raise ValueError("levels must name at least one of " + ", ".join(FIDELITY_LEVELS))
    for lv in levels:
        v.choice("levels", lv, set(FIDELITY_LEVELS))
    v.choice("reference", reference, set(TIME_DOMAIN_LEVELS))
    v.boolean("shear", shear)
    v.boolean("steady", steady)
    run_levels = (reference,) + tuple(lv for lv in levels if lv != reference)
    # every level on the same mesh and step: the derived defaults unless given
    defaults = default_settings(scene)
    if "dt" not in simulate_kwargs and "n_elements" not in simulate_kwargs:
        simulate_kwargs = dict(simulate_kwargs, **defaults)

    rows = []
    for speed in speeds:
        ref = None
        for lv in run_levels:
            kw = dict(simulate_kwargs)
            if lv.startswith("linear/") and n_modes is not None:
                kw["n_modes"] = n_modes
            if lv == PERIODIC_LEVEL:
                row = _row(speed, "level", lv, lambda: periodic_response(scene, float(speed)))
            else:
                row = _row(speed, "level", lv, lambda: simulate(
                    scene, float(speed), fidelity=lv, **kw), steady=steady)
            ref = row if lv == reference else ref
            rows.append(_with_differences(row, ref))
    df = _table(rows, tol, "level")
    df.attrs["tol"] = tol
    df.attrs["reference"] = reference
    df.attrs["recommended"] = recommend(df)
    if scene.irregularity is not None and scene.irregularity.parts:
        df.attrs["contact_filter"] = contact_filter_judgement(scene)
    if scene.vehicle is not None and scene.vehicle.n_bodies:
        veh = vehicle_adequacy(scene, speeds, tol=tol, fidelity=reference, **simulate_kwargs)
        df.attrs["vehicle"] = veh
        df.attrs["vehicle_recommended"] = veh.attrs["recommended"]
    if shear:
        df.attrs["shear"] = shear_judgement(scene, speeds, tol=tol, **simulate_kwargs)
    return df


def _headline(r, steady: bool = False) -> dict:
    """Headline outputs of a run by column; with several wheels those of the worst wheel
    (largest amplitude max|d|; the peak force is the largest of any wheel); ``steady``: over
    the run's steady part. A periodic response: those of its steady state."""
    if isinstance(r, PeriodicResponse):
        return {_HEAD["amplitude"]: r.amplitude, _HEAD["main_frequency"]: r.main_frequency,
                _HEAD["peak_contact_force"]: r.max_force, _LOST: False}
    analyses = [analyse(r, wheel=i, steady=steady) for i in range(r.n_wheels)]
    worst = max(analyses, key=lambda a: a.amplitude)
    return {_HEAD["amplitude"]: worst.amplitude, _HEAD["main_frequency"]: worst.main_frequency,
            _HEAD["peak_contact_force"]: max(a.max_contact_force for a in analyses),
            _LOST: any(a.lost_contact for a in analyses)}


def _row(speed: float, key: str, value: str, run, steady: bool = False) -> dict:
    """One row of a fidelity table: the speed [m/s], ``key`` = ``value`` (the level), the
    headline outputs of ``run()`` (a Result, or a PeriodicResponse) and its wall time, or NaN
    and the error if it failed."""
    row = {_SPEED: float(speed), _SPEED_KMH: float(speed) * 3.6, key: value, "error": ""}
    try:
        t0 = time.perf_counter()
        r = run()
        wall = time.perf_counter() - t0
        row.update(_headline(r, steady))
        row[_WALL] = getattr(r, "wall_time", wall)
    except (ValueError, RuntimeError) as exc:  # DivergenceError is a RuntimeError
        row.update({c: np.nan for c in _HEAD.values()})
        row.update({_LOST: False, _WALL: np.nan, "error": str(exc)})
    return row


def _with_differences(row: dict, ref: dict) -> dict:
    """``row`` with the relative differences d_<output> of its headline outputs from ``ref``."""
    for name, column in _HEAD.items():
        row["d_" + name] = abs(row[column] / ref[column] - 1.0) if ref[column] else np.nan
    return row


def _table(rows: list[dict], tol: float, key: str) -> pd.DataFrame:
    """The fidelity table of ``rows`` (the columns of ADEQUACY_COLUMNS, ``level`` named
    ``key``), ``adequate`` where every difference is <= tol and the run did not fail."""
    import pandas as pd  # lazily: keeps `import trackwheel` light

    columns = [key if q.name == "level" else q.label for q in ADEQUACY_COLUMNS
               if q.name != "adequate"]
    df = pd.DataFrame(rows, columns=columns)
    df["adequate"] = (df[["d_" + n for n in _HEAD]] <= tol).all(axis=1) & (df.error == "")
    return df


#: vehicle levels of :func:`vehicle_adequacy`, least detailed first
VEHICLE_LEVELS = ("unsprung masses", "bogie", "half car")


def vehicle_levels(scene: Scene) -> dict:
    """The scene's vehicle at each level it can be cut down to: "unsprung masses" (the wheels
    alone, each under its constant static load of the weight distribution), "bogie" (the
    bogie frames on their primary suspensions, the car body replaced by its constant pivot
    loads; only with a car body) and the vehicle as given ("half car" with a car body, else
    "bogie")."""
    from dataclasses import replace

    veh = scene.active_vehicle
    g = scene.gravity
    loads = veh.static_loads(g)
    wheels = tuple(replace(w, load=P - w.mass * g) for w, P in zip(veh.wheels, loads))
    out = {"unsprung masses": replace(scene, vehicle=Vehicle(wheels=wheels,
                                                             positions=veh.positions))}
    if veh.car is not None:
        bogies = tuple(replace(b, load=F) for b, F in zip(veh.bogies, veh.pivot_loads(g)))
        out["bogie"] = replace(scene, vehicle=replace(veh, bogies=bogies, car=None))
        out["half car"] = scene
    else:
        out["bogie"] = scene
    return out


def vehicle_adequacy(scene: Scene, speeds=(100 / 3.6, 300 / 3.6), *, tol: float = 0.005,
                     **simulate_kwargs) -> pd.DataFrame:
    """Whether the bogies and the car body matter for ``scene`` (a scene with a vehicle):
    runs each of :func:`vehicle_levels` at each speed [m/s] and compares the worst wheel's
    headline outputs (``amplitude``, ``main_frequency``, ``peak_contact_force``) with the
    vehicle as given. One row per (speed, vehicle level) with the relative differences
    ``d_*`` and ``adequate`` (all <= tol); ``df.attrs["recommended"]`` is the least detailed
    level adequate at every speed. The suspension isolates the bodies above ~20 Hz, so for
    the wheel/rail force they rarely matter; the neighbouring wheels' waves through the rail
    are in every level."""
    if not isinstance(scene, Scene) or scene.vehicle is None:
        raise ValueError("vehicle_adequacy needs a Scene with a vehicle (Scene(vehicle=...))")
    scenes = vehicle_levels(scene)
    full = list(scenes)[-1]
    rows = []
    for speed in np.atleast_1d(np.asarray(speeds, dtype=float)):
        ref = None
        for name in [full] + [n for n in scenes if n != full]:
            row = _row(speed, "vehicle", name,
                       lambda: simulate(scenes[name], float(speed), **simulate_kwargs))
            ref = row if ref is None else ref
            rows.append(_with_differences(row, ref))
    df = _table(rows, tol, "vehicle")
    ok = df.groupby("vehicle", sort=False)["adequate"].all()
    df.attrs["tol"] = tol
    df.attrs["recommended"] = next((n for n in VEHICLE_LEVELS if ok.get(n, False)), full)
    return df


def shear_judgement(scene: Scene, speeds, *, tol: float = 0.005, **simulate_kwargs) -> dict:
    """Whether shear matters for ``scene`` at ``speeds`` [m/s]: ``{"pinned_pinned_euler": [Hz],
    "pinned_pinned_timoshenko": [Hz], "d_amplitude", "d_main_frequency",
    "d_peak_contact_force": largest relative difference Timoshenko vs Euler-Bernoulli of the
    linear/hertz level over the speeds, "matters": any of them > tol}``."""
    f_e, f_t = pinned_pinned_frequencies(scene)
    out = {"pinned_pinned_euler": f_e, "pinned_pinned_timoshenko": f_t}
    out.update({"d_" + k: 0.0 for k in _HEAD})
    for speed in np.atleast_1d(speeds):
        heads = []
        for beam in ("euler", "timoshenko"):
            sc = dataclasses.replace(scene, rail=dataclasses.replace(scene.rail, beam=beam))
            a = analyse(simulate(sc, float(speed), fidelity="linear/hertz", **simulate_kwargs))
            heads.append((a.amplitude, a.main_frequency, a.max_contact_force))
        for key, e, t in zip(_HEAD, *heads):
            out["d_" + key] = max(out["d_" + key], abs(t / e - 1.0) if e else 0.0)
    out["matters"] = any(out["d_" + k] > tol for k in _HEAD)
    return out


def contact_filter_judgement(scene: Scene) -> dict:
    """Whether the contact filter matters for the scene's rail profile (see :func:`adequacy`)."""
    a = contact_half_width(scene)
    lam = scene.irregularity.shortest_wavelength()
    h = abs(float(filter_attenuation(lam, a)[0])) if lam > 2.0 * a else 0.0
    return {"half_width": a, "shortest_wavelength": lam,
            "attenuation_db": -20.0 * math.log10(h) if h > 0.0 else math.inf,
            "matters": filter_matters(lam, a)}


def recommend(df) -> str:
    """The least detailed level (last in :data:`FIDELITY_LEVELS`) adequate at every speed in
    an :func:`adequacy` table; the reference level if none other is.

    The order of detail, not the measured wall time, decides: the choice is then the same on
    any machine and under any load (same inputs, same sweep), and the simpler model is the one
    a scene needs when both are adequate."""
    adequate = df.groupby("level")["adequate"].all()
    ok = [lvl for lvl in FIDELITY_LEVELS if adequate.get(lvl, False)]
    if not ok:
        return df.attrs.get("reference", "full")
    return ok[-1]
