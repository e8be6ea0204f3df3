// Generalized-alpha on the full path (the scheme: ga_scheme.hpp): the true accelerations satisfy
// the equations at t_{n+1}, the algorithmic accelerations a carry the alpha weighting. Newton on
// the analytic iteration matrix with the bordered banded solver; the rolling constraints are
// enforced at velocity level at every step (no drift). A unilateral ballast's sleepers take
// their states at each iterate (System::residual) like a contact that opens: the matrix is
// rebuilt when a state changed, and a step converges only when the states at its converged
// iterate are those it was solved in. With a rail profile or an out-of-round wheel the contact
// force changes within a step, so the contact block is taken new at every iteration through the
// split iteration matrix (system.hpp: no band factorisation); otherwise the whole matrix is kept
// (modified Newton) while the contacts stay near where it was built.
#pragma once

#include <vector>

#include "full_path.hpp"
#include "ga_scheme.hpp"

namespace trackwheel {

class GeneralizedAlpha : public FullStepper {
 public:
  // acc: the accelerations at the start state (the algorithmic ones start equal to them).
  GeneralizedAlpha(System& sys, SimState& st, Eval& ev, Accel& acc, SimOutput& out,
                   const Divergence& div);
  void step(long n) override;
  void record(long n) override { record_sample(n * c_.h); }
  // Test hook: at the iterate x of the step from the current state to t1, the negated residual
  // -r (the right-hand side of J dx = -r, as the Newton loop solves it) and the assembled
  // (unfactorised) iteration matrix J = dr/dx, dense; x = [e''_free, border, z''], and dx the
  // kernel's Newton correction (the sleepers condensed) in that layout.
  void probe(double t1, const Accel& x, Eigen::VectorXd& minus_r, Eigen::MatrixXd& J,
             Eigen::VectorXd& dx);

 private:
  // q_{n+1}, v_{n+1} and the algorithmic accelerations (alg1_) from the iterate x.
  void predict(const SimState& s0, const Accel& acc0, const Accel& x, SimState& s1);
  bool newton(long n, double t1, const SimState& s0, const Accel& acc0, Accel& x, SimState& s1);
  bool matrix_is_stale(const SimState& s1, int it) const;
  void rebuild_matrix(long n, const SimState& s1, const Accel& x, int it);
  int commit_slip_states(Accel& x, SimState& s1, bool& changed);

  const GACoefficients c_;
  const BorderLayout layout_;
  Accel alg_, alg1_;  // algorithmic accelerations and their candidates at the current iterate
  Accel prev_;        // accelerations of the step before (predictor)
  bool have_prev_ = false;
  // the largest contraction at which Newton may stop on its error estimate (newton())
  double theta_max_ = 0.0;
  // The factorised matrix is reused (modified Newton) while every wheel's contact stays in
  // the element, slip state and 5 % of an element it was built at.
  struct MatrixKey {
    int element = -1;
    SlipState state = SlipState::Free;
    double sigma = 0.0, s = 0.0;
    bool locked = false;
  };
  std::vector<MatrixKey> key_;
  long ballast_version_ = -1;  // the sleepers' states the matrix was built in (sleepers.hpp)
  bool have_matrix_ = false;
  bool fresh_contact_ = false;  // a new contact block every iteration (SimSettings::fresh_contact)
  long rail_step_ = 0;          // the step of the rail band's last refresh
  Eigen::VectorXd r1_, r2_, x1_, x2_, dz_, dedd_;
  SimState s0_, s1_;  // the step's start and its iterate
  Accel acc0_, x_;    // the start accelerations and the Newton iterate
};

}  // namespace trackwheel
