// The track-and-wheel system's energies (system.hpp): the balance the tests check.
#include <algorithm>
#include <vector>

#include "sleepers.hpp"
#include "system.hpp"
#include "vehicle.hpp"

namespace trackwheel {

double vehicle_energy_of(const Model& model, const SimState& st) {
  Eigen::VectorXd u, udot;
  vehicle_coordinates(st, u, udot);
  return vehicle_energy(vehicle_matrices(model.vehicle, model.n_wheels()), u, udot);
}

double total_energy(const Model& model, const SimState& st, const Eval& ev) {
  const RailModel& rail = model.rail;
  const Eigen::VectorXd v = rail.to_free(st.edot);
  Eigen::VectorXd Mv, Q;
  rail.mass().multiply(v, Mv);
  double U = 0.0;
  rail.internal_force(st.e, nullptr, Q, &U);
  // summed in this order so that one wheel gives the same rounding as the one-wheel kernel
  double E = 0.5 * v.dot(Mv);
  for (int w = 0; w < model.n_wheels(); ++w) {
    const WheelParams& p = model.wheels[w];
    const WheelState& s = st.wheels[w];
    E += 0.5 * p.mass * s.ydot * s.ydot;
    E += 0.5 * p.inertia * s.thetadot * s.thetadot;
  }
  E += U;
  const Sleepers sl(rail);
  if (!sl.empty()) {
    std::vector<int> identity(rail.n_dof());
    for (int i = 0; i < rail.n_dof(); ++i) identity[i] = i;
    E += sl.energy(st.e, identity, st.z, st.zdot);
  }
  for (int w = 0; w < model.n_wheels(); ++w)
    E += ev.w[w].cf.compliant ? ev.w[w].cf.energy
                              : contact_potential(model.contact.law, model.contact.stiffness,
                                                  std::max(ev.w[w].cf.delta, 0.0));
  E -= rail.gravity_force().dot(st.e - rail.reference());
  for (int w = 0; w < model.n_wheels(); ++w) {
    E += model.wheels[w].total_load() * st.wheels[w].y;
    E -= model.wheels[w].torque * st.wheels[w].theta;
  }
  if (model.n_bodies() > 0) E += vehicle_energy_of(model, st);
  return E;
}

double vibration_energy(const Model& model, const SimState& st) {
  const Eigen::VectorXd v = model.rail.to_free(st.edot);
  Eigen::VectorXd Mv;
  model.rail.mass().multiply(v, Mv);
  double E = 0.5 * v.dot(Mv) + vertical_kinetic_energy(model, st);
  if (st.zdot.size() > 0) E += Sleepers(model.rail).kinetic_energy(st.zdot);
  return E;
}

}  // namespace trackwheel
