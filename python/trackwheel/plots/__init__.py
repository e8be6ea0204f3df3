"""Figures of trackwheel results, drawn with matplotlib's object API.

Every function returns a :class:`matplotlib.figure.Figure` built without ``pyplot``, so nothing is
registered in pyplot's global figure list and no backend is needed: save it with
``fig.savefig("x.png")`` or let Jupyter show it (after ``%matplotlib inline``). Where a function
takes ``ax``, pass it to draw into an axes of your own figure instead. Every axis names its unit;
figures show SI quantities in the units a track engineer reads (mm and µm, MN/m, km/h).

Layer 5, one module per topic:

- :mod:`.modes` -- :func:`eigen` (the paper's Fig. 3) and :func:`mode_shapes`;
- :mod:`.convergence` -- :func:`time_step_convergence` (Fig. 4), :func:`element_convergence`
  (Fig. 5);
- :mod:`.sweeps` -- :func:`support_stiffness` (Fig. 6), :func:`speed` (Fig. 7);
- :mod:`.passage` -- :func:`dynamic` (one run: y_B, y_qs, d(t) and its spectrum) and
  :func:`acceleration_terms` (Fig. 8);
- :mod:`.excitation` -- :func:`irregularity_profile`, :func:`contact_force`,
  :func:`force_bands`;
- :mod:`.track` -- :func:`receptance`, :func:`decay_rate`;
- :mod:`.track_along_x` -- :func:`sleeper_envelope` (each sleeper's force envelope beside the
  supports' properties along X);
- :mod:`.periodic` -- :func:`periodic_force` (the steady force over the bay and its
  harmonics), :func:`random_force_bands` (its band RMS under a random profile);
- :mod:`.settlement` -- :func:`settlement_profile` (the settlement along X growing, beside
  the support stiffness), :func:`dynamic_factor_cycles` (the settlement loop,
  :func:`trackwheel.settle`);
- :mod:`.common` -- what they share, and :func:`run_label` / :func:`format_dt`, the names of
  runs in legends and tables.

This package imports matplotlib; ``import trackwheel`` does not, until ``trackwheel.plots`` is
used.
"""

from .common import format_dt, run_label
from .convergence import element_convergence, time_step_convergence
from .excitation import contact_force, force_bands, irregularity_profile
from .modes import eigen, mode_shapes
from .passage import acceleration_terms, dynamic
from .periodic import periodic_force, random_force_bands
from .settlement import dynamic_factor_cycles, settlement_profile
from .sweeps import DODGE, speed, support_stiffness
from .track import decay_rate, receptance
from .track_along_x import sleeper_envelope

__all__ = [
    "DODGE",
    "acceleration_terms",
    "contact_force",
    "decay_rate",
    "dynamic_factor_cycles",
    "dynamic",
    "eigen",
    "element_convergence",
    "force_bands",
    "format_dt",
    "irregularity_profile",
    "mode_shapes",
    "periodic_force",
    "random_force_bands",
    "receptance",
    "run_label",
    "settlement_profile",
    "sleeper_envelope",
    "speed",
    "support_stiffness",
    "time_step_convergence",
]
