// Time integration of the wheel rolling over the flexible rail (MODEL.md §3-§6, §8).
//
// Coordinates: rail e (full ANCF vector; fixed coordinates stay at their reference values),
// wheel Y_A and theta; X_A(t) = X_0 + v t is prescribed (driving constraint; its reaction is
// recorded). Equations of motion (MODEL.md §6):
//   rail   M e''   = Q_g - Q_kl - Q_kt - Q_s + Q_contact + lambda b_rail
//   wheel  M Y_A'' = -(F + M g) + N n_y + lambda t_y
//          J th''  = T - rho lambda
// with lambda the multiplier of the rolling constraint g = t.(V_A - S edot) - rho th' = 0 while
// sticking, or lambda = sigma mu N while sliding (sigma the sign of the friction force), or 0
// without contact.
//
// Integrators (both run the whole time loop in C++):
//  * GeneralizedAlpha: Chung & Hulbert (1993) parameters from the spectral radius rho_inf, in
//    the Arnold & Bruls (2007) form (true accelerations satisfy the equations at t_{n+1}, the
//    algorithmic accelerations a carry the alpha weighting); Newton on the analytic Jacobian
//    with the bordered banded solver; the rolling constraint is enforced at velocity level at
//    every step (no drift).
//  * ExplicitRK4: the paper's way -- the constraint differentiated to acceleration level
//    (paper eqs. 20-21, 25), the index-1 system solved for accelerations and lambda each stage,
//    classical 4th-order Runge-Kutta; optional Baumgarte stabilisation g' + alpha g = 0. Stable
//    for omega_max dt < 2 sqrt(2).
#pragma once

#include <Eigen/Core>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "contact.hpp"
#include "rail.hpp"
#include "wheel.hpp"

namespace trackwheel {

enum class Integrator { GeneralizedAlpha = 0, ExplicitRK4 = 1 };
enum class SlipState { Free = 0, Stick = 1, Slip = 2 };

struct SimSettings {
  Integrator integrator = Integrator::GeneralizedAlpha;
  double speed = 0.0;       // v [m/s]
  double x_start = 0.0;     // X_0 [m]
  double t_end = 0.0;       // duration [s]
  double dt = 1e-5;         // time step [s]
  double rho_inf = 0.8;     // generalized-alpha spectral radius at infinity [-], in [0, 1]
  double baumgarte = 0.0;   // explicit: Baumgarte alpha [1/s] (0 = off)
  double friction = 0.3;    // mu [-]
  bool rolling = true;      // rolling constraint with slip judgement (false: frictionless)
  int output_every = 1;     // keep every n-th step [-]
  int max_newton = 25;      // Newton iterations per step [-]
  double newton_tol = 1e-11;  // Newton tolerance on displacement corrections [m]
  bool record_energy = false;  // record the total mechanical energy per sample
  bool reuse_jacobian = true;  // modified Newton: keep the factorised matrix while it converges
  long progress_every = 2000;  // steps between progress callbacks [-]
};

struct SimState {
  Eigen::VectorXd e, edot;  // rail coordinates (full) and velocities
  double y = 0.0, ydot = 0.0;          // wheel centre height [m] and velocity [m/s]
  double theta = 0.0, thetadot = 0.0;  // rolling angle [rad] and rate [rad/s]
  double s = 0.0;                      // contact parameter warm start [m]
  SlipState state = SlipState::Stick;
  double sigma = 1.0;                  // sign of the sliding friction force on the wheel
};

// Output samples (every output_every steps, plus t = 0).
struct SimOutput {
  std::vector<double> t, x_wheel, y_wheel, ydot_wheel, theta, thetadot, contact_s, y_contact,
      normal_force, tangential_force, slip, v_error, phi, acc_contact, acc_A, acc_B, acc_C, acc_D,
      acc_E, reaction, penetration;
  std::vector<double> energy;  // total mechanical energy [J] (if record_energy)
  std::vector<int> state;    // SlipState per sample
  long steps = 0;            // time steps taken
  long newton_iterations = 0;
  long factorizations = 0;   // Newton matrix factorisations (generalized-alpha)
  long state_changes = 0;
  SimState final_state;
  double stability_limit = 0.0;  // explicit: predicted dt limit [s]
};

class DivergenceError : public std::runtime_error {
 public:
  DivergenceError(const std::string& msg, double time, long step, const std::string& cause)
      : std::runtime_error(msg), time(time), step(step), cause(cause) {}
  double time;
  long step;
  std::string cause;
};

using ProgressFn = std::function<void(long step, long n_steps)>;

// Throws std::invalid_argument for settings no integrator can run (dt, t_end, output_every,
// rho_inf out of range).
void check_settings(const SimSettings& settings);

// A number with 3 significant digits, for error messages.
std::string format3(double x);

SimOutput simulate(const RailModel& rail, const WheelParams& wheel, const ContactParams& contact,
                   const SimSettings& settings, const SimState& initial,
                   const ProgressFn& progress = nullptr);

// Largest eigenvalue omega_max^2 of the linearised rail + wheel-on-contact-spring system at the
// state (power iteration with banded solves); the explicit RK4 limit is 2 sqrt(2)/omega_max.
double highest_frequency(const RailModel& rail, const WheelParams& wheel,
                         const ContactParams& contact, const Eigen::VectorXd& e, double x_wheel,
                         double y_wheel);  // [rad/s]
double explicit_stability_limit(double omega_max);  // [s]

}  // namespace trackwheel
