"""What :func:`trackwheel.reproduce.reproduce` computes (the :class:`Plan`: :data:`FULL` or
:data:`QUICK`), what every step gets (the :class:`Context`) and what a step is."""

from __future__ import annotations

import sys
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

from ..run.defaults import default_settings
from ..scene import Scene

#: wheel position of the mode-shape figure and of the reported frequencies [m] (mid-rail)
X_REPORT = 2.5
#: sample spacing of the convergence runs [s]: every run keeps its samples on this grid (or on
#: its own step, if coarser), so that runs at different time steps are compared at equal times
CONVERGENCE_SAMPLE = 1e-6
#: name of the sweep store inside the output folder
STORE_NAME = "sweep-store"
#: folder (inside the output folder) of the summary sections, one file per step
SECTIONS_NAME = "summary-sections"


# --------------------------------------------------------------------------------------------
# what it computes
@dataclass(frozen=True)
class Plan:
    """What :func:`reproduce` computes. Speeds in km/h, stiffnesses in N/m, lengths in m.

    The convergence runs (Figs. 4, 5) start where every run starts (the middle of the first
    support bay) and cover only ``fig4_stretch`` / ``fig5_stretch`` of track: the paper's
    smallest explicit step over the whole passage is expensive (the summary states the cost per
    step measured in the run and what the whole passage would take).
    """

    name: str
    n_eigen_positions: int  #: Fig. 3: wheel positions over the rail
    fig4_stretch: float  #: Fig. 4: length of track covered [m]
    fig5_stretch: float  #: Fig. 5: length of track covered [m]
    stiffness: tuple[float, ...]  #: Fig. 6: support stiffnesses [N/m]
    speeds_kmh: tuple[float, ...]  #: Fig. 7: speeds [km/h]
    #: settings of the sweeps (Figs. 6, 7) and of the Fig. 8 runs, passed to simulate; empty:
    #: simulate's derived defaults (trackwheel.default_settings)
    simulate: dict = field(default_factory=dict)
    fig4_speed_kmh: float = 50.0
    fig4_n_elements: int = 20
    fig4_explicit_dt: tuple[float, ...] = (1e-6, 1e-7, 1e-8)  #: the paper's steps [s]
    fig4_alpha_dt: tuple[float, ...] = (1e-5, 5e-6)  #: generalized-alpha at larger steps [s]
    fig5_speed_kmh: float = 200.0
    fig5_n_elements: tuple[int, ...] = (20, 40, 80)
    fig5_explicit_dt: float = 1e-7  #: the paper's step [s]
    fig5_alpha_dt: float = 1e-5  #: [s]
    fig6_speeds_kmh: tuple[float, ...] = (100.0, 300.0)
    fig8_speeds_kmh: tuple[float, ...] = (100.0, 300.0)

    def describe_settings(self, scene: Scene) -> str:
        """The simulate settings of the sweeps, in words."""
        if not self.simulate:
            d = default_settings(scene)
            return (f"simulate's derived defaults (generalized-alpha, {d['n_elements']} "
                    f"elements, dt = {d['dt']:.3g} s)")
        return ", ".join(f"{k} = {val}" for k, val in self.simulate.items())


#: The full run: the paper's ranges (Fig. 6: 20-300 MN/m, 10 values; Fig. 7: 50-400 km/h in
#: steps of 50) at simulate's derived (converged) settings.
FULL = Plan(
    name="full", n_eigen_positions=201, fig4_stretch=0.10, fig5_stretch=0.25,
    stiffness=tuple(k * 1e6 for k in (20, 30, 45, 70, 100, 140, 180, 220, 260, 300)),
    speeds_kmh=tuple(float(s) for s in range(50, 401, 50)))
#: --quick: coarse grids, the paper's 20-element mesh at 1e-5 s for the sweeps (amplitudes
#: within about 5 % of the full run's), short convergence stretches.
QUICK = Plan(
    name="quick", n_eigen_positions=41, fig4_stretch=0.005, fig5_stretch=0.01,
    stiffness=(20e6, 45e6, 70e6, 140e6, 300e6), speeds_kmh=(50.0, 100.0, 200.0, 300.0, 400.0),
    simulate={"n_elements": 20, "dt": 1e-5})


@dataclass
class Context:
    """What every step gets: the scene, the output folder and the plan; steps append the files
    they wrote and the lines of their summary section, and report progress through :meth:`log`."""

    scene: Scene
    out: Path
    plan: Plan = FULL
    workers: int | None = None  #: sweep processes (None: one per core)
    stream: object = None  #: where progress is printed (None: stdout)
    written: list[Path] = field(default_factory=list)
    summary: list[str] = field(default_factory=list)  #: the current step's section

    def log(self, message: str) -> None:
        print(f"      {message}", file=self.stream or sys.stdout, flush=True)

    @property
    def store(self) -> Path:
        return self.out / STORE_NAME

    def save(self, fig, name: str) -> None:
        path = self.out / name
        fig.savefig(path, dpi=150)
        self.written.append(path)

    def table(self, df, name: str) -> None:
        """Write ``df`` as CSV (its columns named with their units)."""
        path = self.out / name
        df.to_csv(path, index=False)
        self.written.append(path)


@dataclass(frozen=True)
class Step:
    """One figure of the paper: ``run(ctx)`` computes it and writes its files into ``ctx.out``."""

    name: str  #: short id, e.g. "fig3"
    title: str  #: what it reproduces
    run: Callable[[Context], None]

