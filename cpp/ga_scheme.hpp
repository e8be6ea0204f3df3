// The generalized-alpha scheme (Chung & Hulbert 1993) in the Arnold & Bruls (2007) form, written
// once for both paths (docs: Model § Equations of motion). With the true accelerations q'' and
// the algorithmic ones a, a step from t_n to t_{n+1} = t_n + h is
//   (1 - alpha_m) a_{n+1} + alpha_m a_n = (1 - alpha_f) q''_{n+1} + alpha_f q''_n
//   q_{n+1}  = q_n + h q'_n + h^2 ((1/2 - beta) a_n + beta a_{n+1})
//   q'_{n+1} = q'_n + h ((1 - gamma) a_n + gamma a_{n+1}),
// so q_{n+1} and q'_{n+1} are affine in q''_{n+1}, with slopes cq = beta' h^2 and cv = gamma' h
// (beta' = beta (1 - alpha_f)/(1 - alpha_m), likewise gamma'). Every block of a state (rail,
// wheels, vehicle bodies, sleepers) takes the same update. The full path evaluates it at each
// Newton iterate directly (ga_state_at); the linear path, whose residual is affine in q''_{n+1}
// too, splits it into the predictor at q''_{n+1} = 0 (ga_predictor) and the correction
// cq q''_{n+1}, cv q''_{n+1} (ga_corrector). The two forms agree to round-off, and each path
// keeps its own, so that its results stay what they were bit for bit.
#pragma once

#include "state.hpp"

namespace trackwheel {

// Chung-Hulbert parameters from the spectral radius at infinite frequency rho_inf in [0, 1], and
// the step h [s].
struct GACoefficients {
  GACoefficients(double rho_inf, double h);
  double am, af, gam, bet;  // alpha_m, alpha_f, gamma, beta
  double bp, gp;            // beta' = beta (1 - af)/(1 - am), gamma' = gamma (1 - af)/(1 - am)
  double h, cq, cv;         // h [s], cq = beta' h^2 [s^2], cv = gamma' h [s]
  // d a_{n+1} / d q''_{n+1} = (1 - af)/(1 - am)
  double corrector() const { return (1.0 - af) / (1.0 - am); }
  // a_{n+1} from the true accelerations q''_{n+1}, q''_n and a_n (an Eigen expression or a number)
  template <class T>
  auto algorithmic(const T& qdd1, const T& qdd0, const T& a0) const {
    return (af * qdd0 - am * a0 + (1.0 - af) * qdd1) / (1.0 - am);
  }
  // a_{n+1} at q''_{n+1} = 0 (the predictor's)
  template <class T>
  auto algorithmic_start(const T& qdd0, const T& a0) const {
    return (af * qdd0 - am * a0) / (1.0 - am);
  }
  // q_{n+1}, q'_{n+1} from q_n, q'_n, a_n and a_{n+1}
  template <class T, class Out>
  void newmark(const T& q0, const T& v0, const T& a0, const T& a1, Out& q1, Out& v1) const {
    q1 = q0 + h * v0 + h * h * ((0.5 - bet) * a0 + bet * a1);
    v1 = v0 + h * ((1.0 - gam) * a0 + gam * a1);
  }
};

// The full path's form: the state s1 and its algorithmic accelerations alg1 at the iterate x of
// the true accelerations at t_{n+1}, from the state s0, its true accelerations acc0 and
// algorithmic ones alg0 at t_n. A multiplier has no algorithmic counterpart (alg1's entries 0).
void ga_state_at(const GACoefficients& c, const BorderLayout& b, const SimState& s0,
                 const Accel& acc0, const Accel& alg0, const Accel& x, SimState& s1, Accel& alg1);

// The linear path's form: the predictor p (the state at x = 0) and its algorithmic
// accelerations algp; ga_corrector then gives the state at x (q = p + cq x, q' = p' + cv x),
// ga_corrected_alg its algorithmic accelerations (algp + (1 - af)/(1 - am) x).
void ga_predictor(const GACoefficients& c, const BorderLayout& b, const SimState& s0,
                  const Accel& acc0, const Accel& alg0, SimState& p, Accel& algp);
void ga_corrector(const GACoefficients& c, const BorderLayout& b, const SimState& p, const Accel& x,
                  SimState& s1);
void ga_corrected_alg(const GACoefficients& c, const BorderLayout& b, const Accel& algp,
                      const Accel& x, Accel& alg1);

}  // namespace trackwheel
