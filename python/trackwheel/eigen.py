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
    #: (n_pos, n_dof + n_vehicle + n_sleepers, n_modes): rail ANCF coords, then the wheel Y
    #: (one wheel) or the vehicle's coordinates u = [Y_A per wheel, (z, phi) per body], then
    #: the sleepers' z_j (layered supports) [-]
    shapes: np.ndarray
    axial_frequencies: np.ndarray  #: lowest axial (x) modes, (min(n_axial, axial dofs),) [Hz]
    n_elements: int  #: mesh used
    n_vehicle: int = 1  #: vehicle coordinates after the rail's n_dof in each shape [-]
    #: share of each mode's kinetic energy in the vehicle's bodies, (n_pos, n_modes) [-]: near 1
    #: for the suspension (rigid-body) modes, near 0 for the track modes; None for one wheel
    body_fraction: np.ndarray | None = None

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

    With a ``scene.vehicle`` the positions place the vehicle's reference point (x = 0; every
    wheel must be on the rail) and the modes are those of the rail, the wheels on their
    linearised contact springs and the bodies on their suspensions together (undamped): the
    lowest are the suspension's rigid-body modes (car body ~1 Hz, bogies 5-10 Hz),
    ``body_fraction`` tells them from the track modes.

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
    if scene.vehicle is not None:
        return _vehicle_eigen(scene, x, n_modes, ne, n_axial)
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


def _vehicle_eigen(scene: Scene, x: np.ndarray, n_modes: int, ne: int, n_axial: int
                   ) -> EigenResult:
    """:func:`eigen` for a vehicle: K q = omega^2 M q over [rail vertical coords, u, sleepers'
    z_j (layered supports)]."""
    from scipy.linalg import eigh

    if scene.rail.beam != "euler":
        raise ValueError(f"eigen with a vehicle takes Rail(beam='euler') (the ANCF rail "
                         f"linearised), got beam = {scene.rail.beam!r}")

    veh = scene.active_vehicle
    model = _kernel.rail_model(scene, ne)
    rear, front = veh.span
    if x.min() + rear < 0.0 or x.max() + front > scene.rail.length:
        raise ValueError(f"positions: the vehicle's wheels span x = {rear}..{front} m, so its "
                         f"reference must lie in [{-rear:.4g}, {scene.rail.length - front:.4g}] m")
    free = np.asarray(model.free_to_full)
    e0 = model.reference()
    Kr = np.asarray(model.tangent_dense(e0))
    Mr = np.asarray(model.mass_dense())
    vert = free[free % 2 == 1]  # y and dy/ds: the straight rail's vertical coordinates
    nr, nw, nb = vert.size, veh.n_wheels, veh.n_bodies
    vm = _vehicle_matrices(scene)
    Ks, Ms, Ss = _sleeper_blocks(scene, model, e0, vert)
    ns = Ms.shape[0]
    n_modes = v.integer("n_modes", n_modes, low=1, high=nr + nw + 2 * nb + ns)
    kc = scene.contact_stiffness
    nu = nw + 2 * nb
    n = nr + nu + ns
    freqs, shapes, frac = [], [], []
    for x0 in x:
        S = _couplings(model, e0, vert, [x0 + p for p in veh.positions])  # (nw, nr)
        K = np.zeros((n, n))
        M = np.zeros((n, n))
        K[:nr, :nr] = Kr[np.ix_(vert, vert)] + kc * S.T @ S
        M[:nr, :nr] = Mr[np.ix_(vert, vert)]
        K[:nr, nr:nr + nw] = -kc * S.T
        K[nr:nr + nw, :nr] = -kc * S
        K[nr:nr + nu, nr:nr + nu] += vm[0]
        K[nr:nr + nw, nr:nr + nw] += kc * np.eye(nw)
        M[nr:nr + nu, nr:nr + nu] = np.diag(vm[1])
        K[nr + nu:, nr + nu:] = Ks
        M[nr + nu:, nr + nu:] = Ms
        K[:nr, nr + nu:] = Ss.T
        K[nr + nu:, :nr] = Ss
        w2, vec = eigh(K, M, subset_by_index=(0, n_modes - 1))
        freqs.append(np.sqrt(np.maximum(w2, 0.0)) / (2 * np.pi))
        kin = vec * (M @ vec)
        frac.append(kin[nr + nw:nr + nu].sum(axis=0) / kin.sum(axis=0))
        full = np.zeros((model.n_dof + n - nr, n_modes))
        full[vert] = vec[:nr]
        full[model.n_dof:] = vec[nr:]
        shapes.append(full)
    axial = (np.asarray(_core.axial_modes(model, n_axial)[0]).ravel() if n_axial
             else np.empty(0))
    return EigenResult(scene=scene, positions=x, frequencies=np.asarray(freqs),
                       shapes=np.asarray(shapes), axial_frequencies=axial, n_elements=ne,
                       n_vehicle=nw + 2 * nb, body_fraction=np.asarray(frac))


def _sleeper_blocks(scene: Scene, model, e0, vert) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The layered supports' blocks over the sleepers' z_j (docs: Model § Layered supports):
    K_zz = (k_p + k_b) I, M_zz = m_s I and the coupling K_zr = -k_p s(x_j) to the rail's
    vertical coordinates (the pads' k_p s s^T to ground is already in the rail's tangent).
    Empty without sleepers."""
    sp = scene.supports
    if not sp.layered:
        return np.zeros((0, 0)), np.zeros((0, 0)), np.zeros((0, vert.size))
    xs = scene.support_positions
    ns = len(xs)
    Ks = (sp.stiffness + sp.ballast_stiffness) * np.eye(ns)
    return Ks, sp.sleeper_mass * np.eye(ns), -sp.stiffness * _couplings(model, e0, vert, xs)


def _vehicle_matrices(scene: Scene) -> tuple[np.ndarray, np.ndarray]:
    """(K_v, mass diagonal over u) of the scene's vehicle, u = [Y per wheel, (z, phi) per
    body]: K_v = sum k g g^T over the suspensions (docs: Model § The vehicle); the wheels'
    masses on the wheels' entries."""
    veh = scene.active_vehicle
    vp = _kernel.vehicle_params(scene)
    nw = veh.n_wheels
    n = nw + 2 * len(vp.bodies)
    K = np.zeros((n, n))
    for sp in vp.suspensions:
        g = np.zeros(n)
        g[nw + 2 * sp.upper_body] += 1.0
        g[nw + 2 * sp.upper_body + 1] += sp.upper_arm
        if sp.lower_wheel >= 0:
            g[sp.lower_wheel] -= 1.0
        else:
            g[nw + 2 * sp.lower_body] -= 1.0
            g[nw + 2 * sp.lower_body + 1] -= sp.lower_arm
        K += sp.stiffness * np.outer(g, g)
    mass = [w.mass for w in veh.wheels]
    for b in vp.bodies:
        mass += [b.mass, b.inertia]
    return K, np.asarray(mass)


def _couplings(model, e0, vert, xs) -> np.ndarray:
    """s(X) over the rail's vertical coordinates at each X in xs: y(X) = s(X) . e (the
    positions are linear in e; each column from a unit vector)."""
    S = np.zeros((len(xs), vert.size))
    for j, i in enumerate(vert):
        unit = np.zeros_like(e0)
        unit[i] = 1.0
        S[:, j] = np.asarray(model.positions(unit, list(xs)))[:, 1]
    return S


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
