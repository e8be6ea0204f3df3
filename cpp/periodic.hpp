// The moving-load receptance matrix of the infinite periodic track (docs: Model § The periodic
// level). The numerical core of trackwheel.periodic: the Python side holds the same formulas
// in numpy (python/trackwheel/periodic/_track.py) for its tests and docs.
//
// Conventions: time dependence exp(+i w t), space exp(+i k X), upward positive. The free rail
// under a travelling force exp(i(k X + w t)) [N/m] has the dynamic stiffness D(k, w) [N/m^2]
// (Euler-Bernoulli: EI k^4 - m w^2; Timoshenko: kappa G A k^2 (EI k^2 - rho I w^2) /
// (EI k^2 + kappa G A - rho I w^2) - m w^2); the supports every d are point springs of
// dynamic stiffness s(w) (single: k + i w c; pad-sleeper-ballast: s_p (s_b - m_s w^2) /
// (s_p + s_b - m_s w^2)); S(k, w) = (1/d) sum_q 1 / D(k + 2 pi q / d, w) is the lattice sum
// (closed form from the partial fractions of 1/D and sum_q 1/(k_q^2 - a^2) =
// (d / 4a) [cot((k - a) d/2) - cot((k + a) d/2)]).
//
// A force exp(i w_m t) moving at v along the track drives the rail under it at w_m + p w_s
// (w_s = 2 pi v / d); with w_m = Omega + m w_s, the displacement harmonic p per force harmonic
// m, read Delta behind/ahead of the force, is
//   A_pm = (1 / 2 pi) int dk exp(i k Delta) I_pm(k),
//   I_pm = d delta_pm h_m + c h_p h_m,  h_q = 1 / (d D(k_q, w')),  c = -d s / (1 + s S),
// at w' = Omega - k v. The integral runs over the real k axis: half Brillouin zones over
// [-K, K] (K = 2 pi (n + 4) / d) and the tails k = +-K / u, u in (0, 1]; the zeros of 1 + s S
// near the real axis (the track's lightly damped Bloch waves, the integrand's only poles) are
// found first and their pole terms subtracted near them and added back exactly; adaptive
// Gauss-Kronrod (7/15) bisection to rtol of the largest entry.
#pragma once

#include <Eigen/Core>
#include <complex>
#include <vector>

namespace trackwheel {

// The periodic track of one bay, SI units.
struct PeriodicTrackParams {
  double bay = 0.6;                // d, support spacing [m]
  double EI = 0.0;                 // bending stiffness [N m^2]
  double mass = 0.0;               // m = rho A [kg/m]
  double shear = 0.0;              // kappa G A [N]; 0: Euler-Bernoulli
  double rotary = 0.0;             // rho I [kg m] (Timoshenko)
  double pad_stiffness = 0.0;      // k_s or k_p [N/m]
  double pad_damping = 0.0;        // c_s or c_p [N s/m]
  double sleeper_mass = 0.0;       // m_s [kg]; 0: single supports
  double ballast_stiffness = 0.0;  // k_b [N/m]
  double ballast_damping = 0.0;    // c_b [N s/m]
};

// Work counts of one periodic_receptance_matrix call (machine-independent costs).
struct PeriodicStats {
  long points = 0;           // integrand evaluations (each: 2n+1 harmonics)
  int poles = 0;             // zeros of 1 + s S subtracted
  int rounds = 0;            // bisection rounds
  long den_evaluations = 0;  // evaluations of 1 + s S while finding the poles
};

// A (one (2n+1) x (2n+1) matrix per offset) [m/N]: the moving-load receptance matrix above for
// harmonics p, m = -n..n at speed v [m/s] (>= 0) and base frequency omega [rad/s] (v > 0 or
// omega != 0), read at each of offsets Delta [m]; converged to rtol of its largest entry.
// Throws std::invalid_argument on bad parameters, std::runtime_error if the quadrature does not
// converge (a nearly undamped wave).
std::vector<Eigen::MatrixXcd> periodic_receptance_matrix(const PeriodicTrackParams& track,
                                                         double speed, double omega, int n,
                                                         const std::vector<double>& offsets,
                                                         double rtol,
                                                         PeriodicStats* stats = nullptr);

// The lattice sum S(k, w) [m/N] (w != 0), for tests of the kernel's closed form.
std::complex<double> periodic_lattice_sum(const PeriodicTrackParams& track, std::complex<double> k,
                                          std::complex<double> w);

}  // namespace trackwheel
