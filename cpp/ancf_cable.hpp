// Planar gradient-deficient ANCF "cable" element (docs: Model § Rail).
//
// Nodal coordinates e_i = [x, y, dx/ds, dy/ds]; element vector e = [e_1; e_2] (8).
// r(xi) = S(xi) e with the cubic Hermite functions (Shabana 1998; Gerstmayr & Irschik 2008):
//   s1 = 1 - 3xi^2 + 2xi^3, s2 = l(xi - 2xi^2 + xi^3), s3 = 3xi^2 - 2xi^3, s4 = l(xi^3 - xi^2),
// each multiplying the 2x2 identity, xi = s / l.
// Energies: axial 1/2 int EA eps^2 ds with Green strain eps = (r_s.r_s - 1)/2;
//           bending 1/2 int EI kappa^2 ds with kappa = (r_s x r_ss)/|r_s|^3 (exact, default)
//           or kappa = r_s x r_ss (simplified option).
// The elastic force Q = dU/de and its Jacobian K = d2U/de2 are analytic.
#pragma once

#include <Eigen/Core>

namespace trackwheel {

using Vec8 = Eigen::Matrix<double, 8, 1>;
using Mat8 = Eigen::Matrix<double, 8, 8>;
using Mat28 = Eigen::Matrix<double, 2, 8>;

// The four Hermite functions and their first and second derivatives with respect to s
// (not xi) at xi in [0, 1] for an element of length l [m].
struct HermiteValues {
  double n[4];    // s1..s4 [-, m, -, m]
  double ns[4];   // d/ds
  double nss[4];  // d2/ds2
};
HermiteValues hermite(double xi, double l);

// 2x8 shape-function matrix S(xi) and its s-derivatives.
Mat28 shape_matrix(const double n[4]);

// Gauss-Legendre points and weights on [0, 1] (1 to limits::kMaxGauss points).
void gauss_points(int n, double* xi, double* w);
// Throws std::invalid_argument unless n is an element's Gauss-point count,
// limits::kMinGauss .. limits::kMaxGauss.
void check_gauss(int n);

struct CableSection {
  double length;  // element length l [m]
  double EA;      // axial stiffness [N]
  double EI;      // bending stiffness [N m^2]
  double rhoA;    // mass per length [kg/m]
  bool exact_curvature = true;
  int n_gauss = 5;  // Gauss points per element
};

// Gauss points and shape functions for one element length, computed once and reused.
struct CableQuadrature {
  int n = 0;
  double w[10];
  HermiteValues h[10];
};
CableQuadrature make_quadrature(const CableSection& c);

// Constant consistent mass matrix M = int rhoA S^T S ds [kg].
Mat8 cable_mass(const CableSection& c);

// Elastic force Q = dU/de [N], its Jacobian K = dQ/de [N/m] and the strain energy U [J].
// Any of the outputs may be null.
// quad: optional precomputed quadrature for c (computed on the fly if null).
void cable_elastic(const CableSection& c, const Vec8& e, Vec8* Q, Mat8* K, double* U,
                   const CableQuadrature* quad = nullptr);

// Separate axial and bending parts (for tests and diagnostics).
void cable_axial(const CableSection& c, const Vec8& e, Vec8* Q, Mat8* K, double* U,
                 const CableQuadrature* quad = nullptr);
void cable_bending(const CableSection& c, const Vec8& e, Vec8* Q, Mat8* K, double* U,
                   const CableQuadrature* quad = nullptr);

}  // namespace trackwheel
