// The beam of the linear track (docs: Model § Rail (linearised), § Shear-deformable rail): the
// Euler-Bernoulli Hermite beam (exactly the ANCF element linearised about the straight rail, its
// y coordinates only) or a Timoshenko beam, on the rail's linear supports, as constant band
// matrices over the y coordinates of the ANCF numbering.
//
// Timoshenko element: the two-node "interdependent interpolation element" (IIE; Reddy 1997,
// Friedman & Kosmatka 1993) with nodal DOFs (w, psi), w the deflection and psi the rotation of
// the cross-section; they take the places of (y, y_s) in the ANCF numbering, so the end
// conditions and the band stay those of the Euler-Bernoulli beam. With phi = 12 EI / (kGA l^2)
// and mu = 1 / (1 + phi) the interpolation solves the homogeneous static Timoshenko equations
// exactly, so the stiffness is exact:
//   K = EI mu / l^3 [12, 6l, -12, 6l; 6l, (4+phi) l^2, -6l, (2-phi) l^2; sym: 12, -6l; (4+phi) l^2]
// = the Hessian of U = 1/2 int (EI psi'^2 + kGA (w' - psi)^2) dx. The consistent mass
// M = int (rhoA N_w^T N_w + rhoI N_psi^T N_psi) dx includes the rotary inertia. phi -> 0 (kGA
// -> infinity) recovers the Hermite element.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "banded.hpp"
#include "rail.hpp"

namespace trackwheel {

// The beam theory of the linear track. shear_stiffness = 0 selects Euler-Bernoulli.
struct BeamParams {
  double shear_stiffness = 0.0;  // kappa G A [N]; 0: Euler-Bernoulli (no shear deformation)
  double rotary_inertia = 0.0;   // rho I [kg m], mass moment of inertia per length (Timoshenko)
  bool timoshenko() const { return shear_stiffness > 0.0; }
};

// IIE shape functions at xi in [0, 1] on an element of length l [m], phi = 12 EI / (kGA l^2):
// w = sum w[a] q_a, w' = sum ws[a] q_a, w'' = sum wss[a] q_a, psi = sum psi[a] q_a,
// psi' = sum psis[a] q_a over q = [w1, psi1, w2, psi2].
struct BeamShapes {
  double w[4], ws[4], wss[4], psi[4], psis[4];
};
BeamShapes timoshenko_shapes(double xi, double l, double phi);

// Exact IIE element stiffness [N/m, N, N m] (closed form above).
Eigen::Matrix4d timoshenko_stiffness(double EI, double kGA, double l);
// Consistent IIE element mass [kg, kg m, kg m^2] with rotary inertia (4-point Gauss, exact).
Eigen::Matrix4d timoshenko_mass(double rhoA, double rhoI, double EI, double kGA, double l);
// Element strain energy U(q) = 1/2 int (EI psi'^2 + kGA (w' - psi)^2) dx [J] (4-point Gauss).
double timoshenko_energy(double EI, double kGA, double l, const Eigen::Vector4d& q);

// The element's own compliance under a point load between its nodes (docs: Model § Contact,
// "The rail under the load between nodes"). The element's w functions are exact homogeneous
// static solutions (IIE; the Hermite cubics for Euler-Bernoulli), so under the work-equivalent
// nodal loads S(a)^T P of a point load P at a in [0, l] the nodal values are exact, and the
// exact deflection under the load is the interpolation plus the element's clamped-clamped
// (fixed-end) Green's function at the load point, G(a) P: condensing the exact stiffness of
// the two parts of lengths a and b = l - a at the load point gives, with p = a b and
// phi = 12 EI c_s / l^2 (c_s = 1 / kGA the shear compliance, 0 for Euler-Bernoulli),
//   G(a) = p^3 / (3 EI l^3 (1 + phi)) + c_s p^2 / (l^3 (1 + phi)) + c_s p / l     [m/N],
// l^3/(192 EI) + l/(4 kGA) at mid-element, 0 at the nodes; c_s = 0 leaves the Euler-Bernoulli
// a^3 b^3 / (3 EI l^3).
struct ElementCompliance {
  double G = 0.0;    // G(a) [m/N]
  double Ga = 0.0;   // dG/da [1/N]
  double Gaa = 0.0;  // d2G/da2 [1/(N m)]
};
// EI [N m^2], shear_compliance c_s = 1/kGA [1/N] (0: Euler-Bernoulli), element length l [m],
// load position a in [0, l] [m] (clamped to it).
ElementCompliance fixed_end_compliance(double EI, double shear_compliance, double l, double a);

// Where X lies on the linear beam: element and the w shape functions (and x-derivatives).
struct BeamPoint {
  int element = 0;
  double xi = 0.0;             // local coordinate in [0, 1]
  double n[4], ns[4], nss[4];  // [-, m, 1/m, -, ...]: w(X) = sum n[a] q_a of the element
};
BeamPoint beam_point(const RailModel& rail, const BeamParams& beam, double X);

// The beam on its supports over the y coordinates (full_of_y: y coordinate -> full ANCF index,
// y_of_full the inverse, -1 if fixed): band matrices M [kg], C [N s/m], K [N/m] (half bandwidth
// 3) and the consistent gravity load Qg [N]. Euler-Bernoulli: the y blocks of the ANCF rail's
// matrices at the straight reference.
void linear_beam(const RailModel& rail, const BeamParams& beam, const std::vector<int>& full_of_y,
                 const std::vector<int>& y_of_full, BandMatrix& M, BandMatrix& C, BandMatrix& K,
                 Eigen::VectorXd& Qg);

}  // namespace trackwheel
