"""Natural frequencies of the coupled wheel/rail/support system (paper §3, docs: Model § Eigen analysis).

The rail is the ANCF rail linearised about the straight reference, which is exactly an
Euler-Bernoulli Hermite beam in y (and a cubic bar in x, whose modes are reported apart in
``axial_frequencies``); with ``Rail(beam="timoshenko")`` it is the shear-deformable ANCF rail
linearised, which is exactly the linear track's Timoshenko (IIE) beam in y (docs: Model, section
"Shear-deformable rail (Timoshenko)"), its mode shapes carrying the section rotation psi in the
slope slots. The wheel is the mass M on the contact spring k (linearised Hertz),
attached to the rail at the wheel position X through the element shape functions, so X need not
be a node. Layered supports add one DOF per sleeper (mass m_s between the pad and the ballast
springs). ``K x = omega^2 M x`` is solved for each position by one of two methods:

- ``"dense"``: the symmetric-definite generalised eigensolver (Eigen, in the C++ kernel; scipy's
  ``eigh`` with a vehicle), all modes, O(n^2) memory and O(n^3) time, at most
  ``MAX_DENSE_EIGEN_DOF`` coordinates;
- ``"sparse"``: the lowest modes only, by shift-invert Lanczos (ARPACK through
  :func:`scipy.sparse.linalg.eigsh`) on the banded K and M the kernel exports (rail, wheel,
  sleepers), O(n) memory and time per mode; one wheel only (a vehicle takes the dense
  method);

``"auto"`` takes the sparse method above ``AUTO_SPARSE_DOF`` coordinates where it can.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .. import _core
from ..base import validate as v
from ..base.limits import MAX_DENSE_EIGEN_DOF
from ..scene import Scene
from . import kernel
from .defaults import derived_mesh, mesh

#: ``method="auto"`` solves problems with more coordinates than this by the sparse method [-]:
#: below it the dense solve takes milliseconds and gives every mode.
AUTO_SPARSE_DOF = 400
METHODS = ("auto", "dense", "sparse")
#: Lanczos basis size (ARPACK's ncv, at least 2 n_modes + 1) and relative tolerance of the
#: eigenvalues of the sparse method [-].
SPARSE_BASIS = 64
SPARSE_TOL = 1e-12
#: the shift sits this fraction below the first estimate of the lowest eigenvalue omega_1^2 [-]
#: (closer gains little and costs accuracy on ill-conditioned pencils such as a long bare rail)
SPARSE_SHIFT = 0.1


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
        bands = ", ".join(f"{a:.1f}" if n_pos == 1 else f"{a:.1f}-{b:.1f}"
                          for a, b in zip(lo[:shown], hi[:shown]))
        more = f" (+{n_modes - shown} more)" if n_modes > shown else ""
        axial = ", ".join(f"{f:.1f}" for f in self.axial_frequencies[:3])
        where = (f"X = {self.positions[0]:.4g} m" if n_pos == 1 else
                 f"{n_pos} wheel positions X = {self.positions.min():.4g}.."
                 f"{self.positions.max():.4g} m")
        return (f"<trackwheel.EigenResult: {n_modes} vertical mode{'s' * (n_modes != 1)} at "
                f"{'one wheel position ' * (n_pos == 1)}{where}, "
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
        model = kernel.rail_model(self.scene, self.n_elements)
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
          n_axial: int = 3, method: str = "auto") -> EigenResult:
    """Lowest ``n_modes`` vertical natural frequencies [Hz] with the wheel at each of
    ``positions`` [m] (0 <= X <= L); ``method`` is "auto", "dense" or "sparse" (module
    docstring).

    With a ``scene.vehicle`` the positions place the vehicle's reference point (x = 0; every
    wheel must be on the rail) and the modes are those of the rail, the wheels on their
    linearised contact springs and the bodies on their suspensions together (undamped): the
    lowest are the suspension's rigid-body modes (car body ~1 Hz, bogies 5-10 Hz),
    ``body_fraction`` tells them from the track modes.

    ``n_elements`` defaults to the mesh a run of the scene takes
    (:func:`trackwheel.default_settings`: 80 for the paper's scene), so that the modes are the
    run's.

    >>> r = eigen(Scene.kato2005(), [2.5])
    >>> r.frequencies.shape
    (1, 6)
    """
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a trackwheel.Scene, got {type(scene).__name__}")
    x = v.positions("positions", positions, 0.0, scene.rail.length)
    model = kernel.rail_model(scene, _mesh(scene, n_elements))
    if scene.vehicle is not None:
        _dense_only(method)
        return _vehicle_eigen(scene, x, n_modes, model.n_nodes - 1, n_axial)
    n_y = sum(1 for i in model.free_to_full if i % 2 == 1)
    n_sleepers = len(scene.support_positions) if scene.supports.layered else 0
    n_x = sum(1 for i in model.free_to_full if i % 2 == 0)
    n = n_y + 1 + n_sleepers
    sparse = _sparse(method, n)
    # ARPACK finds at most n - 1 modes of an n x n problem
    n_modes = v.integer("n_modes", n_modes, low=1, high=n - 1 if sparse else n)
    # at most the n_x axial modes the mesh has (one element has only one or two)
    n_axial = min(v.integer("n_axial", n_axial, low=0), n_x - 1 if _sparse(method, n_x) else n_x)
    if sparse:
        res = [_sparse_modes(model, 1, n_modes, scene.wheel.mass, scene.contact_stiffness, xi)
               for xi in x]
        freqs = np.array([f for f, _ in res])
        shapes = np.array([s for _, s in res])
    else:
        _check_dense(n)
        freqs, shapes = _core.vertical_modes(model, scene.wheel.mass, scene.contact_stiffness,
                                             x.tolist(), n_modes)
    axial = np.empty(0)
    if n_axial and _sparse(method, n_x):
        axial = _sparse_modes(model, 0, n_axial)[0]
    elif n_axial:
        _check_dense(n_x)
        axial = np.asarray(_core.axial_modes(model, n_axial)[0]).ravel()
    return EigenResult(scene=scene, positions=x, frequencies=np.asarray(freqs),
                       shapes=np.asarray(shapes), axial_frequencies=axial,
                       n_elements=model.n_nodes - 1)


def rail_frequencies(scene: Scene, n_modes: int = 6, *, n_elements: int | None = None,
                     method: str = "auto") -> np.ndarray:
    """Vertical natural frequencies of the rail on its supports without the wheel [Hz]
    (``method`` and the default mesh as in :func:`eigen`)."""
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a trackwheel.Scene, got {type(scene).__name__}")
    model = kernel.rail_model(scene, _mesh(scene, n_elements))
    n_y = sum(1 for i in model.free_to_full if i % 2 == 1)
    n = n_y + (len(scene.support_positions) if scene.supports.layered else 0)
    sparse = _sparse(method, n)
    n_modes = v.integer("n_modes", n_modes, low=1, high=n - 1 if sparse else n)
    if sparse:
        return _sparse_modes(model, 1, n_modes)[0]
    _check_dense(n)
    freqs, _ = _core.vertical_modes(model, 0.0, 0.0, [0.0], n_modes)
    return np.asarray(freqs).ravel()


def vertical_matrices(scene: Scene, *, n_elements: int | None = None):
    """The linear vertical rail's sparse M [kg], C [N s/m] and K [N/m] (scipy CSR) over its free
    y coordinates (y, y_s per node), then the sleepers' z_j on layered supports, at the straight
    reference, with the support and end-zone dampers in C, and the full ANCF index of each rail
    coordinate: ``(M, C, K, dofs)`` (``dofs`` has no entries for the sleepers). The same band
    matrices the linear path integrates (docs: Model § Rail (linearised))."""
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a trackwheel.Scene, got {type(scene).__name__}")
    model = kernel.rail_model(scene, mesh(scene, n_elements))
    d = _core.direction_pencil(model, 1)
    return (*(_csr(d, key) for key in ("M", "C", "K")), np.asarray(d["dofs"]))


def _mesh(scene: Scene, n_elements) -> int:
    """``n_elements`` checked, or the mesh a run of the scene takes by default
    (:func:`trackwheel.run.defaults.derived_mesh`), so that the modes are those of the run."""
    return derived_mesh(scene) if n_elements is None else mesh(scene, n_elements)


def _sparse(method: str, n: int) -> bool:
    v.choice("method", method, set(METHODS))
    return method == "sparse" or (method == "auto" and n > AUTO_SPARSE_DOF)


def _dense_only(method: str) -> None:
    v.choice("method", method, set(METHODS))
    if method == "sparse":
        raise ValueError("method='sparse' is not available with a vehicle; allowed: "
                         "method='dense' or 'auto'")


def _check_dense(n: int) -> None:
    if n > MAX_DENSE_EIGEN_DOF:
        raise ValueError(f"method='dense' takes at most MAX_DENSE_EIGEN_DOF = "
                         f"{MAX_DENSE_EIGEN_DOF} coordinates, this mesh has {n}; allowed: "
                         "method='sparse' or 'auto', or fewer elements")


def _csr(d: dict, key: str):
    from scipy.sparse import csr_matrix

    n = d["n"]
    return csr_matrix((np.asarray(d[key]), (np.asarray(d["row"]), np.asarray(d["col"]))),
                      shape=(n, n))


def _sparse_modes(model, component: int, n_modes: int, wheel_mass: float = 0.0,
                  contact_stiffness: float = 0.0, position: float = 0.0):
    """(frequencies (n_modes,) [Hz], mass-normalised shapes over the full rail coordinates then
    the wheel's Y and the sleepers' z (vertical) or over the rail's (axial)) of the lowest
    ``n_modes`` modes by
    shift-invert Lanczos about 0. The start vector is fixed, so the result is reproducible."""
    from scipy.sparse.linalg import eigsh

    d = _core.direction_pencil(model, component, wheel_mass, contact_stiffness, position)
    K, M = _csr(d, "K").tocsc(), _csr(d, "M").tocsc()
    # A long rail's lowest modes crowd just above the cut-on frequency (hundreds within 1 Hz at
    # 100 m), where shift-invert about 0 barely separates them. So a rough lowest eigenvalue
    # first (a Ritz value of the inverted pencil: an upper bound, here within 1e-6), then the
    # shift below it by the fraction SPARSE_SHIFT: the modes nearest the shift are then the
    # lowest, spread apart 10x more by the inversion than about 0. With a wide basis and a
    # relative tolerance of 1e-12 this takes 200 m of the paper's track from 20 s to 3-5 s.
    v0 = np.ones(d["n"])
    ncv = min(d["n"] - 1, max(2 * n_modes + 1, SPARSE_BASIS))
    lowest = eigsh(K, k=1, M=M, sigma=0.0, which="LM", v0=v0, ncv=min(d["n"] - 1, 20),
                   tol=1e-6, return_eigenvectors=False)[0]
    w2, vec = eigsh(K, k=n_modes, M=M, sigma=lowest * (1.0 - SPARSE_SHIFT), which="LM", v0=v0,
                    ncv=ncv, tol=SPARSE_TOL)
    order = np.argsort(w2)
    w2, vec = w2[order], vec[:, order]
    vec = vec / np.sqrt(np.einsum("ik,ik->k", vec, M @ vec))
    dofs = np.asarray(d["dofs"])
    # local order: rail coordinates, the wheel's Y (with a wheel), the sleepers' z
    nr, wheel = dofs.size, int(wheel_mass > 0.0)
    shapes = np.zeros((model.n_dof + (d["n"] - nr + 1 - wheel if component == 1 else 0), n_modes))
    shapes[dofs] = vec[:nr]
    if component == 1:
        shapes[model.n_dof] = vec[nr] if wheel else 0.0
        shapes[model.n_dof + 1:] = vec[nr + wheel:]
    return np.sqrt(np.maximum(w2, 0.0)) / (2.0 * np.pi), shapes


def _vehicle_eigen(scene: Scene, x: np.ndarray, n_modes: int, ne: int, n_axial: int
                   ) -> EigenResult:
    """:func:`eigen` for a vehicle: K q = omega^2 M q over [rail vertical coords, u, sleepers'
    z_j (layered supports)], every block from the kernel: the track's vertical pencil (rail,
    supports, sleepers), the vehicle's suspension matrices, and the wheels' linearised contact
    springs k coupling Y_A to the rail through its shape functions at each wheel."""
    from scipy.linalg import eigh

    veh = scene.active_vehicle
    model = kernel.rail_model(scene, ne)
    rear, front = veh.span
    if x.min() + rear < 0.0 or x.max() + front > scene.rail.length:
        raise ValueError(f"positions: the vehicle's wheels span x = {rear}..{front} m, so its "
                         f"reference must lie in [{-rear:.4g}, {scene.rail.length - front:.4g}] m")
    K0, M0, vert, nu = _vehicle_pencil(scene, model)
    nr, nw, n = vert.size, veh.n_wheels, K0.shape[0]
    # a body that cannot pitch (every spring under its centre) has a pitch coordinate that
    # nothing couples: left out of the pencil (it would be a 0 Hz mode), zero in the shapes
    free = np.ones(n, dtype=bool)
    for j, unpitched in enumerate(veh.unpitched):
        free[nr + nw + 2 * j + 1] = not unpitched
    n_modes = v.integer("n_modes", n_modes, low=1, high=int(free.sum()))
    kc = scene.contact_stiffness
    e0 = model.reference()
    freqs, shapes, frac = [], [], []
    for x0 in x:
        S = _couplings(model, e0, vert, [x0 + p for p in veh.positions])  # (nw, nr)
        K = K0.copy()
        K[:nr, :nr] += kc * S.T @ S
        K[:nr, nr:nr + nw] = -kc * S.T
        K[nr:nr + nw, :nr] = -kc * S
        K[nr:nr + nw, nr:nr + nw] += kc * np.eye(nw)
        w2, reduced = eigh(K[np.ix_(free, free)], M0[np.ix_(free, free)],
                           subset_by_index=(0, n_modes - 1))
        vec = np.zeros((n, n_modes))
        vec[free] = reduced
        freqs.append(np.sqrt(np.maximum(w2, 0.0)) / (2 * np.pi))
        kin = vec * (M0 @ vec)
        frac.append(kin[nr + nw:nr + nu].sum(axis=0) / kin.sum(axis=0))
        full = np.zeros((model.n_dof + n - nr, n_modes))
        full[vert] = vec[:nr]
        full[model.n_dof:] = vec[nr:]
        shapes.append(full)
    axial = (np.asarray(_core.axial_modes(model, n_axial)[0]).ravel() if n_axial
             else np.empty(0))
    return EigenResult(scene=scene, positions=x, frequencies=np.asarray(freqs),
                       shapes=np.asarray(shapes), axial_frequencies=axial, n_elements=ne,
                       n_vehicle=nu, body_fraction=np.asarray(frac))


def _vehicle_pencil(scene: Scene, model) -> tuple[np.ndarray, np.ndarray, np.ndarray, int]:
    """(K, M, vert, n_u): the dense pencil of the track and the vehicle without the contact
    springs, over [rail vertical coordinates (full indices ``vert``), u (n_u = n_wheels +
    2 n_bodies), sleepers' z_j]: the kernel's vertical track pencil (``direction_pencil``: the
    rail, its supports and sleepers at the straight reference) and its vehicle matrices."""
    veh = scene.active_vehicle
    d = _core.direction_pencil(model, 1)
    vert = np.asarray(d["dofs"])
    nr, nt = vert.size, d["n"]
    nu = veh.n_wheels + 2 * veh.n_bodies
    _check_dense(nt + nu)
    Kv, _, mv = kernel.vehicle_matrices(scene)
    n = nt + nu
    track = np.r_[0:nr, nr + nu:n]  # the track's rows in the assembled order
    K, M = np.zeros((n, n)), np.zeros((n, n))
    K[np.ix_(track, track)] = _csr(d, "K").toarray()
    M[np.ix_(track, track)] = _csr(d, "M").toarray()
    K[nr:nr + nu, nr:nr + nu] = Kv
    M[nr:nr + nu, nr:nr + nu] = np.diag(mv)
    return K, M, vert, nu


def _couplings(model, e0, vert, xs) -> np.ndarray:
    """s(X) over the rail's vertical coordinates at each X in xs: y(X) = s(X) . e (the
    positions are linear in e; each column from a unit vector)."""
    S = np.zeros((len(xs), vert.size))
    for j, i in enumerate(vert):
        unit = np.zeros_like(e0)
        unit[i] = 1.0
        S[:, j] = np.asarray(model.positions(unit, list(xs)))[:, 1]
    return S
