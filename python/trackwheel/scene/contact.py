"""The wheel/rail contact law (docs: Model § Contact, § Rolling and slip)."""

from __future__ import annotations

from dataclasses import dataclass

from ..base import validate as v
from ..base.limits import ranges_doc


@dataclass(frozen=True)
class Contact:
    """Wheel/rail contact (docs: Model § Contact, § Rolling and slip).

    ``law="linear"``: N = k (rho0 - rho) (the paper's eq. 22); ``law="hertz"``:
    N = C_H (rho0 - rho)^1.5. ``stiffness=None`` takes the Hertz constant for the wheel on a flat
    rail, C_H = 4/3 E* sqrt(rho0) with 1/E* = (1 - nu_w^2)/E_w + (1 - nu_r^2)/E_r, and for the
    linear law its linearisation at the static load P = F + M g, k = 1.5 C_H^(2/3) P^(1/3)
    (about 7.1e8 N/m for the paper's scene).
    """

    law: str = "linear"  #: "linear" or "hertz"
    stiffness: float | None = None  #: k [N/m] (linear) or C_H [N/m^1.5] (hertz); None: Hertz
    damping: float = 0.0  #: contact damping [N s/m]
    friction: float = 0.3  #: mu, friction coefficient for the slip judgement [-]
    #: the wheel sees the rail profile averaged over its static Hertz patch, length 2a (the 1D
    #: contact filter; :func:`trackwheel.irregularity.contact_half_width` gives a)
    patch_filter: bool = False
    #: add the rail element's own fixed-end compliance G(a) under the load, in series with the
    #: law: the interpolated rail misses the deflection of the element under a load between
    #: its nodes, which on a shear-deformable rail kicks the wheel at every node it crosses
    #: (docs: Model § Contact, "The rail under the load between nodes"). True, False, or None:
    #: on for ``Rail(beam="timoshenko")``, off for "euler" (the paper's model unchanged)
    element_compliance: bool | None = None

    def __post_init__(self):
        v.choice("Contact.law", self.law, {"linear", "hertz"})
        v.boolean("Contact.patch_filter", self.patch_filter)
        if self.element_compliance is not None:
            v.boolean("Contact.element_compliance", self.element_compliance)
        if self.stiffness is not None:
            v.field("Contact.stiffness", self.stiffness,
                    key="Contact.stiffness" if self.law == "linear" else "Contact.stiffness.hertz")
        v.field("Contact.damping", self.damping)
        v.field("Contact.friction", self.friction)



Contact.__doc__ += ranges_doc("Contact")
