// Wheel/rail contact (docs: Model § Contact).
//
// The contact point on the rail is the foot of the normal from the wheel centre R_A:
//   f(s) = (R_A - r(s)) . r_s(s) = 0, solved by Newton from the last s (warm start), moving
// across element boundaries. rho = |R_A - r(s*)|, n = (R_A - r(s*))/rho, penetration
// delta = rho0 - rho, normal force N = k delta (linear contact rigidity, the paper's eq. 22)
// or N = C_H delta^1.5 (Hertz), plus optional damping c * d(delta)/dt, and N = 0 when
// delta <= 0 (unilateral). Forces: +N n on the wheel centre, -S(s*)^T N n on the rail.
//
// With a rail profile (profile.hpp) the wheel touches the running surface
//   p(s) = r(s) + R(x(s)) e_y,  x(s) = r_x(s),
// not the centre line r(s): the search, rho, n and t above use p. Its Jacobian with respect to
// the element coordinates at fixed s is T = dp/de = S + e_y R'(x) S_x (S_x the x row of S), and
// T_s = dT/ds = S_s + e_y (R'' x_s S_x + R' S_x,s). Without a profile p = r and T = S.
//
// Because rho(q) is the distance from R_A to the surface, the elastic part of the contact
// force is the gradient of the potential V(rho(q)) and its Jacobian is symmetric:
//   grad rho = G^T n,  G = [I, -T(s*)]  (q = [X_A, Y_A, e_el(8)]),
//   hess rho = G^T (I - n n^T) G / rho + rho w w^T / f_s - n_y R'' S_x^T S_x (e block),
//   w = G^T p_s / rho + [0; T_s^T n],  f_s = -p_s.p_s + (R_A - p).p_ss.
//
// Element compliance (ContactParams::element_compliance; docs: Model § Contact, "The rail under
// the load between nodes"): the interpolated rail misses the element's own fixed-end deflection
// G(a) N under a load at a between its nodes (linear_beam.hpp: fixed_end_compliance), so the
// law acts in series with G at the contact point's place in its element, a(s*):
//   N_e = N_law(delta - G N_e)   (linear: k delta / (1 + k G); Hertz: a scalar Newton).
// The series spring stores Phi(delta, G) = V_law(delta - G N_e) + G N_e^2 / 2 with
// dPhi/d(delta) = N_e and dPhi/dG = -N_e^2 / 2, so the elastic force is -grad Phi(delta(q),
// G(s*(q))):  F = N grad rho + (N_e^2 / 2) G' ds*/dq  (the second term: the wheel climbing the
// element's deflection as the load moves; ds*/dq ~ [1, 0, ...] makes it mostly horizontal),
// and its Jacobian, with u = grad rho + N_e G' ds*/dq and k_t = dN_e/d(delta) = N_law'/(1 + G
// N_law'), is the Hessian of Phi:
//   K = k_t u u^T - N hess rho - (N_e^2 / 2) (G'' ds*/dq ds*/dq^T + G' d2s*/dq2),
// d2s*/dq2 from the implicit contact condition (contact_parameter_derivatives).
#pragma once

#include <Eigen/Core>

#include "linear_beam.hpp"
#include "rail.hpp"

namespace trackwheel {

using Vec10 = Eigen::Matrix<double, 10, 1>;
using Mat10 = Eigen::Matrix<double, 10, 10>;

enum class ContactLaw { Linear = 0, Hertz = 1 };

struct ContactParams {
  ContactLaw law = ContactLaw::Linear;
  double stiffness = 0.0;  // k [N/m] (linear) or C_H [N/m^1.5] (Hertz)
  double damping = 0.0;    // contact damping c [N s/m]
  double radius = 0.0;     // undeformed wheel radius rho0 [m] (Model::contact_of sets it)
  double friction = 0.0;   // mu, friction coefficient of the slip judgement [-]
  // The rail element's fixed-end compliance G(a) under the load, in series with the law (see
  // above). Off: the law acts on the interpolated rail (the paper's model).
  bool element_compliance = false;
};

// Elastic normal force N_e(delta) [N] and its slope dN_e/d(delta) [N/m] of the law, for the
// full and linear paths alike: k delta (linear, also for delta < 0: the linear path's bilateral
// spring) or C_H delta^1.5 (Hertz, 0 for delta <= 0).
double elastic_normal_force(ContactLaw law, double stiffness, double delta, double& slope);
// Contact potential V(delta) [J] with dV/d(delta) = N_e: k delta^2/2 or 2/5 C_H delta^2.5.
double contact_potential(ContactLaw law, double stiffness, double delta);
// Compression under the static load P [N]: P/k or (P/C_H)^(2/3) [m].
double static_compression(ContactLaw law, double stiffness, double P);
// Stiffness of the law linearised at the static load P: k, or 1.5 C_H^(2/3) P^(1/3) [N/m].
double linearised_stiffness(ContactLaw law, double stiffness, double P);

// The law in series with a compliance G >= 0 [m/N] under the total approach delta [m]:
// N = N_law(delta - G N) (linear: k delta / (1 + k G), also for delta < 0; Hertz: 0 for
// delta <= 0, else Newton on the compression).
struct SeriesForce {
  double N = 0.0;            // elastic normal force [N]
  double slope = 0.0;        // dN/d(delta) at fixed G, N_law' / (1 + G N_law') [N/m]
  double compression = 0.0;  // the law's own compression delta - G N [m]
};
SeriesForce series_normal_force(ContactLaw law, double stiffness, double G, double delta);
// Energy of the series spring Phi = V_law(delta - G N) + G N^2 / 2 [J] (delta > 0 for Hertz).
double series_potential(ContactLaw law, double stiffness, double G, double delta);
// Total approach under the static load P [N]: static_compression + G P [m].
double series_static_approach(ContactLaw law, double stiffness, double G, double P);

struct ContactPoint {
  double s = 0.0;              // contact parameter s* on the rail [m]
  MeshPoint mp;                // its element and shape functions
  Eigen::Vector2d r, rs, rss;  // centre line r(s*), r_s, r_ss
  Eigen::Vector2d p, ps, pss;  // running surface p(s*), p_s, p_ss (= r, r_s, r_ss without profile)
  ProfileValue profile;        // R, R', R'' at x(s*) (zero without profile)
  bool lifted = false;         // a profile is present (T != S)
  double rho = 0.0;            // |R_A - p(s*)| [m]
  Eigen::Vector2d n;           // unit normal, surface -> wheel centre
  Eigen::Vector2d t;           // unit tangent p_s/|p_s|
  double phi = 0.0;            // obliquity of the centre line atan2(y_s, x_s) [rad]
  int iterations = 0;          // Newton iterations of the search
  bool converged = false;
  // The element's fixed-end compliance at s* (G, dG/ds, d2G/ds2: a = s* - the element's start)
  ElementCompliance compliance;
  double nsss[4] = {0.0, 0.0, 0.0, 0.0};           // d3/ds3 of the centre-line functions (constant)
  Eigen::Vector2d psss = Eigen::Vector2d::Zero();  // p_sss(s*)
};

// Newton search for s*, starting from s_guess. Throws std::runtime_error if it fails. The rail's
// profile is read at x + profile_shift (a travelling window: the window's travel since the
// start, the profile being given in the start window's rail coordinate).
ContactPoint find_contact_point(const RailModel& rail, const Eigen::VectorXd& e,
                                const Eigen::Vector2d& RA, double s_guess,
                                double profile_shift = 0.0);

struct ContactForce {
  double delta = 0.0;        // penetration rho0 - rho [m]
  double N = 0.0;            // normal force [N] (>= 0)
  bool active = false;       // N > 0
  double dN_ddelta = 0.0;    // elastic contact stiffness dN/d(delta) at this penetration [N/m]
  bool compliant = false;    // the element compliance is in series (ContactParams)
  double Ne = 0.0;           // the elastic part of N [N]
  double compression = 0.0;  // the law's compression (= delta without element compliance) [m]
  double deflection = 0.0;   // the element's own deflection under the load G N_e, along -n [m]
  double energy = 0.0;       // contact potential (series: Phi above) [J]
  Vec10 dNe_dq;              // d N_e / dq [N/m] (-dN_ddelta grad rho without compliance)
  Vec10 ddeflection_dq;      // d(G N_e)/dq = G dN_e/dq + N_e G' ds*/dq [-] (0 without)
  Vec10 grad_rho;            // d rho / dq
  Vec10 F;                   // generalised contact force on q = [X_A, Y_A, e_el] [N]
  Mat10 K;                   // -dF/dq [N/m] (damping's own q-dependence neglected)
  Mat10 C;                   // -dF/dqdot [N s/m]
};

// Evaluate the contact force at a found contact point; qdot = [V_A; edot_el] (for damping).
// cp.radius is the wheel's radius at the contact (rho0 + its out-of-roundness there) and
// radius_rate its rate of change [m/s], which the contact damper sees too.
ContactForce contact_force(const ContactParams& cp, const ContactPoint& pt, const Vec10& qdot,
                           bool want_jacobian, double radius_rate = 0.0);

// T = dp/de_el at fixed s (2 x 8; S without a profile) and its s-derivative T_s.
Mat28 surface_jacobian(const ContactPoint& pt);
Mat28 surface_jacobian_s(const ContactPoint& pt);

// d rho/dq and the Hessian of rho (exposed for tests).
void distance_derivatives(const ContactPoint& pt, Vec10& grad, Mat10* hess);

// d s*/dq and (if hess) d2 s*/dq2 of the contact parameter, from the implicit contact condition
// f(s, q) = (R_A - p(s)).p_s(s) = 0 (exposed for tests).
void contact_parameter_derivatives(const ContactPoint& pt, Vec10& grad, Mat10* hess);

}  // namespace trackwheel
