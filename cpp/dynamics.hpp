// Time simulation of the wheels rolling over the flexible rail, the full path (docs: Model § Wheel,
// § Contact, § Rolling and slip, § Equations of motion, § Outputs).
//
// Coordinates: rail e (full ANCF vector; fixed coordinates stay at their reference values),
// per wheel Y_A and theta; X_A(t) = X_0 + x_offset + v t is prescribed (driving constraint; its
// reaction is recorded). The equations and unknowns are in system.hpp, the integrators in
// generalized_alpha.hpp and explicit_rk4.hpp, the time loop in time_loop.hpp and the recorded
// fields in output.hpp.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "model.hpp"
#include "state.hpp"
#include "time_loop.hpp"

namespace trackwheel {

// Runs the whole time loop; initial.wheels has one state per model wheel. Throws
// std::invalid_argument for bad settings or sizes, DivergenceError when the solution diverges.
SimOutput simulate(const Model& model, const SimSettings& settings, const SimState& initial,
                   const ProgressFn& progress = nullptr);

// omega_max [rad/s], the highest natural frequency of the rail linearised at e with every
// wheel on its linearised contact spring at (x[w], y[w]) (power iteration with banded solves).
double highest_frequency(const Model& model, const Eigen::VectorXd& e, const std::vector<double>& x,
                         const std::vector<double>& y);
// The explicit RK4 stability limit 2 sqrt(2)/omega_max [s].
double explicit_stability_limit(double omega_max);

}  // namespace trackwheel
