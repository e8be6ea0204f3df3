// Reduced-fidelity fast path: the linear vertical track (docs: Model § Rail (linearised), § Eigen
// analysis).
//
// The rail is the Euler-Bernoulli Hermite beam in y (exactly the ANCF element linearised about the
// straight rail, its y coordinates only), or the Timoshenko beam of linear_beam.hpp, on linear
// supports, with constant mass, damping and
// stiffness matrices: M q'' + C q' + K q = Q_g + s(X)^T F. Optionally it is reduced to its lowest
// n_modes modes (modal superposition, q = Phi z). The wheel acts at X_A(t) = X_0 + v t through
// the shape functions s(X) and is one of:
//   MovingForce  the constant force P = F + M g (no wheel dynamics);
//   MovingMass   the wheel rigidly on the rail: Y_A = y(X_A) + rho0 (multiplier N);
//   Sprung       a linear contact spring N = k (rho0 - Y_A + y(X_A)) (bilateral, linear system);
//   Hertz        N = C_H delta^1.5 for delta > 0, else 0 (unilateral: loss of contact).
// Contact stays vertical at X_A (no obliquity, no contact-point search, no rolling constraint:
// the tangential dynamics do not enter the vertical problem of a straight linear beam).
// Generalized-alpha (Arnold-Bruls form, ga_scheme.hpp) with the constant band part factorised
// once; each wheel and its contact force are a 2-wide border, so a step costs one band solve per
// wheel for the moving coupling (cached per element) plus one for the right-hand side (one
// Newton iteration for the linear levels). The rooms mirror the full path's: the workspace
// (linear_system.hpp, beside system.hpp), the stepper's shared part (linear_path.hpp, beside
// full_path.hpp) and the integrator (linear_alpha.hpp, beside generalized_alpha.hpp); the time
// loop, watchdog and divergence reports are time_loop.hpp's, the contact law contact.hpp's, the
// vehicle's and the sleepers' rows vehicle.hpp's and sleepers.hpp's, as on the full path.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "linear_beam.hpp"
#include "model.hpp"
#include "time_loop.hpp"

namespace trackwheel {

enum class WheelModel { MovingForce = 0, MovingMass = 1, Sprung = 2, Hertz = 3 };

struct LinearOptions {
  WheelModel wheel_model = WheelModel::Sprung;
  int n_modes = 0;           // 0: all coordinates (factorise once); > 0: modal superposition
  bool sudden = false;       // start: false = static equilibrium, true = rail under own weight
  double drop_height = 0.0;  // wheel lifted this much at the start [m]
  BeamParams beam;           // the rail's beam theory (default Euler-Bernoulli)
};

// Every model wheel is of options.wheel_model; wheel w acts at X_0 + x_offset_w + v t.
SimOutput simulate_linear(const Model& model, const SimSettings& settings,
                          const LinearOptions& options, const ProgressFn& progress = nullptr);

// The quasi-static line of the linear track: the rail displacement y(X_i) [m] under the wheel
// load P [N] resting at X_i, for each X_i, from the track's own statics K q = Q_g - P s(X)
// (so a linear run starts on it, whatever its contact law: at rest N = P), sleepers condensed at
// rest. n_modes as in LinearOptions. One band factorisation, then one band solve per position.
// element_compliance: the element's own deflection under the load, G(X) P, included (as the
// linear path's y_contact with ContactParams::element_compliance; contact.hpp).
Eigen::VectorXd linear_static_line(const RailModel& rail, const BeamParams& beam, double load,
                                   const std::vector<double>& x, int n_modes,
                                   bool element_compliance = false);

}  // namespace trackwheel
