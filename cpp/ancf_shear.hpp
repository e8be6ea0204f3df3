// Planar shear-deformable ANCF beam element (docs: Model, section "Shear-deformable rail
// (Timoshenko)").
//
// Nodal coordinates e_i = [x, y, d_x, d_y] as the cable's, but d is the director of the
// cross-section (its normal; d = r_s when the section does not shear). Element vector
// e = [r_1; d_1; r_2; d_2] (8). Componentwise interpolation with the IIE Timoshenko functions
// (linear_beam.hpp: timoshenko_shapes), phi = 12 EI / (kGA l^2):
//   centre line r(xi) = sum_k w_k(xi) e_k,   director d(xi) = sum_k psi_k(xi) e_k,
// e_k the k-th 2-block of e. At phi = 0, psi_k = dw_k/ds and the element is the cable.
// Strains (invariant under rigid motions, which the interpolation represents exactly):
//   axial   eps   = (r_s.r_s - 1) / 2                          (Green strain, as the cable)
//   bending kappa = (d x d_s) / |d|^3 (exact) or d x d_s (simplified)
//   shear   gamma = (d x r_s) / (d.d)                          (-> w' - psi, linearised)
//   stretch eps_d = (d.d - r_s.r_s) / 2                        (-> d_x - 1 - u', linearised)
// U = 1/2 int (EA eps^2 + EI kappa^2 + kGA gamma^2 + kGA eps_d^2) ds; Q = dU/de and K = d2U/de2
// analytic. The director's length has no meaning of its own (the section turns, it does not
// stretch); without eps_d it entered U only through the centre line's interpolation, with weight
// 1/(1 + phi) ~ l^2, and the rail had a branch of near-free director-stretch modes that softened
// with the mesh (docs: Model, section "Shear-deformable rail (Timoshenko)"). eps_d holds |d| at
// |r_s| with the shear stiffness: linearised, the director's departure from the tangent costs kGA
// |r_s - d|^2 / 2 in either direction (gamma: its turn, eps_d: its length). eps_d vanishes
// identically at phi = 0 (d = r_s, the cable) and has no linear part in y, so the linearised
// element's y part is unchanged.
// Mass M = int (rhoA N^T N + rhoI Psi^T Psi) ds (constant): the rhoI |d_dot|^2 term is the
// rotary inertia rhoI psi_dot^2 of the section, and also gives the director's stretch rate
// d_x_dot a tiny inertia (relative to the axial inertia of a wave of wavenumber k: (r_g k)^2,
// r_g = sqrt(I/A) the radius of gyration).
#pragma once

#include <Eigen/Core>

#include "ancf_cable.hpp"

namespace trackwheel {

struct ShearSection {
  double length;  // element length l [m]
  double EA;      // axial stiffness [N]
  double EI;      // bending stiffness [N m^2]
  double kGA;     // shear stiffness kappa G A [N], > 0
  double rhoA;    // mass per length [kg/m]
  double rhoI;    // rotary inertia per length rho I [kg m]
  bool exact_curvature = true;
  int n_gauss = 5;  // Gauss points per element
  double phi() const { return 12.0 * EI / (kGA * length * length); }
};

// The interpolation at one xi: centre line w (and its s-derivatives), director psi (and psi_s).
struct ShearShapes {
  double w[4], ws[4], wss[4];  // [-, m, -, m] and d/ds, d2/ds2
  double psi[4], psis[4];      // [1/m, -, 1/m, -] and d/ds
};
ShearShapes shear_shapes(const ShearSection& c, double xi);
// The centre line's functions (contact, supports, outputs) in the cable's container.
HermiteValues shear_centre_line(const ShearSection& c, double xi);

struct ShearQuadrature {
  int n = 0;
  double w[10];
  ShearShapes s[10];
};
ShearQuadrature make_shear_quadrature(const ShearSection& c);

// Constant consistent mass M = int (rhoA N^T N + rhoI Psi^T Psi) ds [kg, kg m, kg m^2].
Mat8 shear_mass(const ShearSection& c);

// Elastic force Q = dU/de [N], its Jacobian K [N/m] and the strain energy U [J]; any output
// may be null. quad: optional precomputed quadrature for c.
void shear_elastic(const ShearSection& c, const Vec8& e, Vec8* Q, Mat8* K, double* U,
                   const ShearQuadrature* quad = nullptr);

}  // namespace trackwheel
