"""Static equilibrium and the quasi-static contact line (docs: Model § Outputs).

``static`` solves the nonlinear ANCF rail on its supports, under its own weight, with the wheel
held at ``x_wheel`` and pressed down by P = F + M g through the contact law (Newton on the
analytic Jacobian, in the C++ kernel). ``quasi_static`` repeats it along the track and returns
y_qs(X), the line the dynamic contact-point displacement is measured from. The fields of every
static result come from one table, :data:`trackwheel.run.results.STATIC_FIELDS`.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from .. import _core
from ..base import validate as v
from ..base.fields import Quantity, by_name, dataclass_fields, generated_doc
from ..scene import Scene
from . import kernel
from . import profile as rail_profile
from .defaults import mesh
from .results import STATIC_FIELDS, static_from_kernel

_STATIC = by_name(STATIC_FIELDS)
#: the quasi-static line's fields, each an array over the wheel positions
_LINE = ("y_contact", "y_wheel", "contact_s", "normal_force")
#: the rail's state shared by the wheels of a vehicle's static solve
_RAIL = ("rail_coordinates", "sleeper_z", "ballast_force")


def _per_position(name: str, shape: str, rename: str = "") -> Quantity:
    """The static field ``name`` as an array of ``shape`` (named ``rename`` if given)."""
    q = _STATIC[name]
    return dataclasses.replace(q, name=rename or name, doc=f"{q.doc}, {shape}",
                               kind="np.ndarray")


class _StaticMethods:
    def __repr__(self) -> str:
        return (f"<trackwheel.StaticResult: wheel at X = {self.x_wheel:.4g} m, "
                f"{self.n_elements} elements>\n"
                f"  y_contact = {self.y_contact:.6g} m, y_wheel = {self.y_wheel:.6g} m, "
                f"N = {self.normal_force:.6g} N, s* = {self.contact_s:.6g} m "
                f"({self.iterations} Newton iterations)")

    def rail_shape(self, n_points: int = 201) -> tuple[np.ndarray, np.ndarray]:
        """(x, y) of the deflected rail at ``n_points`` material points [m]."""
        n_points = v.integer("n_points", n_points, low=2, high=10**7)
        model = kernel.rail_model(self.scene, self.n_elements)
        s = np.linspace(0.0, self.scene.rail.length, n_points)
        r = model.positions(self.rail_coordinates, s)
        return r[:, 0], r[:, 1]


_STATIC_RESULT = (Quantity("scene", "", "the scene", "Scene"),
                  Quantity("x_wheel", "m", "X_A, where the wheel rests"),
                  *STATIC_FIELDS[:-2], Quantity("n_elements", "", "mesh used", "int"),
                  *STATIC_FIELDS[-2:])
StaticResult = dataclasses.make_dataclass(
    "StaticResult", dataclass_fields(_STATIC_RESULT), bases=(_StaticMethods,), frozen=True,
    repr=False, namespace={"__module__": __name__, "__doc__": generated_doc(
        "The static state with the wheel resting at ``x_wheel``:", _STATIC_RESULT)})


class _LineMethods:
    def __repr__(self) -> str:
        x, y = self.positions, self.y_contact
        return (f"<trackwheel.QuasiStatic: {x.size} wheel positions "
                f"X = {x.min():.4g}..{x.max():.4g} m>\n"
                f"  y_qs = {y.min():.6g}..{y.max():.6g} m, "
                f"N = {self.normal_force.min():.6g}..{self.normal_force.max():.6g} N")


_QUASI_STATIC = (Quantity("positions", "m", "X, the wheel positions, (n,)", "np.ndarray"),
                 *(_per_position(name, "(n,)") for name in _LINE))
QuasiStatic = dataclasses.make_dataclass(
    "QuasiStatic", dataclass_fields(_QUASI_STATIC), bases=(_LineMethods,), frozen=True,
    repr=False, namespace={"__module__": __name__, "__doc__": generated_doc(
        "y_qs(X): the static contact-point displacement with the wheel resting at each X "
        "(``y_contact``):", _QUASI_STATIC)})

_VEHICLE_STATIC = (
    Quantity("x_wheels", "m", "X_A of each wheel, (n_wheels,)", "np.ndarray"),
    _per_position("y_wheel", "(n_wheels,)", "y_wheels"),
    _per_position("y_contact", "(n_wheels,)"),
    _per_position("normal_force", "(n_wheels,): the lever rule's static wheel loads"),
    Quantity("bodies", "", "(n_bodies, 2): z [m], phi [rad] of the bogies, then the car body",
             "np.ndarray"),
    *(_STATIC[name] for name in _RAIL))
VehicleStatic = dataclasses.make_dataclass(
    "VehicleStatic", dataclass_fields(_VEHICLE_STATIC), frozen=True,
    namespace={"__module__": __name__, "__doc__": generated_doc(
        "The static state of a vehicle on the track (the start of "
        ":func:`trackwheel.simulate`); the per-wheel fields are arrays over the wheels:",
        _VEHICLE_STATIC)})


def _check_scene(scene) -> Scene:
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a trackwheel.Scene, got {type(scene).__name__}")
    return scene


def static(scene: Scene, x_wheel: float, *, n_elements: int | None = None) -> StaticResult:
    """Static equilibrium with the wheel centre held at ``x_wheel`` [m] (0 <= x_wheel <= L).

    Returns the deflected rail and the contact-point displacement y_B [m]. With a
    ``scene.vehicle`` this is its derived ``Scene.wheel`` alone (the first wheel under the mean
    static load); :func:`vehicle_static` gives the whole vehicle's static state.
    """
    _check_scene(scene)
    x = v.number("x_wheel", x_wheel, low=0.0, high=scene.rail.length, unit="m")
    ne = mesh(scene, n_elements)
    model = kernel.rail_model(scene, ne)
    d = _core.static_solve(model, kernel.wheel_params(scene), kernel.contact_params(scene), x)
    return StaticResult(scene=scene, x_wheel=x, n_elements=ne,
                        **static_from_kernel(d, (q.name for q in STATIC_FIELDS)))


def quasi_static(scene: Scene, positions, *, n_elements: int | None = None) -> QuasiStatic:
    """The quasi-static line y_qs(X) [m] at each wheel position X [m] (vectorised; each solve
    warm-starts from the previous one), on the full model's rail (with
    ``Rail(beam="timoshenko")`` the shear-deformable ANCF rail; the linear track's line is
    :func:`linear_quasi_static`)."""
    _check_scene(scene)
    x = v.positions("positions", positions, 0.0, scene.rail.length)
    model = kernel.rail_model(scene, mesh(scene, n_elements))
    d = _core.quasi_static(model, kernel.wheel_params(scene), kernel.contact_params(scene),
                           x.tolist())
    return QuasiStatic(positions=x, **{name: np.asarray(d[name]) for name in _LINE})


def vehicle_static(scene: Scene, x_ref: float, *, n_elements: int | None = None
                   ) -> VehicleStatic:
    """Static equilibrium of the scene's vehicle with its reference point (x = 0) at
    ``x_ref`` [m]: the rail under every wheel's static load of the weight distribution at once
    (docs: Model § The vehicle), each body where its springs carry those loads."""
    _check_scene(scene)
    veh = scene.active_vehicle
    rear, front = veh.span
    x = v.number("x_ref", x_ref, low=-rear, high=scene.rail.length - front, unit="m")
    model = kernel.rail_model(scene, mesh(scene, n_elements))
    xs = [x + p for p in veh.positions]
    contacts = []
    for w in veh.wheels:
        c = kernel.contact_params(scene)
        c.radius = w.radius
        contacts.append(c)
    sols = _core.static_solve_wheels(model, kernel.static_wheels_params(scene), contacts, xs)
    y = np.array([d["y_wheel"] for d in sols])
    return VehicleStatic(
        x_wheels=np.asarray(xs), y_wheels=y,
        y_contact=np.array([d["y_contact"] for d in sols]),
        normal_force=np.array([d["normal_force"] for d in sols]),
        bodies=kernel.static_bodies(scene, y).reshape(-1, 2),
        **static_from_kernel(sols[0], _RAIL))


def linear_quasi_static(scene: Scene, positions, *, n_elements: int | None = None,
                        n_modes: int | None = None) -> np.ndarray:
    """The quasi-static line of the linear track (the ``linear/*`` levels): the rail
    displacement y_qs(X) [m] under the wheel at each position X [m], from the linear track's
    own statics K q = Q_g - P s(X) with P = F + M g (docs: Model § Rail (linearised)), for
    the scene's beam theory (Euler-Bernoulli or Timoshenko).

    A linear run starts on this line whatever its contact law (at rest N = P), and it differs
    from :func:`quasi_static`'s ANCF line only by the ANCF model's nonlinearity. ``n_modes``:
    the line of the modal reduction the run used (None: all coordinates). In all coordinates
    it costs O(1) per position after one O(n) pass over the rail (the entries of K^-1 within
    its band, :func:`linear_line_of`): a line over a long rail costs O(L).
    """
    _check_scene(scene)
    x = v.positions("positions", positions, 0.0, scene.rail.length)
    if n_modes is None:
        return linear_line_of(scene, static_rail(scene, n_elements), scene.static_load, x)
    model = kernel.rail_model(scene, mesh(scene, n_elements))
    modes = v.integer("n_modes", n_modes, low=1)
    return np.asarray(_core.linear_static_line(model, kernel.beam_params(scene),
                                               scene.static_load, x.tolist(), modes,
                                               kernel.element_compliance(scene)))


def static_rail(scene: Scene, n_elements: int | None = None,
                support_origin: float = 0.0) -> _core.RailModel:
    """The kernel's rail of ``scene`` for the linear track's statics, which do not read the
    rail profile: without it (building a random profile's table would cost more than the
    line), its supports the track's at X = ``support_origin`` + x [m]."""
    return _core.RailModel(kernel.rail_params(scene, mesh(scene, n_elements)),
                           kernel.support_params(scene, support_origin), _core.Profile())


def linear_line_of(scene: Scene, model, load: float, x: np.ndarray) -> np.ndarray:
    """The linear track's static line [m] in all its coordinates on the kernel rail ``model``
    under ``load`` [N] at the rail coordinates ``x`` [m]: y(X) = s(X) . q_g - P s(X)^T K^-1 s(X)
    from the entries of K^-1 within its band (the selected inverse, one O(n) pass), O(1) per
    position; with a unilateral ballast a solve per position (an active set under each load)."""
    return np.asarray(_core.linear_static_line_selected(
        model, kernel.beam_params(scene), load, np.asarray(x, dtype=float).tolist(),
        kernel.element_compliance(scene)))


def linear_vehicle_line(scene: Scene, x_ref, *, n_elements: int | None = None) -> np.ndarray:
    """(n, n_wheels) [m]: each wheel's static rail displacement under it on the linear track
    (the ``linear/*`` levels' statics, :func:`linear_quasi_static`) with the vehicle's reference
    point at each of ``x_ref`` [m], every wheel under its lever-rule load: the linear track's
    statics superpose, so it is the wheel's own line under its load P_i minus
    sum_j P_j alpha_0(X_i, X_j) over the other wheels, alpha_0 the track's static flexibility
    (the receptance at 0 Hz of the same linear track), from the entries of K^-1 within the
    vehicle's span (O(1) per position after one pass over the rail; a unilateral bed takes
    the receptance position by position)."""
    _check_scene(scene)
    veh = scene.active_vehicle
    rear, front = veh.span
    x_ref = v.positions("x_ref", x_ref, -rear, scene.rail.length - front)
    X = x_ref[:, None] + np.asarray(veh.positions)[None, :]
    return linear_vehicle_line_on(scene, static_rail(scene, n_elements), X)


def linear_vehicle_line_on(scene: Scene, model, X: np.ndarray) -> np.ndarray:
    """:func:`linear_vehicle_line` on the kernel rail ``model`` (:func:`static_rail`) with the
    wheels at its rail coordinates ``X`` (n, n_wheels) [m]: (n, n_wheels) [m]."""
    veh = scene.active_vehicle
    loads = veh.static_loads(scene.gravity)
    beam = kernel.beam_params(scene)
    X = np.asarray(X, dtype=float)
    y = np.empty_like(X)
    for i in range(veh.n_wheels):
        y[:, i] = linear_line_of(scene, model, loads[i], X[:, i])
    nw = veh.n_wheels
    if scene.supports.unilateral:  # the receptance's bilateral bed, position by position
        for k in range(X.shape[0]):
            alpha = np.asarray(_core.receptance(model, beam, X[k].tolist(), X[k].tolist(),
                                                [0.0])).real.reshape(nw, nw)
            # alpha[j, i]: wheel i's displacement under a unit (upward) force at wheel j
            for i in range(nw):
                y[k, i] -= sum(loads[j] * alpha[j, i] for j in range(nw) if j != i)
        return y
    # the same flexibility from the entries of K^-1 within the vehicle's span: O(1) a pair
    pairs = [(i, j) for i in range(nw) for j in range(nw) if j != i]
    if not pairs:
        return y
    xa = np.concatenate([X[:, i] for i, _ in pairs])
    xb = np.concatenate([X[:, j] for _, j in pairs])
    flex = np.asarray(_core.linear_static_flexibility(model, beam, xa.tolist(), xb.tolist()))
    flex = flex.reshape(len(pairs), X.shape[0])
    for i in range(nw):
        y[:, i] -= sum(loads[j] * flex[p] for p, (a, j) in enumerate(pairs) if a == i)
    return y


def rail_axial_load(profile, horizontal_reaction, normal_force, contact_s):
    """The horizontal load the wheels put on the rail [N], which its axial hold carries: the
    forces holding them at their X (``horizontal_reaction`` [N]) less the part the rail
    profile takes, -N R'(s) at each contact point s = ``contact_s`` [m] of the kernel rail
    whose ``profile`` (a ``_core.Profile``) the statics read (the contact reads the profile
    at the place, so a profile's slope tilts the contact force on the wheel without loading
    the rail axially: its force on the rail, -T^T N n with T = S + e_y R' S_x, has the x
    part -N (n_x + R' n_y); n_y = 1 to O(slope^2)). Arrays over the wheels, summed over the
    last axis."""
    H = np.asarray(horizontal_reaction, dtype=float)
    if profile.empty:
        return H.sum(axis=-1)
    s = np.asarray(contact_s, dtype=float)
    slope = np.array([profile(x)[1] for x in s.ravel()]).reshape(s.shape)
    return (H - np.asarray(normal_force) * slope).sum(axis=-1)


def vehicle_line_on(scene: Scene, model, X: np.ndarray) -> np.ndarray:
    """The ANCF statics of the scene's vehicle (:func:`vehicle_static`) on the kernel rail
    ``model`` with its wheels at the rail coordinates of each row of ``X`` (n, n_wheels) [m]:
    each wheel's contact-point displacement y_B [m], (n, n_wheels)."""
    return _vehicle_statics_on(scene, model, X)[0]


def _vehicle_statics_on(scene: Scene, model, X: np.ndarray):
    """:func:`vehicle_line_on`'s y_B [m] and each wheel's horizontal reaction [N], normal
    force [N] and contact point s* [m] on the rail, (n, n_wheels) each. Each row's Newton
    starts from the straight rail (the kernel's vehicle statics take no warm start; they
    converge in 3 iterations from it), so a row's value does not depend on the others."""
    contacts = []
    for w in scene.active_vehicle.wheels:
        c = kernel.contact_params(scene)
        c.radius = w.radius
        contacts.append(c)
    wheels = kernel.static_wheels_params(scene)
    X = np.asarray(X, dtype=float)
    y, H, N, s = (np.empty_like(X) for _ in range(4))
    for k, row in enumerate(X):
        sols = _core.static_solve_wheels(model, wheels, contacts, row.tolist())
        for i, d in enumerate(sols):
            y[k, i], H[k, i] = d["y_contact"], d["horizontal_reaction"]
            N[k, i], s[k, i] = d["normal_force"], d["contact_s"]
    return y, H, N, s


def window_line(scene: Scene, n_elements: int, origin: float, x, linear: bool) -> np.ndarray:
    """The quasi-static line [m] on the scene's own rail (a travelling window's) with the
    supports of the track at X = ``origin`` + x [m], the wheel at the rail coordinates ``x``
    [m]: of the linear track in all its coordinates (``linear``) or of the ANCF model (the
    rail's profile read as on the window's start rail)."""
    x = np.asarray(x, dtype=float)
    if linear:
        return linear_line_of(scene, static_rail(scene, n_elements, origin), scene.static_load,
                              x)
    model = _core.RailModel(kernel.rail_params(scene, n_elements),
                            kernel.support_params(scene, origin),
                            rail_profile.rail_profile(scene))
    return np.asarray(_core.quasi_static(model, kernel.wheel_params(scene),
                                         kernel.contact_params(scene), x.tolist())["y_contact"])


def piece_scene(scene: Scene, n_elements: int, width: int) -> Scene:
    """The scene of a piece of ``width`` bays [-] of the fixed rail of ``scene`` on
    ``n_elements``: its mesh that of the rail, its ends rigid as the rail's (its supports and
    profile those of the rail where the piece stands: :func:`kernel.support_params` and
    :func:`trackwheel.run.profile.profile_part` at its origin)."""
    d = scene.supports.spacing
    epb = n_elements // round(scene.rail.length / d)
    return dataclasses.replace(scene, rail=dataclasses.replace(
        scene.rail, length=width * d, n_elements=width * epb, absorbing_ends=None))


def _piece(scene: Scene, n_elements: int, first: int, width: int):
    """(the scene of the piece of the fixed rail from bay ``first`` over ``width`` bays [-],
    its kernel rail, the rail's profile on it): its supports, profile and mesh those of the
    rail there, its ends rigid as the rail's."""
    origin = first * scene.supports.spacing
    piece = piece_scene(scene, n_elements, width)
    profile = rail_profile.profile_part(scene, origin, width * piece.supports.spacing)
    model = _core.RailModel(kernel.rail_params(piece), kernel.support_params(piece, origin),
                            profile)
    return piece, model, profile


def piece_line(scene: Scene, n_elements: int, first: int, width: int, x):
    """The ANCF quasi-static line [m] of a fixed rail solved on the piece of it from bay
    ``first`` over ``width`` bays [-] (rigid ends, as the rail's), at the piece's rail
    coordinates ``x`` [m] (X - first d): its supports, profile and mesh those of the rail
    there, and the rail's axial load [N] (:func:`rail_axial_load`), each (n,). The wheel's
    static solves warm-start one from the next."""
    piece, model, profile = _piece(scene, n_elements, first, width)
    d = _core.quasi_static(model, kernel.wheel_params(piece), kernel.contact_params(piece),
                           np.asarray(x, dtype=float).tolist())
    H = rail_axial_load(profile, np.asarray(d["horizontal_reaction"])[:, None],
                        np.asarray(d["normal_force"])[:, None],
                        np.asarray(d["contact_s"])[:, None])
    return np.asarray(d["y_contact"]), H


def vehicle_piece_line(scene: Scene, n_elements: int, first: int, width: int,
                       X: np.ndarray):
    """The ANCF statics of the scene's vehicle (:func:`vehicle_line_on`) on the piece of the
    fixed rail from bay ``first`` over ``width`` bays [-] (as :func:`piece_line`), its wheels
    at the piece's rail coordinates of each row of ``X`` (n, n_wheels) [m] (X - first d):
    each wheel's y_B [m], (n, n_wheels), and the rail's axial load (n,) [N]
    (:func:`rail_axial_load`)."""
    piece, model, profile = _piece(scene, n_elements, first, width)
    y, H, N, s = _vehicle_statics_on(piece, model, X)
    return y, rail_axial_load(profile, H, N, s)


def vehicle_window_line(scene: Scene, n_elements: int, origin: float, X: np.ndarray,
                        linear: bool) -> np.ndarray:
    """The vehicle's static line (n, n_wheels) [m] on the scene's own rail (a travelling
    window's) with the supports of the track at X = ``origin`` + x [m], its wheels at the rail
    coordinates of each row of ``X`` (n, n_wheels) [m]: of the linear track in all its
    coordinates (``linear``, :func:`linear_vehicle_line_on`) or of the ANCF model
    (:func:`vehicle_line_on`, the rail's profile read as on the window's start rail, as
    :func:`window_line`)."""
    if linear:
        return linear_vehicle_line_on(scene, static_rail(scene, n_elements, origin), X)
    model = _core.RailModel(kernel.rail_params(scene, n_elements),
                            kernel.support_params(scene, origin),
                            rail_profile.rail_profile(scene))
    return vehicle_line_on(scene, model, X)
