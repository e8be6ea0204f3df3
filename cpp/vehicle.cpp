#include "vehicle.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <stdexcept>
#include <string>

namespace trackwheel {

namespace {
void require(bool ok, const std::string& what, const std::string& range) {
  if (!ok) throw std::invalid_argument(what + " must be " + range);
}

// g_s: the extension's gradient over u
Eigen::VectorXd extension_gradient(const SuspensionParams& s, int nw, int nu) {
  Eigen::VectorXd g = Eigen::VectorXd::Zero(nu);
  g(nw + 2 * s.upper_body) += 1.0;
  g(nw + 2 * s.upper_body + 1) += s.upper_arm;
  if (s.lower_wheel >= 0) {
    g(s.lower_wheel) -= 1.0;
  } else {
    g(nw + 2 * s.lower_body) -= 1.0;
    g(nw + 2 * s.lower_body + 1) -= s.lower_arm;
  }
  return g;
}
}  // namespace

void check_vehicle(const VehicleParams& v, int nw) {
  const int nb = v.n_bodies();
  for (int b = 0; b < nb; ++b) {
    const BodyParams& p = v.bodies[b];
    const std::string n = "body " + std::to_string(b) + " ";
    require(std::isfinite(p.mass) && p.mass > 0, n + "mass", "> 0 kg");
    require(std::isfinite(p.inertia) && p.inertia > 0, n + "inertia", "> 0 kg m^2");
    require(std::isfinite(p.gravity) && p.gravity >= 0, n + "gravity", ">= 0 m/s^2");
    require(std::isfinite(p.load) && p.load >= 0, n + "load", ">= 0 N");
  }
  for (std::size_t i = 0; i < v.suspensions.size(); ++i) {
    const SuspensionParams& s = v.suspensions[i];
    const std::string n = "suspension " + std::to_string(i) + " ";
    require(std::isfinite(s.stiffness) && s.stiffness > 0, n + "stiffness", "> 0 N/m");
    require(std::isfinite(s.damping) && s.damping >= 0, n + "damping", ">= 0 N s/m");
    require(s.upper_body >= 0 && s.upper_body < nb, n + "upper_body",
            "in [0, " + std::to_string(nb) + ")");
    const bool wheel = s.lower_wheel >= 0 && s.lower_wheel < nw && s.lower_body < 0;
    const bool body =
        s.lower_wheel < 0 && s.lower_body >= 0 && s.lower_body < nb && s.lower_body != s.upper_body;
    require(wheel || body, n + "lower end",
            "one wheel in [0, " + std::to_string(nw) + ") or one other body in [0, " +
                std::to_string(nb) + ")");
    require(std::isfinite(s.lower_arm) && std::isfinite(s.upper_arm), n + "arms", "finite [m]");
  }
}

double vehicle_weight(const VehicleParams& v) {
  double W = 0.0;
  for (const BodyParams& b : v.bodies) W += b.mass * b.gravity + b.load;
  return W;
}

VehicleMatrices vehicle_matrices(const VehicleParams& v, int nw) {
  const int nb = v.n_bodies(), nu = nw + 2 * nb;
  VehicleMatrices vm;
  vm.n_wheels = nw;
  vm.K = Eigen::MatrixXd::Zero(nu, nu);
  vm.C = Eigen::MatrixXd::Zero(nu, nu);
  vm.mass = Eigen::VectorXd::Zero(nu);
  vm.G = Eigen::VectorXd::Zero(nu);
  for (int b = 0; b < nb; ++b) {
    vm.mass(nw + 2 * b) = v.bodies[b].mass;
    vm.mass(nw + 2 * b + 1) = v.bodies[b].inertia;
    vm.G(nw + 2 * b) = v.bodies[b].mass * v.bodies[b].gravity + v.bodies[b].load;
  }
  for (const SuspensionParams& s : v.suspensions) {
    const Eigen::VectorXd g = extension_gradient(s, nw, nu);
    vm.K += s.stiffness * g * g.transpose();
    vm.C += s.damping * g * g.transpose();
  }
  return vm;
}

Eigen::VectorXd vehicle_forces(const VehicleMatrices& vm, const Eigen::VectorXd& u,
                               const Eigen::VectorXd& udot) {
  return -(vm.K * u + vm.C * udot + vm.G);
}

double vehicle_energy(const VehicleMatrices& vm, const Eigen::VectorXd& u,
                      const Eigen::VectorXd& udot) {
  const int nw = vm.n_wheels;
  const auto vb = udot.tail(udot.size() - nw);
  const double kinetic = 0.5 * vb.dot(vm.mass.tail(vb.size()).cwiseProduct(vb));
  return kinetic + 0.5 * u.dot(vm.K * u) + vm.G.dot(u);
}

Eigen::VectorXd static_bodies(const VehicleMatrices& vm, const Eigen::VectorXd& Y) {
  const int nw = vm.n_wheels, m = static_cast<int>(vm.G.size()) - nw;
  const Eigen::MatrixXd Kbb = vm.K.bottomRightCorner(m, m);
  const Eigen::VectorXd rhs = -vm.G.tail(m) - vm.K.bottomLeftCorner(m, nw) * Y;
  return Kbb.completeOrthogonalDecomposition().solve(rhs);
}

Eigen::VectorXd static_wheel_forces(const VehicleMatrices& vm, const Eigen::VectorXd& Y) {
  const int nw = vm.n_wheels;
  Eigen::VectorXd u(vm.G.size());
  u.head(nw) = Y;
  u.tail(u.size() - nw) = static_bodies(vm, Y);
  return vehicle_forces(vm, u, Eigen::VectorXd::Zero(u.size())).head(nw);
}

void vehicle_coordinates(const SimState& st, Eigen::VectorXd& u, Eigen::VectorXd& udot) {
  const int nw = static_cast<int>(st.wheels.size()), nb2 = static_cast<int>(st.body.size());
  u.resize(nw + nb2);
  udot.resize(nw + nb2);
  for (int w = 0; w < nw; ++w) {
    u(w) = st.wheels[w].y;
    udot(w) = st.wheels[w].ydot;
  }
  u.tail(nb2) = st.body;
  udot.tail(nb2) = st.bodydot;
}

VehicleRows::VehicleRows(const VehicleParams& vehicle, const BorderLayout& layout)
    : vm_(vehicle_matrices(vehicle, layout.n_wheels)), layout_(layout) {}

void VehicleRows::add_forces(const SimState& st, Eigen::VectorXd& fb) const {
  vehicle_coordinates(st, u_, udot_);
  fu_ = vehicle_forces(vm_, u_, udot_);
  for (int i = 0; i < fu_.size(); ++i) fb(layout_.vehicle(i)) += fu_(i);
}

void VehicleRows::body_residual(const Eigen::VectorXd& x, const Eigen::VectorXd& fb,
                                Eigen::VectorXd& r) const {
  const int nw = layout_.n_wheels;
  for (int k = 0; k < 2 * layout_.n_bodies; ++k) {
    const int i = layout_.body(k);
    r(i) = fb(i) - vm_.mass(nw + k) * x(i);
  }
}

void VehicleRows::add_block(Eigen::MatrixXd& D, bool inertia_only, double cq, double cv) const {
  const int nw = layout_.n_wheels, nu = nw + 2 * layout_.n_bodies;
  for (int k = 0; k < 2 * layout_.n_bodies; ++k)
    D(layout_.body(k), layout_.body(k)) += vm_.mass(nw + k);
  if (inertia_only) return;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nu; ++j) {
      const double v = cq * vm_.K(i, j) + cv * vm_.C(i, j);
      if (v != 0.0) D(layout_.vehicle(i), layout_.vehicle(j)) += v;
    }
}

double VehicleRows::energy(const SimState& st) const {
  vehicle_coordinates(st, u_, udot_);
  return vehicle_energy(vm_, u_, udot_);
}

}  // namespace trackwheel
