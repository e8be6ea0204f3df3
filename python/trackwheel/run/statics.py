"""Static equilibrium and the quasi-static contact line (docs: Model § Outputs).

``static`` solves the nonlinear ANCF rail on its supports, under its own weight, with the wheel
held at ``x_wheel`` and pressed down by P = F + M g through the contact law (Newton on the
analytic Jacobian, in the C++ kernel). ``quasi_static`` repeats it along the track and returns
y_qs(X), the line the dynamic contact-point displacement is measured from.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from . import _core, _kernel
from . import _validate as v
from .scene import MAX_ELEMENTS, Scene


@dataclass(frozen=True)
class StaticResult:
    """The static state with the wheel resting at ``x_wheel``."""

    scene: Scene
    x_wheel: float  #: X_A [m]
    y_wheel: float  #: Y_A, wheel-centre height [m]
    contact_s: float  #: s*, rail coordinate of the contact point [m]
    y_contact: float  #: y_B = y(s*), rail displacement under the wheel [m] (negative = down)
    normal_force: float  #: N [N] (equals F + M g)
    rail_coordinates: np.ndarray  #: ANCF coordinates e, (4 (n_e + 1),) [m, m, -, -]
    n_elements: int  #: mesh used
    iterations: int  #: Newton iterations
    #: layered supports: sleeper heights z_j [m] (negative = down), one per support; else empty
    sleeper_z: np.ndarray = field(default_factory=lambda: np.empty(0))
    #: layered supports: ballast force under each sleeper, -k_b z_j [N] (positive =
    #: compression); their sum is the wheel load plus the weight of rail and sleepers on them
    ballast_force: np.ndarray = field(default_factory=lambda: np.empty(0))

    def __repr__(self) -> str:
        return (f"<trackwheel.StaticResult: wheel at X = {self.x_wheel:.4g} m, "
                f"{self.n_elements} elements>\n"
                f"  y_contact = {self.y_contact:.6g} m, y_wheel = {self.y_wheel:.6g} m, "
                f"N = {self.normal_force:.6g} N, s* = {self.contact_s:.6g} m "
                f"({self.iterations} Newton iterations)")

    def rail_shape(self, n_points: int = 201) -> tuple[np.ndarray, np.ndarray]:
        """(x, y) of the deflected rail at ``n_points`` material points [m]."""
        n_points = v.integer("n_points", n_points, low=2, high=10**7)
        model = _kernel.rail_model(self.scene, self.n_elements)
        s = np.linspace(0.0, self.scene.rail.length, n_points)
        r = model.positions(self.rail_coordinates, s)
        return r[:, 0], r[:, 1]


@dataclass(frozen=True)
class QuasiStatic:
    """y_qs(X): static contact-point displacement with the wheel resting at each X."""

    positions: np.ndarray  #: X, (n,) [m]
    y_contact: np.ndarray  #: y_qs, (n,) [m]
    y_wheel: np.ndarray  #: wheel-centre height, (n,) [m]
    contact_s: np.ndarray  #: s*, (n,) [m]
    normal_force: np.ndarray  #: N, (n,) [N]

    def __repr__(self) -> str:
        x, y = self.positions, self.y_contact
        return (f"<trackwheel.QuasiStatic: {x.size} wheel positions "
                f"X = {x.min():.4g}..{x.max():.4g} m>\n"
                f"  y_qs = {y.min():.6g}..{y.max():.6g} m, "
                f"N = {self.normal_force.min():.6g}..{self.normal_force.max():.6g} N")


def _mesh(scene: Scene, n_elements) -> int:
    if n_elements is None:
        return scene.rail.n_elements
    return v.integer("n_elements", n_elements, low=1, high=MAX_ELEMENTS)


def static(scene: Scene, x_wheel: float, *, n_elements: int | None = None) -> StaticResult:
    """Static equilibrium with the wheel centre held at ``x_wheel`` [m] (0 <= x_wheel <= L).

    Returns the deflected rail and the contact-point displacement y_B [m]. With a
    ``scene.vehicle`` this is its derived ``Scene.wheel`` alone (the first wheel under the mean
    static load); :func:`vehicle_static` gives the whole vehicle's static state.
    """
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a trackwheel.Scene, got {type(scene).__name__}")
    x = v.number("x_wheel", x_wheel, low=0.0, high=scene.rail.length, unit="m")
    ne = _mesh(scene, n_elements)
    model = _kernel.rail_model(scene, ne)
    d = _core.static_solve(model, _kernel.wheel_params(scene), _kernel.contact_params(scene), x)
    return StaticResult(scene=scene, x_wheel=x, y_wheel=d["y_wheel"], contact_s=d["contact_s"],
                        y_contact=d["y_contact"], normal_force=d["normal_force"],
                        rail_coordinates=np.asarray(d["e"]), n_elements=ne,
                        iterations=d["iterations"], sleeper_z=np.asarray(d["sleeper_z"]),
                        ballast_force=np.asarray(d["ballast_force"]))


def quasi_static(scene: Scene, positions, *, n_elements: int | None = None) -> QuasiStatic:
    """The quasi-static line y_qs(X) [m] at each wheel position X [m] (vectorised; each solve
    warm-starts from the previous one), on the full model's rail (with
    ``Rail(beam="timoshenko")`` the shear-deformable ANCF rail; the linear track's line is
    :func:`linear_quasi_static`)."""
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a trackwheel.Scene, got {type(scene).__name__}")
    x = v.positions("positions", positions, 0.0, scene.rail.length)
    ne = _mesh(scene, n_elements)
    model = _kernel.rail_model(scene, ne)
    d = _core.quasi_static(model, _kernel.wheel_params(scene), _kernel.contact_params(scene),
                           x.tolist())
    return QuasiStatic(positions=x, y_contact=np.asarray(d["y_contact"]),
                       y_wheel=np.asarray(d["y_wheel"]), contact_s=np.asarray(d["contact_s"]),
                       normal_force=np.asarray(d["normal_force"]))


@dataclass(frozen=True)
class VehicleStatic:
    """The static state of a vehicle on the track (the start of :func:`trackwheel.simulate`)."""

    x_wheels: np.ndarray  #: X_A of each wheel, (n_wheels,) [m]
    y_wheels: np.ndarray  #: Y_A, (n_wheels,) [m]
    y_contact: np.ndarray  #: y_B under each wheel, (n_wheels,) [m]
    normal_force: np.ndarray  #: N = the lever-rule static wheel loads, (n_wheels,) [N]
    bodies: np.ndarray  #: (n_bodies, 2): z [m], phi [rad] of the bogies, then the car body
    rail_coordinates: np.ndarray  #: ANCF coordinates e [m, m, -, -]
    #: layered supports: sleeper heights z_j [m] (negative = down), one per support; else empty
    sleeper_z: np.ndarray = field(default_factory=lambda: np.empty(0))
    #: layered supports: ballast force under each sleeper, -k_b z_j [N] (positive =
    #: compression); their sum is the vehicle's weight plus that of rail and sleepers on them
    ballast_force: np.ndarray = field(default_factory=lambda: np.empty(0))


def vehicle_static(scene: Scene, x_ref: float, *, n_elements: int | None = None
                   ) -> VehicleStatic:
    """Static equilibrium of the scene's vehicle with its reference point (x = 0) at
    ``x_ref`` [m]: the rail under every wheel's static load of the weight distribution at once
    (docs: Model § The vehicle), each body where its springs carry those loads."""
    from .vehicle import static_bodies

    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a trackwheel.Scene, got {type(scene).__name__}")
    veh = scene.active_vehicle
    rear, front = veh.span
    x = v.number("x_ref", x_ref, low=-rear, high=scene.rail.length - front, unit="m")
    model = _kernel.rail_model(scene, _mesh(scene, n_elements))
    xs = [x + p for p in veh.positions]
    contacts = []
    for w in veh.wheels:
        c = _kernel.contact_params(scene)
        c.radius = w.radius
        contacts.append(c)
    sols = _core.static_solve_wheels(model, _kernel.static_wheels_params(scene), contacts, xs)
    y = np.array([d["y_wheel"] for d in sols])
    return VehicleStatic(
        x_wheels=np.asarray(xs), y_wheels=y,
        y_contact=np.array([d["y_contact"] for d in sols]),
        normal_force=np.array([d["normal_force"] for d in sols]),
        bodies=np.asarray(static_bodies(veh, scene.gravity, y)).reshape(-1, 2),
        rail_coordinates=np.asarray(sols[0]["e"]),
        sleeper_z=np.asarray(sols[0]["sleeper_z"]),
        ballast_force=np.asarray(sols[0]["ballast_force"]))


def linear_quasi_static(scene: Scene, positions, *, n_elements: int | None = None,
                        n_modes: int | None = None) -> np.ndarray:
    """The quasi-static line of the linear track (the ``linear/*`` levels): the rail
    displacement y_qs(X) [m] under the wheel at each position X [m], from the linear track's
    own statics K q = Q_g - P s(X) with P = F + M g (docs: Model § Rail (linearised)), for
    the scene's beam theory (Euler-Bernoulli or Timoshenko).

    A linear run starts on this line whatever its contact law (at rest N = P), and it differs
    from :func:`quasi_static`'s ANCF line only by the ANCF model's nonlinearity. ``n_modes``:
    the line of the modal reduction the run used (None: all coordinates).
    """
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a trackwheel.Scene, got {type(scene).__name__}")
    x = v.positions("positions", positions, 0.0, scene.rail.length)
    model = _kernel.rail_model(scene, _mesh(scene, n_elements))
    modes = 0 if n_modes is None else v.integer("n_modes", n_modes, low=1)
    return np.asarray(_core.linear_static_line(model, _kernel.beam_params(scene),
                                                 scene.static_load, x.tolist(), modes))
