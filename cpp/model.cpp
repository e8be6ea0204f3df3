#include "model.hpp"

#include <cmath>

namespace trackwheel {

namespace {
void require(bool ok, const std::string& what, const std::string& range) {
  if (!ok) throw std::invalid_argument(what + " must be " + range);
}
}  // namespace

void check_model(const Model& m) {
  if (m.wheels.empty()) throw std::invalid_argument("the model needs at least one wheel");
  for (int w = 0; w < m.n_wheels(); ++w) {
    const WheelParams& p = m.wheels[w];
    const std::string n = "wheel " + std::to_string(w) + " ";
    require(std::isfinite(p.mass) && p.mass > 0, n + "mass", "> 0 kg");
    require(std::isfinite(p.inertia) && p.inertia > 0, n + "inertia", "> 0 kg m^2");
    require(std::isfinite(p.radius) && p.radius > 0, n + "radius", "> 0 m");
    require(std::isfinite(p.load) && p.load >= 0, n + "load", ">= 0 N");
    require(std::isfinite(p.torque), n + "torque", "finite [N m]");
    require(std::isfinite(p.brake_torque) && p.brake_torque >= 0, n + "brake_torque", ">= 0 N m");
    require(std::isfinite(p.gravity) && p.gravity >= 0, n + "gravity", ">= 0 m/s^2");
    require(std::isfinite(p.x_offset), n + "x_offset", "finite [m]");
  }
  const ContactParams& c = m.contact;
  require(std::isfinite(c.stiffness) && c.stiffness > 0, "contact stiffness", "> 0");
  require(std::isfinite(c.damping) && c.damping >= 0, "contact damping", ">= 0 N s/m");
  require(std::isfinite(c.friction) && c.friction >= 0, "friction", ">= 0");
  check_vehicle(m.vehicle, m.n_wheels());
}

std::vector<double> static_wheel_loads(const Model& m) {
  const int nw = m.n_wheels(), nb = m.n_bodies();
  const Eigen::VectorXd fv =
      nb > 0 ? static_wheel_forces(vehicle_matrices(m.vehicle, nw), Eigen::VectorXd::Zero(nw))
             : Eigen::VectorXd();
  std::vector<double> P;
  for (int w = 0; w < nw; ++w) P.push_back(m.wheels[w].total_load() - (nb > 0 ? fv(w) : 0.0));
  return P;
}

double vertical_kinetic_energy(const Model& m, const SimState& st) {
  double E = 0.0;
  for (int w = 0; w < m.n_wheels(); ++w)
    E += 0.5 * m.wheels[w].mass * st.wheels[w].ydot * st.wheels[w].ydot;
  for (int b = 0; b < m.n_bodies(); ++b)
    E += 0.5 * m.vehicle.bodies[b].mass * st.bodydot(2 * b) * st.bodydot(2 * b);
  return E;
}

}  // namespace trackwheel
