"""Named quantities with their units: the rows of trackwheel's tables of fields and columns.

A :class:`Quantity` is defined once -- name, SI unit, description -- and the classes, table
columns, CSV headers, command-line formats and docs that show it are derived from it. Its
:attr:`~Quantity.label` is its name with its unit spelt as a suffix (``amplitude`` in m:
``amplitude_m``; ``speed`` in km/h: ``speed_kmh``), the one naming of every table trackwheel
writes (sweep tables, their stores and CSV files, the adequacy tables).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

#: How a unit is spelt in a column label; a unit not listed here may not be used in a table.
UNIT_SUFFIX = {
    "": "", "-": "", "m": "m", "s": "s", "Hz": "hz", "N": "N", "N/m": "N_m", "m/s": "m_s",
    "m/s^2": "m_s2", "km/h": "kmh", "%": "percent", "1/s": "1_s", "kg": "kg", "J": "J",
    "rad": "rad",
}


class _NoDefault:
    def __repr__(self) -> str:
        return "NO_DEFAULT"


#: a Quantity without a default value (a required field)
NO_DEFAULT = _NoDefault()


@dataclass(frozen=True)
class Quantity:
    """One named quantity: a field of a result class, a column of a table."""

    name: str  #: its name in the API (an attribute, a keyword, a field)
    unit: str  #: SI unit as the docs write it ("" for a count, a flag, a label; "-": a ratio)
    doc: str  #: what it is, with its symbol
    kind: str = "float"  #: the Python type (an annotation): "float", "int", "bool", "str", ...
    #: its default as a dataclass field (NO_DEFAULT: none), or a factory of it
    default: object = NO_DEFAULT
    factory: object = None
    symbol: str = ""  #: short name in the command line's table headers ("" : the name)
    display: tuple[str, float] = ("", 1.0)  #: (unit shown to people, factor from SI to it)

    def __post_init__(self):
        if self.unit not in UNIT_SUFFIX:
            raise ValueError(f"Quantity {self.name!r}: unit {self.unit!r} has no label suffix; "
                             f"allowed: {sorted(UNIT_SUFFIX)}")

    @property
    def label(self) -> str:
        """The column name: the name with its unit as a suffix (``amplitude_m``)."""
        suffix = UNIT_SUFFIX[self.unit]
        return f"{self.name}_{suffix}" if suffix else self.name

    @property
    def header(self) -> str:
        """The command line's header: symbol and displayed unit, e.g. "amplitude [µm]"."""
        unit = self.display[0] or self.unit
        name = self.symbol or self.name
        return f"{name} [{unit}]" if unit and unit != "-" else name

    def shown(self, value: float) -> float:
        """``value`` [SI] in the displayed unit."""
        return value * self.display[1]

    def describe(self) -> str:
        """One line of a generated docstring: "``name`` [unit]: doc"."""
        unit = self.unit or "-"
        return f"``{self.name}`` [{unit}]: {self.doc}"


def dataclass_fields(quantities) -> list[tuple]:
    """``dataclasses.make_dataclass`` field specs (name, annotation[, field]) of ``quantities``,
    in order (those with a default last, as Python requires)."""
    out = []
    for q in quantities:
        if q.factory is not None:
            out.append((q.name, q.kind, dataclasses.field(default_factory=q.factory)))
        elif q.default is NO_DEFAULT:
            out.append((q.name, q.kind))
        else:
            out.append((q.name, q.kind, dataclasses.field(default=q.default)))
    return out


def by_name(quantities) -> dict[str, Quantity]:
    """The quantities of a table by name."""
    return {q.name: q for q in quantities}


def generated_doc(head: str, quantities) -> str:
    """A class docstring: ``head`` and one line per quantity (name, unit, description)."""
    return "\n".join([head, "", *(f"- {q.describe()}" for q in quantities)])
