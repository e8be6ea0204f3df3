"""Studies of runs: measuring them, comparing them, sweeping over them (docs: Model § Outputs).

Layer 4: it knows the layers below and calls the kernel only through ``run``.

- :mod:`.columns` -- every quantity a study reports, defined once (name, unit, description):
  the :class:`~trackwheel.Analysis` fields and the sweep and fidelity tables' columns;
- :mod:`.analysis` -- :func:`~trackwheel.analyse`: the dynamic part of the contact-point
  displacement, its amplitude and main frequency, the acceleration terms;
- :mod:`.force_statistics` -- contact-force statistics on plain arrays;
- :mod:`.steady` -- the bay-periodic steady state of a run;
- :mod:`.convergence` -- automatic refinement of the time step and the mesh;
- :mod:`.fidelity` -- the model levels side by side, and the one a scene needs;
- :mod:`.sweep` -- parameter sweeps in parallel, resumable from a store;
- :mod:`.settlement` -- ballast settlement laws per sleeper (``trackwheel.settlement``).
"""
