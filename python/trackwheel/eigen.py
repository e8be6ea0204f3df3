"""Natural frequencies of the coupled wheel/rail/support system (paper §3, docs: Model § Eigen analysis).

The rail is the ANCF rail linearised about the straight reference, which is exactly an
Euler-Bernoulli Hermite beam in y (and a cubic bar in x, whose modes are reported apart in
``axial_frequencies``); with ``Rail(beam="timoshenko")`` it is the linear track's Timoshenko
beam (docs: Model, section "Shear-deformable rail (Timoshenko)"), whose mode shapes carry the section rotation psi in
the slope slots. The wheel is the mass M on the contact spring k (linearised Hertz),
attached to the rail at the wheel position X through the element shape functions, so X need not
be a node. Layered supports add one DOF per sleeper (mass m_s between the pad and the ballast
springs). ``K x = omega^2 M x`` is solved by the symmetric-definite generalised eigensolver
(Eigen, in the C++ kernel) for each position.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import _core, _kernel
from . import _validate as v
from .scene import MAX_ELEMENTS, Scene


@dataclass(frozen=True)
class EigenResult:
    """Vertical modes against wheel position."""

    scene: Scene
    positions: np.ndarray  #: wheel positions X, (n_pos,) [m]
    frequencies: np.ndarray  #: (n_pos, n_modes) [Hz], ascending in each row
    #: (n_pos, n_dof + 1 + n_sleepers, n_modes): rail ANCF coords, wheel Y, then the sleepers'
    #: z_j (layered supports) [-]
    shapes: np.ndarray
    axial_frequencies: np.ndarray  #: lowest axial (x) modes, (min(n_axial, axial dofs),) [Hz]
    n_elements: int  #: mesh used

    def __repr__(self) -> str:
        n_pos, n_modes = self.frequencies.shape
        lo, hi = self.frequencies.min(axis=0), self.frequencies.max(axis=0)
        shown = min(n_modes, 4)
        bands = ", ".join(f"{a:.1f}-{b:.1f}" for a, b in zip(lo[:shown], hi[:shown]))
        more = f" (+{n_modes - shown} more)" if n_modes > shown else ""
        axial = ", ".join(f"{f:.1f}" for f in self.axial_frequencies[:3])
        return (f"<trackwheel.EigenResult: {n_modes} vertical modes at {n_pos} wheel positions "
                f"X = {self.positions.min():.4g}..{self.positions.max():.4g} m, "
                f"{self.n_elements} elements>\n"
                f"  vertical [Hz]: {bands}{more}\n"
                f"  axial [Hz]: {axial or '-'}")

    def rail_mode_shape(self, i_pos: int, mode: int, n_points: int = 201):
        """Vertical mode shape along the rail: (s [m], y(s) [-], wheel Y [-]), scaled so that the
        largest |value| over rail and wheel is 1 and the wheel (or rail maximum) is positive."""
        n_pos, _, n_avail = self.shapes.shape
        i_pos = v.integer("i_pos", i_pos, low=-n_pos, high=n_pos - 1)
        mode = v.integer("mode", mode, low=0, high=n_avail - 1)
        n_points = v.integer("n_points", n_points, low=2, high=10**7)
        model = _kernel.rail_model(self.scene, self.n_elements)
        vec = np.asarray(self.shapes[i_pos, :, mode])
        s = np.linspace(0.0, self.scene.rail.length, n_points)
        n_dof = model.n_dof
        y = model.positions(vec[:n_dof], s)[:, 1]
        wheel = vec[n_dof]
        scale = max(np.max(np.abs(y)), abs(wheel))
        ref = wheel if abs(wheel) > 1e-3 * scale else y[np.argmax(np.abs(y))]
        scale *= np.sign(ref) or 1.0
        return s, y / scale, wheel / scale


def eigen(scene: Scene, positions, n_modes: int = 6, *, n_elements: int | None = None,
          n_axial: int = 3) -> EigenResult:
    """Lowest ``n_modes`` vertical natural frequencies [Hz] with the wheel at each of
    ``positions`` [m] (0 <= X <= L).

    >>> r = eigen(Scene.kato2005(), [2.5])
    >>> r.frequencies.shape
    (1, 6)
    """
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a trackwheel.Scene, got {type(scene).__name__}")
    x = v.positions("positions", positions, 0.0, scene.rail.length)
    ne = scene.rail.n_elements if n_elements is None else v.integer(
        "n_elements", n_elements, low=1, high=MAX_ELEMENTS)
    model = _kernel.rail_model(scene, ne)
    n_y = sum(1 for i in model.free_to_full if i % 2 == 1)
    n_sleepers = len(scene.support_positions) if scene.supports.layered else 0
    n_modes = v.integer("n_modes", n_modes, low=1, high=n_y + 1 + n_sleepers)
    n_x = sum(1 for i in model.free_to_full if i % 2 == 0)
    # at most the n_x axial modes the mesh has (one element has only one or two)
    n_axial = min(v.integer("n_axial", n_axial, low=0), n_x)
    if scene.rail.beam == "euler":
        freqs, shapes = _core.vertical_modes(model, scene.wheel.mass, scene.contact_stiffness,
                                             x.tolist(), n_modes)
    else:
        freqs, shapes = _timoshenko_modes(scene, model, x, n_modes)
    axial = (np.asarray(_core.axial_modes(model, n_axial)[0]).ravel() if n_axial
             else np.empty(0))
    return EigenResult(scene=scene, positions=x, frequencies=np.asarray(freqs),
                       shapes=np.asarray(shapes), axial_frequencies=axial, n_elements=ne)


def rail_frequencies(scene: Scene, n_modes: int = 6, *, n_elements: int | None = None
                     ) -> np.ndarray:
    """Vertical natural frequencies of the rail on its supports without the wheel [Hz]."""
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a trackwheel.Scene, got {type(scene).__name__}")
    ne = scene.rail.n_elements if n_elements is None else v.integer(
        "n_elements", n_elements, low=1, high=MAX_ELEMENTS)
    model = _kernel.rail_model(scene, ne)
    n_modes = v.integer("n_modes", n_modes, low=1)
    if scene.rail.beam == "euler":
        freqs, _ = _core.vertical_modes(model, 0.0, 0.0, [0.0], n_modes)
    else:
        freqs, _ = _core.track_modes(model, _kernel.beam_params(scene), 0.0, 0.0, [0.0], n_modes)
    return np.asarray(freqs).ravel()


def _timoshenko_modes(scene: Scene, model, x: np.ndarray, n_modes: int):
    """The linear track's modes with the Timoshenko rail, shapes scattered into the ANCF
    numbering: the deflection w in the y slot, the section rotation psi in the slope slot."""
    freqs, per_pos = _core.track_modes(model, _kernel.beam_params(scene), scene.wheel.mass,
                                       scene.contact_stiffness, x.tolist(), n_modes)
    y_dofs = [i for i in model.free_to_full if i % 2 == 1]
    shapes = np.zeros((len(per_pos), model.n_dof + 1, n_modes))
    for p, s in enumerate(per_pos):
        shapes[p, y_dofs, :] = np.asarray(s)[:-1]
        shapes[p, -1, :] = np.asarray(s)[-1]
    return freqs, shapes
