"""The quantities a study reports, defined once: name, unit, description.

:data:`ANALYSIS_FIELDS` defines :class:`~trackwheel.Analysis` (its fields and their docs);
:data:`OUTPUTS`, the scalar outputs of an analysis a sweep tabulates per wheel, are among
them. :data:`SWEEP_COLUMNS` defines the sweep table -- the DataFrame of
:func:`trackwheel.sweep` and :func:`trackwheel.load_sweep`, its store's records and its CSV
files -- and :data:`ADEQUACY_COLUMNS` the fidelity tables of :func:`trackwheel.adequacy`. Every
column is named by its :attr:`~trackwheel.base.fields.Quantity.label`: the quantity's name with
its unit (``amplitude_m``, ``speed_m_s``, ``speed_kmh``, ``support_stiffness_N_m``), the same in
a DataFrame, a CSV header and a store. The command line's headers and scales come from here too.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

from ..base.fields import Quantity, by_name
from ..run.results import SETTINGS_FIELDS

_SETTINGS = by_name(SETTINGS_FIELDS)

# --------------------------------------------------------------------------------------------
# the analysis of one run
#: the scalar outputs of an analysis, per wheel: Analysis fields or properties, and the sweep
#: table's output columns
OUTPUTS: tuple[Quantity, ...] = (
    Quantity("amplitude", "m", "max |d|, the amplitude of the dynamic part d = y_B - y_qs",
             display=("µm", 1e6)),
    Quantity("main_frequency", "Hz", "main frequency: the peak of the amplitude spectrum of "
             "d (NaN if none)", symbol="main f"),
    Quantity("frequency_resolution", "Hz", "1 / (N dt) of the record", symbol="±"),
    Quantity("min_contact_force", "N", "min N", display=("kN", 1e-3)),
    Quantity("max_contact_force", "N", "max N", symbol="N", display=("kN", 1e-3)),
    Quantity("lost_contact", "", "N = 0 at some kept sample", "bool", symbol="lost"),
    Quantity("dynamic_factor", "-", "max N / P0, P0 = F + M g the static wheel load",
             symbol="N/P0"),
    Quantity("loss_duration", "s", "total time without contact (0 if the wheel kept contact)"),
    Quantity("force_rms", "N", "RMS of N - mean(N) over the record"),
    Quantity("p1", "N", "P1, the peak of N after the scene's dipped joint (NaN: none)"),
    Quantity("p1_time", "s", "time of P1"),
    Quantity("p2", "N", "P2, the later, lower-frequency peak of N after the joint"),
    Quantity("p2_time", "s", "time of P2"),
    Quantity("max_ballast_force", "N", "the largest ballast force (compression positive) under "
             "any sleeper standing in the wheel's measured stretch of X, over the run (every "
             "wheel's load on it, on a vehicle; single springs: the spring's force; NaN: no "
             "support in the stretch)", symbol="max F_b", display=("kN", 1e-3)),
    Quantity("max_ballast_force_x", "m", "X of the sleeper that carried max_ballast_force",
             symbol="at X"),
    Quantity("max_rail_seat_force", "N", "the largest rail-seat (pad) force (compression "
             "positive) at any support standing in the wheel's measured stretch of X, over the "
             "run",
             symbol="max F_p", display=("kN", 1e-3)),
)
_OUT = by_name(OUTPUTS)


def _array(name: str, unit: str, doc: str) -> Quantity:
    return Quantity(name, unit, f"{doc}, (n_samples,)", "np.ndarray")


#: the fields of :class:`~trackwheel.Analysis`, in order
ANALYSIS_FIELDS: tuple[Quantity, ...] = (
    _array("t", "s", "time"),
    _array("x_wheel", "m", "X_A, wheel-centre position"),
    Quantity("x_range", "m", "(X_from, X_to): the wheel-centre positions measured, the "
             "samples the other fields hold (by default away from the rail's rigid ends and "
             "the start-up transient; the whole run where the rail is too short for that, as "
             "the paper's: docs: Model § Outputs)", "tuple[float, float]"),
    _array("y_contact", "m", "y_B, rail displacement under the wheel"),
    _array("y_qs", "m", "quasi-static line y_qs(X_A(t))"),
    _array("dynamic", "m", "d = y_B - y_qs(X_A)"),
    _OUT["amplitude"],
    Quantity("amplitude_time", "s", "time of max |d|"),
    _OUT["main_frequency"],
    _OUT["frequency_resolution"],
    Quantity("spectrum", "", "(freqs [Hz], amplitude of d [m]): the amplitude spectrum of d "
             "(trackwheel.amplitude_spectrum)", "tuple[np.ndarray, np.ndarray]"),
    Quantity("n_fft", "", "FFT length used (zero padding included)", "int"),
    Quantity("y_qs_error", "m", "estimated interpolation error of y_qs (see QS_DEGREE)"),
    _array("normal_force", "N", "N, the contact force"),
    _OUT["min_contact_force"],
    _OUT["max_contact_force"],
    _OUT["lost_contact"],
    _array("acc_contact", "m/s^2", "d^2 y_B / dt^2"),
    _array("acc_A", "m/s^2", "rho cos(phi) theta' v phi_s (docs: Model § Outputs, eq. 21)"),
    _array("acc_B", "m/s^2", "rho cos(phi) theta' phi_t"),
    _array("acc_C", "m/s^2", "rho cos(phi) v^2 phi_s^2"),
    _array("acc_D", "m/s^2", "rho cos(phi) phi_t^2"),
    _array("acc_E", "m/s^2", "2 rho cos(phi) phi_t v phi_s"),
    Quantity("slide_duration", "s", "total time the wheel slid, |lambda| = mu N (a brake or "
             "torque beyond adhesion, a violent impact; 0 if it rolled throughout)"),
    Quantity("locked_duration", "s", "total time the wheel was locked, theta' = 0 in contact (a "
             "brake beyond adhesion; it slides meanwhile)"),
    Quantity("forces", "", "the contact-force statistics of N "
             "(trackwheel.force_statistics.force_statistics)", "ForceStatistics"),
    _OUT["max_ballast_force"],
    _OUT["max_ballast_force_x"],
    _OUT["max_rail_seat_force"],
)


# --------------------------------------------------------------------------------------------
# the sweep table
@dataclass(frozen=True)
class Column:
    """A column of a table: its quantity and its pandas dtype (None: as pandas infers it)."""

    quantity: Quantity
    dtype: str | None = None

    @property
    def label(self) -> str:
        return self.quantity.label


def _float(q: Quantity) -> Column:
    return Column(q, "float64")


#: the case axes of a sweep table
SPEED = replace(_SETTINGS["speed"], doc="forward speed v")
SPEED_KMH = Quantity("speed", "km/h", "forward speed v", symbol="v")
SUPPORT_STIFFNESS = Quantity("support_stiffness", "N/m", "k_s, the supports' stiffness (layered "
                             "supports: the rail pads')", symbol="k_s", display=("MN/m", 1e-6))

#: The sweep table's columns, in order (one row per case and wheel). Outputs are NaN (and
#: ``lost_contact`` <NA>) for failed cases.
SWEEP_COLUMNS: tuple[Column, ...] = (
    _float(SPEED),
    _float(SPEED_KMH),
    _float(SUPPORT_STIFFNESS),
    Column(Quantity("seed", "", "realisation of the random irregularity (<NA> without a seeds "
                    "axis)", "int"), "Int64"),
    Column(Quantity("wheel", "", "the wheel this row measures (0 for a single wheel; <NA> for "
                    "failed cases)", "int"), "Int64"),
    Column(Quantity("worst", "", "True on the case's worst wheel (largest amplitude): one such "
                    "row per case", "bool"), "boolean"),
    *(Column(q, "boolean" if q.kind == "bool" else "float64") for q in OUTPUTS),
    Column(Quantity("error", "", '"" if the case ran, else "DivergenceError: ..." / '
                    '"ValueError: ..."', "str"), "str"),
    _float(Quantity("wall_time", "s", "simulate's wall time, or periodic_response's at the "
                    "periodic level (time to failure for failed cases)")),
    # the settings used (from Result.settings; for failed cases the requested or default ones)
    Column(_SETTINGS["integrator"]),
    _float(_SETTINGS["dt"]),
    Column(_SETTINGS["n_elements"], "Int64"),
    _float(_SETTINGS["x_start"]),
    _float(Quantity("x_end", "m", "wheel-centre end X_0 + v t_end")),
    _float(_SETTINGS["t_end"]),
    Column(_SETTINGS["output_every"], "Int64"),
    _float(_SETTINGS["rho_inf"]),
    _float(_SETTINGS["baumgarte"]),
    Column(_SETTINGS["rolling"]),
    Column(_SETTINGS["start"]),
    _float(_SETTINGS["drop_height"]),
    Column(_SETTINGS["fidelity"]),
    Column(_SETTINGS["n_modes"]),
    Column(Quantity("steps", "", "time steps taken", "int"), "Int64"),
    Column(Quantity("version", "", "trackwheel version that computed the row", "str")),
    Column(Quantity("case", "", "inputs hash (the store's record name)", "str")),
)
#: the sweep table's column names, in order
COLUMNS: tuple[str, ...] = tuple(c.label for c in SWEEP_COLUMNS)
#: What the periodic level (``fidelity="periodic/linear"``, the steady state in the frequency
#: domain) puts in each output column of the sweep table, by quantity name: the steady
#: state's counterpart of the time-domain measure, or None where it has none (the column is
#: then NaN). Its settings columns are empty (NaN, <NA>, None) but ``fidelity``.
PERIODIC_OUTPUTS: dict[str, str | None] = {
    "amplitude": "max |d| over the steady state, d = y_B - y_qs on the infinite track (exact "
                 "for sines incommensurate with the bay, else an upper bound)",
    "main_frequency": "the frequency of d's largest line (exact: no record)",
    "frequency_resolution": None,  # no record
    "min_contact_force": "the least N over all phases of the steady state",
    "max_contact_force": "the largest N over all phases of the steady state",
    "lost_contact": "False (a steady state that would lose contact is refused)",
    "dynamic_factor": "max N / P",
    "loss_duration": "0 (as lost_contact)",
    "force_rms": "RMS of N - P over a long run, from the lines' amplitudes",
    "p1": None,  # joints are refused: no P1/P2
    "p1_time": None,
    "p2": None,
    "p2_time": None,
    "max_ballast_force": None,  # no support forces in the steady state's outputs
    "max_ballast_force_x": None,
    "max_rail_seat_force": None,
}
#: the columns of the sweep table that hold floats (NaN where a case failed)
FLOAT_COLUMNS: tuple[str, ...] = tuple(c.label for c in SWEEP_COLUMNS if c.dtype == "float64")
#: the output columns of one wheel (a vehicle's case has one row per wheel)
OUTPUT_COLUMNS: tuple[str, ...] = tuple(q.label for q in OUTPUTS)
#: the settings columns copied from ``Result.settings`` (x_end: a property of it)
SETTINGS_COLUMNS: dict[str, str] = {name: _SETTINGS[name].label for name in (
    "integrator", "dt", "n_elements", "x_start", "t_end", "output_every", "rho_inf", "baumgarte",
    "rolling", "start", "drop_height", "fidelity", "n_modes")}
#: the force-statistics columns :func:`trackwheel.summarise_seeds` summarises by default
SEED_COLUMNS: tuple[str, ...] = tuple(_OUT[n].label for n in (
    "max_contact_force", "min_contact_force", "dynamic_factor", "loss_duration", "force_rms"))


#: the column of each quantity name (the first of a name: ``speed`` -> ``speed_m_s``)
_LABELS = {c.quantity.name: c.label for c in reversed(SWEEP_COLUMNS)}


def label(name: str) -> str:
    """The sweep table's column of the quantity ``name`` (``"amplitude"`` -> ``"amplitude_m"``,
    ``"wall_time"`` -> ``"wall_time_s"``; ``"speed"`` -> ``"speed_m_s"``, the km/h column is
    ``"speed_kmh"``)."""
    return _LABELS[name]


def old_name(column: Column) -> str:
    """The column's name in sweep stores of format 3, written before the columns carried their
    units (the quantity's name; ``speed_kmh`` as it was)."""
    q = column.quantity
    return q.label if q.unit == "km/h" else q.name


def periodic_doc_table() -> str:
    """Docstring lines saying what the periodic level puts in each output column."""
    return "\n".join(f"- ``{_OUT[name].label}``: {what or 'NaN'}"
                     for name, what in PERIODIC_OUTPUTS.items())


def doc_table(columns) -> str:
    """Docstring lines listing ``columns`` (Column or Quantity): label, unit, description."""
    lines = []
    for c in columns:
        q = c.quantity if isinstance(c, Column) else c
        lines.append(f"- ``{q.label}`` [{q.unit or '-'}]: {q.doc}")
    return "\n".join(lines)


# --------------------------------------------------------------------------------------------
# the fidelity tables
#: the headline outputs the fidelity tables compare
HEADLINE: tuple[Quantity, ...] = (
    _OUT["amplitude"], _OUT["main_frequency"],
    Quantity("peak_contact_force", "N", "the largest N (of any wheel)"))
#: the columns of :func:`trackwheel.adequacy`'s table (``vehicle_adequacy``: ``vehicle`` for
#: ``level``), one row per (speed, level)
ADEQUACY_COLUMNS: tuple[Quantity, ...] = (
    SPEED, SPEED_KMH,
    Quantity("level", "", "the fidelity level (vehicle_adequacy's column ``vehicle``: the "
             "vehicle level)", "str"),
    Quantity("error", "", "the message if the level failed, else \"\"", "str"),
    *HEADLINE,
    _OUT["lost_contact"],
    Quantity("wall_time", "s", "simulate's wall time (the periodic level: its call's)"),
    *(Quantity(f"d_{q.name}", "-", f"relative difference of {q.name} from the reference level")
      for q in HEADLINE),
    Quantity("adequate", "", "every relative difference <= tol and no error", "bool"),
)
