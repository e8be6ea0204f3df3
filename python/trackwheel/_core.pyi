"""
trackwheel C++ kernel (ANCF rail, supports, contact, statics, eigen analysis)
"""
from __future__ import annotations
import collections.abc
import numpy
import numpy.typing
import typing
import types
__all__: list[str] = ['BeamParams', 'BodyParams', 'ContactLaw', 'ContactParams', 'ENVELOPE_FIELDS', 'GAUSS_RANGE', 'Integrator', 'LinearOptions', 'MAX_DENSE_EIGEN_DOF', 'MAX_ELEMENTS', 'MAX_SPEED', 'MAX_SUPPORTS', 'OUTPUT_FIELDS', 'PeriodicTrackParams', 'Profile', 'RailModel', 'RailParams', 'SUPPORT_FIELDS', 'SimSettings', 'SimState', 'SlipState', 'SupportParams', 'SuspensionParams', 'VehicleParams', 'WheelModel', 'WheelParams', 'WheelState', 'WindowParams', 'axial_modes', 'contact_eval', 'direction_pencil', 'explicit_stability_limit', 'highest_frequency', 'linear_static_flexibility', 'linear_static_line', 'linear_static_line_selected', 'periodic_receptance_matrix', 'quasi_static', 'rail_static', 'receptance', 'simulate', 'simulate_linear', 'static_bodies', 'static_solve', 'static_solve_wheels', 'testing', 'vehicle_matrices', 'vertical_modes']
class RailParams:
    exact_curvature: bool
    pin_far_end: bool
    def __init__(self) -> None:
        ...
    @property
    def EA(self) -> float:
        ...
    @EA.setter
    def EA(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def EI(self) -> float:
        ...
    @EI.setter
    def EI(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def absorbing_axial_damping(self) -> float:
        """
        c_max,x on the axial motion at the rail ends [N s/m^2]
        """
    @absorbing_axial_damping.setter
    def absorbing_axial_damping(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def absorbing_damping(self) -> float:
        """
        c_max at the rail ends [N s/m^2]
        """
    @absorbing_damping.setter
    def absorbing_damping(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def absorbing_length(self) -> float:
        """
        L_z [m]
        """
    @absorbing_length.setter
    def absorbing_length(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def gravity(self) -> float:
        ...
    @gravity.setter
    def gravity(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def length(self) -> float:
        ...
    @length.setter
    def length(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def n_elements(self) -> int:
        ...
    @n_elements.setter
    def n_elements(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def n_gauss(self) -> int:
        ...
    @n_gauss.setter
    def n_gauss(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def rhoA(self) -> float:
        ...
    @rhoA.setter
    def rhoA(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def rotary_inertia(self) -> float:
        """
        rho I [kg m] (shear-deformable element only)
        """
    @rotary_inertia.setter
    def rotary_inertia(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def shear_stiffness(self) -> float:
        """
        kappa G A [N]; 0: Euler-Bernoulli cable, > 0: shear-deformable element
        """
    @shear_stiffness.setter
    def shear_stiffness(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
class SupportParams:
    def __init__(self) -> None:
        ...
    @property
    def ballast_damping(self) -> list[float]:
        ...
    @ballast_damping.setter
    def ballast_damping(self, arg0: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex]) -> None:
        ...
    @property
    def ballast_stiffness(self) -> list[float]:
        ...
    @ballast_stiffness.setter
    def ballast_stiffness(self, arg0: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex]) -> None:
        ...
    @property
    def damping(self) -> list[float]:
        ...
    @damping.setter
    def damping(self, arg0: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex]) -> None:
        ...
    @property
    def position(self) -> list[float]:
        ...
    @position.setter
    def position(self, arg0: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex]) -> None:
        ...
    @property
    def sleeper_mass(self) -> list[float]:
        ...
    @sleeper_mass.setter
    def sleeper_mass(self, arg0: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex]) -> None:
        ...
    @property
    def stiffness(self) -> list[float]:
        ...
    @stiffness.setter
    def stiffness(self, arg0: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex]) -> None:
        ...
    @property
    def tensionless(self) -> bool:
        """
        every sleeper's ballast unilateral (pushes only)
        """
    @tensionless.setter
    def tensionless(self, arg0: bool) -> None:
        ...
    @property
    def void_gap(self) -> list[float]:
        """
        g_j >= 0 [m] per support (empty: none): the void between sleeper j at rest and its ballast bed; g_j > 0 makes that ballast unilateral
        """
    @void_gap.setter
    def void_gap(self, arg0: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex]) -> None:
        ...
class BeamParams:
    def __init__(self) -> None:
        ...
    @property
    def rotary_inertia(self) -> float:
        """
        rho I [kg m]
        """
    @rotary_inertia.setter
    def rotary_inertia(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def shear_stiffness(self) -> float:
        """
        kappa G A [N]; 0: Euler-Bernoulli
        """
    @shear_stiffness.setter
    def shear_stiffness(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
class Profile:
    """
    Running-surface profile r(X): piecewise cubic on a uniform grid
    """
    def __call__(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> tuple[float, float, float]:
        """
        (r, dr/dX, d2r/dX2) at X
        """
    @typing.overload
    def __init__(self) -> None:
        ...
    @typing.overload
    def __init__(self, x0: typing.SupportsFloat | typing.SupportsIndex, dx: typing.SupportsFloat | typing.SupportsIndex, coefficients: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> None:
        ...
    @typing.overload
    def __init__(self, x0: typing.SupportsFloat | typing.SupportsIndex, dx: typing.SupportsFloat | typing.SupportsIndex, n_intervals: typing.SupportsInt | typing.SupportsIndex, chunks: collections.abc.Iterable) -> None:
        """
        The table from an iterable of (4, m_k) coefficient arrays, m_k summing to n_intervals
        """
    @typing.overload
    def __init__(self, x0: typing.SupportsFloat | typing.SupportsIndex, dx: typing.SupportsFloat | typing.SupportsIndex, n_intervals: typing.SupportsInt | typing.SupportsIndex, chunks: typing.Any, retention: typing.SupportsFloat | typing.SupportsIndex) -> None:
        """
        Streamed: the (4, m_k) coefficient arrays of `chunks` (an iterable, or a callable returning a fresh one) are drawn as X advances and dropped once they end more than `retention` [m] behind the furthest X requested. A request behind the kept range draws a fresh iterable from the callable and reads forwards to it, or raises RuntimeError for a plain iterable. An exception of the iterator surfaces where the profile is read
        """
    @property
    def empty(self) -> bool:
        ...
    @property
    def loaded_intervals(self) -> int:
        """
        intervals held now
        """
    @property
    def n_intervals(self) -> int:
        ...
    @property
    def peak_loaded_intervals(self) -> int:
        """
        the most intervals ever held at once
        """
    @property
    def rewinds(self) -> int:
        """
        times the stream was re-opened
        """
    @property
    def streamed(self) -> bool:
        ...
class WheelParams:
    def __init__(self) -> None:
        ...
    @property
    def brake_torque(self) -> float:
        """
        T_b of the friction brake on the rotation [N m] (0: none)
        """
    @brake_torque.setter
    def brake_torque(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def gravity(self) -> float:
        ...
    @gravity.setter
    def gravity(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def inertia(self) -> float:
        ...
    @inertia.setter
    def inertia(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def load(self) -> float:
        ...
    @load.setter
    def load(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def mass(self) -> float:
        ...
    @mass.setter
    def mass(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def out_of_round(self) -> Profile:
        """
        Delta rho(psi) [m] over one revolution psi in [0, 2 pi] (empty: round)
        """
    @out_of_round.setter
    def out_of_round(self, arg0: Profile) -> None:
        ...
    @property
    def radius(self) -> float:
        ...
    @radius.setter
    def radius(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def torque(self) -> float:
        ...
    @torque.setter
    def torque(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def x_offset(self) -> float:
        """
        X_A - (X_0 + v t), the wheel's place along the vehicle [m]
        """
    @x_offset.setter
    def x_offset(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
class ContactLaw:
    """
    Members:
    
      linear
    
      hertz
    """
    __members__: typing.ClassVar[dict[str, ContactLaw]]
    hertz: typing.ClassVar[ContactLaw]
    linear: typing.ClassVar[ContactLaw]
    @typing.overload
    def __eq__(self, other: ContactLaw) -> bool:
        ...
    @typing.overload
    def __eq__(self, other: typing.Any) -> bool:
        ...
    def __getstate__(self) -> int:
        ...
    def __hash__(self) -> int:
        ...
    def __index__(self) -> int:
        ...
    def __init__(self, value: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __int__(self) -> int:
        ...
    @typing.overload
    def __ne__(self, other: ContactLaw) -> bool:
        ...
    @typing.overload
    def __ne__(self, other: typing.Any) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, state: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __str__(self) -> str:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class ContactParams:
    law: ContactLaw
    def __init__(self) -> None:
        ...
    @property
    def damping(self) -> float:
        ...
    @damping.setter
    def damping(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def element_compliance(self) -> bool:
        """
        the rail element's fixed-end compliance under the load in series with the law (docs: Model § Contact)
        """
    @element_compliance.setter
    def element_compliance(self, arg0: bool) -> None:
        ...
    @property
    def friction(self) -> float:
        """
        mu, slip judgement [-]
        """
    @friction.setter
    def friction(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def radius(self) -> float:
        ...
    @radius.setter
    def radius(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def stiffness(self) -> float:
        ...
    @stiffness.setter
    def stiffness(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
class RailModel:
    @typing.overload
    def __init__(self, arg0: RailParams, arg1: SupportParams) -> None:
        ...
    @typing.overload
    def __init__(self, arg0: RailParams, arg1: SupportParams, arg2: Profile) -> None:
        ...
    def gravity_force(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
    def internal_force(self, arg0: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, 1]"]) -> tuple[typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"], float]:
        ...
    def mass_band_dense(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]:
        ...
    def mass_dense(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]:
        ...
    def positions(self, arg0: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, 1]"], arg1: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex]) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]:
        """
        Rail points r(s) (n, 2) [m] for material coordinates s [m]
        """
    def reference(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
    def tangent_dense(self, arg0: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, 1]"]) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]:
        ...
    @property
    def element_length(self) -> float:
        ...
    @property
    def free_to_full(self) -> list[int]:
        ...
    @property
    def n_dof(self) -> int:
        ...
    @property
    def n_free(self) -> int:
        ...
    @property
    def n_nodes(self) -> int:
        ...
    @property
    def profile(self) -> Profile:
        """
        the rail's profile (a streamed one shares its state)
        """
    @property
    def total_mass(self) -> float:
        ...
class BodyParams:
    def __init__(self) -> None:
        ...
    @property
    def gravity(self) -> float:
        """
        [m/s^2]
        """
    @gravity.setter
    def gravity(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def inertia(self) -> float:
        """
        pitch inertia [kg m^2]
        """
    @inertia.setter
    def inertia(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def load(self) -> float:
        """
        constant downward force on the centre [N]
        """
    @load.setter
    def load(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def mass(self) -> float:
        """
        [kg]
        """
    @mass.setter
    def mass(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
class SuspensionParams:
    def __init__(self) -> None:
        ...
    @property
    def damping(self) -> float:
        """
        c [N s/m]
        """
    @damping.setter
    def damping(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def lower_arm(self) -> float:
        """
        [m]
        """
    @lower_arm.setter
    def lower_arm(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def lower_body(self) -> int:
        """
        body index or -1
        """
    @lower_body.setter
    def lower_body(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def lower_wheel(self) -> int:
        """
        wheel index or -1
        """
    @lower_wheel.setter
    def lower_wheel(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def stiffness(self) -> float:
        """
        k [N/m]
        """
    @stiffness.setter
    def stiffness(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def upper_arm(self) -> float:
        """
        [m]
        """
    @upper_arm.setter
    def upper_arm(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def upper_body(self) -> int:
        """
        body index
        """
    @upper_body.setter
    def upper_body(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
class VehicleParams:
    def __init__(self) -> None:
        ...
    @property
    def bodies(self) -> list[BodyParams]:
        """
        a copy: assign the whole list
        """
    @bodies.setter
    def bodies(self, arg0: collections.abc.Sequence[BodyParams]) -> None:
        ...
    @property
    def suspensions(self) -> list[SuspensionParams]:
        """
        a copy: assign the whole list
        """
    @suspensions.setter
    def suspensions(self, arg0: collections.abc.Sequence[SuspensionParams]) -> None:
        ...
class WindowParams:
    def __init__(self) -> None:
        ...
    @property
    def bay(self) -> float:
        """
        sleeper bay d_s [m]; 0: no window
        """
    @bay.setter
    def bay(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def elements_per_bay(self) -> int:
        """
        [-]
        """
    @elements_per_bay.setter
    def elements_per_bay(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def hold(self) -> float:
        """
        s of the rearmost wheel at a shift [m]
        """
    @hold.setter
    def hold(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def origin(self) -> float:
        """
        track coordinate of s = 0 at t = 0 [m]
        """
    @origin.setter
    def origin(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def supports(self) -> SupportParams:
        """
        the track's supports streamed into the window, one per sleeper from the start window's rear support on (a copy: assign it); empty: the rail's
        """
    @supports.setter
    def supports(self, arg0: SupportParams) -> None:
        ...
class Integrator:
    """
    Members:
    
      generalized_alpha
    
      explicit
    """
    __members__: typing.ClassVar[dict[str, Integrator]]
    explicit: typing.ClassVar[Integrator]
    generalized_alpha: typing.ClassVar[Integrator]
    @typing.overload
    def __eq__(self, other: Integrator) -> bool:
        ...
    @typing.overload
    def __eq__(self, other: typing.Any) -> bool:
        ...
    def __getstate__(self) -> int:
        ...
    def __hash__(self) -> int:
        ...
    def __index__(self) -> int:
        ...
    def __init__(self, value: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __int__(self) -> int:
        ...
    @typing.overload
    def __ne__(self, other: Integrator) -> bool:
        ...
    @typing.overload
    def __ne__(self, other: typing.Any) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, state: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __str__(self) -> str:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class SlipState:
    """
    Members:
    
      free
    
      stick
    
      slip
    """
    __members__: typing.ClassVar[dict[str, SlipState]]
    free: typing.ClassVar[SlipState]
    slip: typing.ClassVar[SlipState]
    stick: typing.ClassVar[SlipState]
    @typing.overload
    def __eq__(self, other: SlipState) -> bool:
        ...
    @typing.overload
    def __eq__(self, other: typing.Any) -> bool:
        ...
    def __getstate__(self) -> int:
        ...
    def __hash__(self) -> int:
        ...
    def __index__(self) -> int:
        ...
    def __init__(self, value: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __int__(self) -> int:
        ...
    @typing.overload
    def __ne__(self, other: SlipState) -> bool:
        ...
    @typing.overload
    def __ne__(self, other: typing.Any) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, state: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __str__(self) -> str:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class SimSettings:
    integrator: Integrator
    record_energy: bool
    reuse_jacobian: bool
    rolling: bool
    def __init__(self) -> None:
        ...
    @property
    def baumgarte(self) -> float:
        ...
    @baumgarte.setter
    def baumgarte(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def dt(self) -> float:
        ...
    @dt.setter
    def dt(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def fresh_contact(self) -> int:
        ...
    @fresh_contact.setter
    def fresh_contact(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def max_newton(self) -> int:
        ...
    @max_newton.setter
    def max_newton(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def newton_tol(self) -> float:
        ...
    @newton_tol.setter
    def newton_tol(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def output_every(self) -> int:
        ...
    @output_every.setter
    def output_every(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def progress_every(self) -> int:
        ...
    @progress_every.setter
    def progress_every(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def record_supports(self) -> bool:
        """
        record each support's forces and sleeper displacement per kept sample (a fixed rail)
        """
    @record_supports.setter
    def record_supports(self, arg0: bool) -> None:
        ...
    @property
    def rho_inf(self) -> float:
        ...
    @rho_inf.setter
    def rho_inf(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def speed(self) -> float:
        ...
    @speed.setter
    def speed(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def t_end(self) -> float:
        ...
    @t_end.setter
    def t_end(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def window(self) -> WindowParams:
        """
        the travelling window (a copy: assign it)
        """
    @window.setter
    def window(self, arg0: WindowParams) -> None:
        ...
    @property
    def x_start(self) -> float:
        ...
    @x_start.setter
    def x_start(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
class WheelState:
    state: SlipState
    def __init__(self) -> None:
        ...
    @property
    def brake_sign(self) -> float:
        """
        sign of the brake torque on the turning wheel (-sign theta')
        """
    @brake_sign.setter
    def brake_sign(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def locked(self) -> bool:
        """
        held by the brake at theta' = 0
        """
    @locked.setter
    def locked(self, arg0: bool) -> None:
        ...
    @property
    def s(self) -> float:
        """
        contact parameter warm start [m]
        """
    @s.setter
    def s(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def sigma(self) -> float:
        """
        sign of the sliding friction force
        """
    @sigma.setter
    def sigma(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def theta(self) -> float:
        """
        rolling angle [rad]
        """
    @theta.setter
    def theta(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def thetadot(self) -> float:
        """
        rolling rate [rad/s]
        """
    @thetadot.setter
    def thetadot(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def y(self) -> float:
        """
        Y_A [m]
        """
    @y.setter
    def y(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def ydot(self) -> float:
        """
        dY_A/dt [m/s]
        """
    @ydot.setter
    def ydot(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
class SimState:
    def __init__(self) -> None:
        ...
    @property
    def body(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        (2 n_bodies,) [z, phi] per vehicle body
        """
    @body.setter
    def body(self, arg0: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, 1]"]) -> None:
        ...
    @property
    def bodydot(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        (2 n_bodies,) rates
        """
    @bodydot.setter
    def bodydot(self, arg0: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, 1]"]) -> None:
        ...
    @property
    def e(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        rail coordinates (n_dof,)
        """
    @e.setter
    def e(self, arg0: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, 1]"]) -> None:
        ...
    @property
    def edot(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        rail velocities (n_dof,)
        """
    @edot.setter
    def edot(self, arg0: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, 1]"]) -> None:
        ...
    @property
    def wheels(self) -> list[WheelState]:
        """
        one WheelState per wheel (a copy: assign the whole list)
        """
    @wheels.setter
    def wheels(self, arg0: collections.abc.Sequence[WheelState]) -> None:
        ...
    @property
    def z(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        sleeper heights (n_sleepers,) [m]; empty: at rest under the initial rail
        """
    @z.setter
    def z(self, arg0: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, 1]"]) -> None:
        ...
    @property
    def zdot(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        sleeper velocities (n_sleepers,) [m/s]
        """
    @zdot.setter
    def zdot(self, arg0: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, 1]"]) -> None:
        ...
class WheelModel:
    """
    Members:
    
      moving_force
    
      moving_mass
    
      sprung
    
      hertz
    """
    __members__: typing.ClassVar[dict[str, WheelModel]]
    hertz: typing.ClassVar[WheelModel]
    moving_force: typing.ClassVar[WheelModel]
    moving_mass: typing.ClassVar[WheelModel]
    sprung: typing.ClassVar[WheelModel]
    @typing.overload
    def __eq__(self, other: WheelModel) -> bool:
        ...
    @typing.overload
    def __eq__(self, other: typing.Any) -> bool:
        ...
    def __getstate__(self) -> int:
        ...
    def __hash__(self) -> int:
        ...
    def __index__(self) -> int:
        ...
    def __init__(self, value: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __int__(self) -> int:
        ...
    @typing.overload
    def __ne__(self, other: WheelModel) -> bool:
        ...
    @typing.overload
    def __ne__(self, other: typing.Any) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, state: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __str__(self) -> str:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class LinearOptions:
    beam: BeamParams
    sudden: bool
    wheel_model: WheelModel
    def __init__(self) -> None:
        ...
    @property
    def drop_height(self) -> float:
        ...
    @drop_height.setter
    def drop_height(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def n_modes(self) -> int:
        ...
    @n_modes.setter
    def n_modes(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
class PeriodicTrackParams:
    def __init__(self) -> None:
        ...
    @property
    def EI(self) -> float:
        """
        bending stiffness [N m^2]
        """
    @EI.setter
    def EI(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def ballast_damping(self) -> float:
        """
        c_b [N s/m]
        """
    @ballast_damping.setter
    def ballast_damping(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def ballast_stiffness(self) -> float:
        """
        k_b [N/m]
        """
    @ballast_stiffness.setter
    def ballast_stiffness(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def bay(self) -> float:
        """
        d, support spacing [m]
        """
    @bay.setter
    def bay(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def mass(self) -> float:
        """
        rho A [kg/m]
        """
    @mass.setter
    def mass(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def pad_damping(self) -> float:
        """
        c_s or c_p [N s/m]
        """
    @pad_damping.setter
    def pad_damping(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def pad_stiffness(self) -> float:
        """
        k_s or k_p [N/m]
        """
    @pad_stiffness.setter
    def pad_stiffness(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def rotary(self) -> float:
        """
        rho I [kg m]
        """
    @rotary.setter
    def rotary(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def shear(self) -> float:
        """
        kappa G A [N]; 0: Euler-Bernoulli
        """
    @shear.setter
    def shear(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def sleeper_mass(self) -> float:
        """
        m_s [kg]; 0: single
        """
    @sleeper_mass.setter
    def sleeper_mass(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
def axial_modes(rail: RailModel, n_modes: typing.SupportsInt | typing.SupportsIndex) -> tuple:
    """
    Axial modes of the rail: (frequencies (1, n_modes) [Hz], shapes (1, n_dof, n_modes))
    """
def contact_eval(arg0: RailModel, arg1: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, 1]"], arg2: typing.SupportsFloat | typing.SupportsIndex, arg3: typing.SupportsFloat | typing.SupportsIndex, arg4: typing.SupportsFloat | typing.SupportsIndex, arg5: ContactParams, arg6: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[10, 1]"]) -> dict:
    """
    Contact point and force for q = [X_A, Y_A, e_el]
    """
def direction_pencil(rail: RailModel, component: typing.SupportsInt | typing.SupportsIndex, wheel_mass: typing.SupportsFloat | typing.SupportsIndex = 0.0, contact_stiffness: typing.SupportsFloat | typing.SupportsIndex = 0.0, position: typing.SupportsFloat | typing.SupportsIndex = 0.0) -> dict:
    """
    K [N/m], M [kg], C [N s/m] of one direction (0: x, 1: y with the wheel if wheel_mass > 0) at the straight reference as triplets {n, dofs, row, col, K, M, C} over local coordinates (the direction's free coordinates, full indices in dofs, then the wheel's Y_w and the sleepers' z_j on layered supports)
    """
def explicit_stability_limit(arg0: typing.SupportsFloat | typing.SupportsIndex) -> float:
    """
    The explicit RK4 stability limit 2 sqrt(2) / omega_max [s] for omega_max [rad/s]
    """
def highest_frequency(arg0: RailModel, arg1: WheelParams, arg2: ContactParams, arg3: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, 1]"], arg4: typing.SupportsFloat | typing.SupportsIndex, arg5: typing.SupportsFloat | typing.SupportsIndex) -> float:
    """
    omega_max [rad/s] of the linearised rail + wheel-on-contact-spring system
    """
def linear_static_flexibility(rail: RailModel, beam: BeamParams, xa: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], xb: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex]) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
    """
    The linear track's static flexibility s(xa_k)^T K^-1 s(xb_k) [m/N] for each pair k (the receptance at 0 Hz), from the entries of K^-1 within the pairs' largest coordinate distance: O(1) per pair after one pass over the rail.
    """
def linear_static_line(rail: RailModel, beam: BeamParams, load: typing.SupportsFloat | typing.SupportsIndex, x: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], n_modes: typing.SupportsInt | typing.SupportsIndex = 0, element_compliance: bool = False) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
    """
    Quasi-static line of the linear track: y(X_i) [m] under the load P [N] resting at each X_i [m] (K q = Q_g - P s(X)); n_modes > 0: of its modal reduction; element_compliance: the element's own deflection under the load G(X_i) P included.
    """
def linear_static_line_selected(rail: RailModel, beam: BeamParams, load: typing.SupportsFloat | typing.SupportsIndex, x: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], element_compliance: bool = False) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
    """
    linear_static_line in all coordinates from the selected inverse of K (the entries of K^-1 within its band): O(1) per position after one factorisation; a unilateral ballast falls back to a solve per position.
    """
def periodic_receptance_matrix(track: PeriodicTrackParams, speed: typing.SupportsFloat | typing.SupportsIndex, omega: typing.SupportsFloat | typing.SupportsIndex, n: typing.SupportsInt | typing.SupportsIndex, offsets: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], rtol: typing.SupportsFloat | typing.SupportsIndex, stats: bool = False) -> typing.Any:
    """
    Moving-load receptance matrices (n_offsets, 2n+1, 2n+1) [m/N] of the periodic track; with stats=True also the work counts {points, poles, rounds, den_evaluations}
    """
def quasi_static(rail: RailModel, wheel: WheelParams, contact: ContactParams, x: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex]) -> dict:
    """
    The quasi-static line: a static solve at each X_A in x [m], each from the rail of the one before; {'y_contact', 'y_wheel', 'contact_s' [m], 'normal_force', 'horizontal_reaction' [N]} (n,) each
    """
def rail_static(rail: RailModel) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
    """
    The rail's coordinates e (n_dof,) at rest under its own weight, no wheel
    """
def receptance(rail: RailModel, beam: BeamParams, x: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], x_response: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], freqs: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex]) -> typing.Annotated[numpy.typing.NDArray[numpy.complex128], "[m, n]"]:
    """
    Receptances (n_freq, n_force * n_resp) [m/N] of the linear track, a unit force at each of x (column e * n_resp + r: response r to force e)
    """
def simulate(rail: RailModel, wheels: collections.abc.Sequence[WheelParams], contact: ContactParams, settings: SimSettings, initial: SimState, progress: typing.Any = None, vehicle: VehicleParams = ...) -> dict:
    """
    Run the whole time loop in C++ (GIL released; progress(step, n_steps) called every settings.progress_every steps with the GIL held, which also checks for Ctrl-C). Returns {field: array} for every OUTPUT_FIELDS row (per-wheel fields (n_samples, n_wheels)), every SUPPORT_FIELDS row ((n_samples, n_supports) if settings.record_supports, else None), support_envelope ({ENVELOPE_FIELDS name: (n_supports_seen,)}), the vehicle's body_z, body_phi (n_samples, n_bodies), the counters steps, newton_iterations, factorizations (band_factorizations, band_solves), state_changes, stability_limit, final_state
    """
def simulate_linear(rail: RailModel, wheels: collections.abc.Sequence[WheelParams], contact: ContactParams, settings: SimSettings, options: LinearOptions, progress: typing.Any = None, vehicle: VehicleParams = ...) -> dict:
    """
    Linear vertical track fast path (Euler-Bernoulli or Timoshenko rail, constant matrices)
    """
def static_bodies(vehicle: VehicleParams, y_wheels: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, 1]"]) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
    """
    [z_0, phi_0, z_1, phi_1, ...] [m, rad] of the bodies in static equilibrium above wheel centres held at heights y_wheels [m]: the bodies' rows of K_v u = -G (vehicle.hpp)
    """
def static_solve(rail: RailModel, wheel: WheelParams, contact: ContactParams, x_wheel: typing.SupportsFloat | typing.SupportsIndex) -> dict:
    """
    Static equilibrium of the wheel at X_A = x_wheel [m] on the rail under its load F + M g: {'e' (n_dof,), 'x_wheel', 'y_wheel', 'contact_s' [m], 'y_contact' [m] (the rail under the load), 'normal_force', 'horizontal_reaction' [N], 'iterations', 'sleeper_z' [m], 'ballast_force' [N]}
    """
def static_solve_wheels(rail: RailModel, wheels: collections.abc.Sequence[WheelParams], contacts: collections.abc.Sequence[ContactParams], x_wheels: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex]) -> list:
    """
    Static equilibrium of several wheels on the rail, wheel w at x_wheels[w] under its load F + M g: one static_solve dict per wheel (the same rail e in each)
    """
def vehicle_matrices(vehicle: VehicleParams, n_wheels: typing.SupportsInt | typing.SupportsIndex) -> dict:
    """
    The vehicle's constant matrices over u = [Y_A per wheel, (z, phi) per body] (vehicle.hpp): {'K' [N/m], 'C' [N s/m]: sum k g g^T, sum c g g^T over the suspensions; 'mass': the bodies' masses [kg] and pitch inertias [kg m^2], the wheels' entries 0; 'G': the bodies' weights and loads [N]}
    """
def vertical_modes(rail: RailModel, wheel_mass: typing.SupportsFloat | typing.SupportsIndex, contact_stiffness: typing.SupportsFloat | typing.SupportsIndex, positions: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], n_modes: typing.SupportsInt | typing.SupportsIndex) -> tuple:
    """
    Vertical modes of the rail with the wheel (mass M [kg] on the contact spring k [N/m]) at each position [m]: (frequencies (n_pos, n_modes) [Hz], shapes (n_pos, n_dof + 1 + n_sleepers, n_modes))
    """
ENVELOPE_FIELDS: tuple = (('x', 'm', "X_j, the support's track coordinate"), ('ballast_force_max', 'N', 'largest ballast force (compression positive)'), ('ballast_force_min', 'N', 'smallest ballast force (negative: the bed pulls)'), ('rail_seat_force_max', 'N', 'largest rail-seat force (compression positive)'), ('rail_seat_force_min', 'N', 'smallest rail-seat force (negative: the pad pulls)'), ('sleeper_z_min', 'm', "the sleeper's largest downward displacement, min z"), ('contact_time', 's', 'time the ballast carried load (ballast force > 0)'), ('observed_time', 's', "time the support was in the rail (a travelling window's share)"))
GAUSS_RANGE: tuple = (2, 10)
MAX_DENSE_EIGEN_DOF: int = 4000
MAX_ELEMENTS: int = 20000
MAX_SPEED: float = 300.0
MAX_SUPPORTS: int = 100000
OUTPUT_FIELDS: tuple = (('t', 's', 'time', False, 'float64'), ('x_wheel', 'm', 'X_A, wheel-centre position (prescribed X_0 + v t)', True, 'float64'), ('y_wheel', 'm', 'Y_A, wheel-centre height', True, 'float64'), ('ydot_wheel', 'm/s', 'dY_A/dt', True, 'float64'), ('theta', 'rad', 'rolling angle', True, 'float64'), ('thetadot', 'rad/s', 'rolling rate', True, 'float64'), ('contact_s', 'm', 's*, rail coordinate of the contact point', True, 'float64'), ('y_contact', 'm', 'y_B = y(s*), rail displacement under the wheel', True, 'float64'), ('normal_force', 'N', 'N, normal contact force (0 without contact)', True, 'float64'), ('tangential_force', 'N', 'lambda, tangential contact force on the wheel', True, 'float64'), ('slip', 'm/s', 'slip velocity t.(V_A - S edot) - rho thetadot', True, 'float64'), ('slip_state', '', '0 no contact, 1 stick, 2 slide', True, 'int32'), ('v_error', '%', "paper's eq. 28, (dX/dt - rho dtheta/dt)/(dX/dt) 100", True, 'float64'), ('phi', 'rad', 'rail obliquity at the contact point', True, 'float64'), ('acc_contact', 'm/s^2', "vertical acceleration of the contact point d2 y_B/dt2 = S_y e'' + 2 s' S_y,s e' + s'^2 y_ss (s'' y_s neglected)", True, 'float64'), ('acc_A', 'm/s^2', "rho cos(phi) theta' v phi_s (docs: Model § Outputs)", True, 'float64'), ('acc_B', 'm/s^2', "rho cos(phi) theta' phi_t", True, 'float64'), ('acc_C', 'm/s^2', 'rho cos(phi) v^2 phi_s^2', True, 'float64'), ('acc_D', 'm/s^2', 'rho cos(phi) phi_t^2', True, 'float64'), ('acc_E', 'm/s^2', '2 rho cos(phi) phi_t v phi_s', True, 'float64'), ('reaction', 'N', 'horizontal force holding X_A = X_0 + v t', True, 'float64'), ('penetration', 'm', 'rho0 - rho (negative: gap)', True, 'float64'), ('energy', 'J', 'total mechanical energy (recorded on request only)', False, 'float64'))
SUPPORT_FIELDS: tuple = (('rail_seat_force', 'N', "rail-seat force of each support, the pad's compression -(k_p (y - z) + c_p (y' - z')) (single springs: -(k_s y + c_s y'))"), ('ballast_force', 'N', "ballast force under each sleeper, the bed's compression -(k_b z + c_b z') (over a void or tensionless: k_b d + c_b d', d = -z - g, on its bed, 0 off it; single springs: the spring's force)"), ('sleeper_z', 'm', "each sleeper's displacement z (up positive; 0 for single springs)"))
#: The test-only probes and benchmark hooks of the kernel (not public API, no stubs).
testing: types.ModuleType
