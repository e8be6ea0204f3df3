#include "dynamics.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>

#include "banded.hpp"
#include "explicit_rk4.hpp"
#include "generalized_alpha.hpp"
#include "sleepers.hpp"
#include "slip.hpp"

namespace trackwheel {

namespace {

void check_initial(const Model& model, const SimState& st) {
  if (st.e.size() != model.rail.n_dof() || st.edot.size() != model.rail.n_dof())
    throw std::invalid_argument("initial rail state has the wrong size");
  const int ns = Sleepers(model.rail).size();
  if ((st.z.size() != 0 && st.z.size() != ns) || st.zdot.size() != st.z.size())
    throw std::invalid_argument("initial sleeper state z, zdot must be empty (static) or have " +
                                std::to_string(ns) + " entries");
  if (static_cast<int>(st.wheels.size()) != model.n_wheels())
    throw std::invalid_argument("initial state has " + std::to_string(st.wheels.size()) +
                                " wheel states; the model has " + std::to_string(model.n_wheels()) +
                                " wheels");
  const long nb2 = 2L * model.n_bodies();
  if (st.body.size() != nb2 || st.bodydot.size() != nb2)
    throw std::invalid_argument("initial body state must have 2 n_bodies = " + std::to_string(nb2) +
                                " entries (z, phi per body)");
}

// Sleepers not given start at rest in equilibrium under the initial rail.
void start_sleepers(const RailModel& rail, SimState& st) {
  const Sleepers sl(rail);
  if (sl.empty() || st.z.size() == sl.size()) return;
  st.z = sl.static_z(st.e);
  st.zdot = Eigen::VectorXd::Zero(sl.size());
}

// Consistent start: contact points, slip states and the accelerations that go with them.
void start_state(System& sys, SimState& st, Eval& ev, Accel& acc) {
  const SimSettings& set = sys.settings();
  sys.evaluate(0.0, st, true, ev);
  for (int w = 0; w < sys.n_wheels(); ++w) st.wheels[w].s = ev.w[w].pt.s;
  for (int k = 0; k < 3; ++k) {
    sys.accelerations(st, ev, acc);
    bool changed = false;
    for (int w = 0; w < sys.n_wheels(); ++w)
      changed |= update_slip_state(set.rolling, sys.model().contact.friction, set.speed,
                                   st.wheels[w], ev.w[w], acc.x(kBorderPerWheel * w + kLambda));
    if (!changed) break;
  }
}

std::string stability_cause(const SimSettings& set, double limit, double omega_max) {
  const double h = set.dt;
  if (set.integrator == Integrator::ExplicitRK4 && h > 0.9 * limit)
    return "time step " + format3(h) + " s is above the explicit stability limit of about " +
           format3(limit) + " s (highest frequency " + format3(omega_max / (2 * M_PI)) + " Hz)";
  if (set.integrator == Integrator::ExplicitRK4)
    return "numerical instability of the explicit scheme (time step " + format3(h) +
           " s, predicted limit " + format3(limit) + " s)";
  return "the time step " + format3(h) +
         " s is too large for the contact or slip transitions, or the scene is unstable (e.g. "
         "the wheel left the rail)";
}

}  // namespace

SimOutput simulate(const Model& model_in, const SimSettings& set, const SimState& initial,
                   const ProgressFn& progress) {
  check_settings(set);
  check_model(model_in);
  check_initial(model_in, initial);
  // a travelling window that streams the supports in sets them on the run's own rail
  const bool streams = set.window.streams();
  std::optional<RailModel> own_rail;
  SupportFeed feed;
  if (streams) {
    own_rail.emplace(model_in.rail);
    feed = SupportFeed(set.window, *own_rail);
  }
  const Model model =
      streams ? Model{*own_rail, model_in.wheels, model_in.contact, model_in.vehicle} : model_in;
  System sys(model, set);
  SimOutput out;
  SimState st = initial;
  start_sleepers(model.rail, st);
  Eval ev;
  Accel acc;
  start_state(sys, st, ev, acc);

  std::vector<double> xs, ys;
  for (int w = 0; w < model.n_wheels(); ++w) {
    xs.push_back(sys.s_at(w, 0.0));  // the rail coordinate
    ys.push_back(st.wheels[w].y);
  }
  // a sleeper between pad and ballast can be stiffer than anything in the rail
  double omega_max =
      std::max(highest_frequency(model, st.e, xs, ys), Sleepers(model.rail).highest_frequency());
  if (streams) {  // the stiffest sleeper the window will carry
    const SupportParams& k = set.window.supports;
    for (std::size_t j = 0; j < k.sleeper_mass.size(); ++j)
      omega_max = std::max(
          omega_max, std::sqrt((k.stiffness[j] + k.ballast_stiffness[j]) / k.sleeper_mass[j]));
  }
  out.stability_limit = explicit_stability_limit(omega_max);
  const Divergence div(set, [&] { return stability_cause(set, out.stability_limit, omega_max); });

  std::unique_ptr<FullStepper> stepper;
  if (set.integrator == Integrator::GeneralizedAlpha)
    stepper = std::make_unique<GeneralizedAlpha>(sys, st, ev, acc, out, div);
  else
    stepper = std::make_unique<ExplicitRK4>(sys, st, ev, acc, out, div);
  stepper->stream_supports(feed);
  run_time_loop(*stepper, model, set, div, out, progress);
  out.final_state = st;
  record_ballast(sys.sleepers(), out);
  return out;
}

double highest_frequency(const Model& model, const Eigen::VectorXd& e,
                         const std::vector<double>& xw, const std::vector<double>& yw) {
  const RailModel& rail = model.rail;
  const int nf = rail.n_free(), nw = model.n_wheels();
  BandMatrix K(nf, kHalfBandwidth), M = rail.mass();
  rail.add_tangent(e, 1.0, K);
  if (!M.factorize()) throw std::runtime_error("rail mass matrix is singular");
  // each contact spring couples its wheel's Y and the rail
  std::vector<Mat10> Kc(nw);
  std::vector<int> d0(nw);
  for (int w = 0; w < nw; ++w) {
    const ContactPoint pt = find_contact_point(rail, e, Eigen::Vector2d(xw[w], yw[w]), xw[w]);
    const ContactForce cf = contact_force(model.contact_of(w), pt, Vec10::Zero(), true);
    Kc[w] = cf.K;
    if (!cf.active)  // the linear stiffness at the static load
      Kc[w] = linearised_stiffness(model.contact.law, model.contact.stiffness,
                                   model.wheels[w].total_load()) *
              cf.grad_rho * cf.grad_rho.transpose();
    d0[w] = pt.mp.dof0();
  }
  const auto& f2f = rail.full_to_free();
  auto index = [&](int w, int a) { return a == 1 ? nf + w : f2f[d0[w] + a - 2]; };
  Eigen::VectorXd x(nf + nw);
  for (int i = 0; i < nf + nw; ++i) x(i) = 1.0 + 0.37 * std::sin(1.3 * i);  // deterministic
  double lam = 0.0;
  auto applyK = [&](const Eigen::VectorXd& u, Eigen::VectorXd& out) {
    Eigen::VectorXd ur = u.head(nf), kr;
    K.multiply(ur, kr);
    out = Eigen::VectorXd::Zero(nf + nw);
    out.head(nf) = kr;
    for (int w = 0; w < nw; ++w)
      for (int a = 1; a < 10; ++a) {
        const int i = index(w, a);
        if (i < 0) continue;
        for (int c = 1; c < 10; ++c) {
          const int j = index(w, c);
          if (j >= 0) out(i) += Kc[w](a, c) * u(j);
        }
      }
  };
  Eigen::VectorXd Kx, y, Mx;
  for (int it = 0; it < 400; ++it) {
    applyK(x, Kx);
    y = Kx;
    M.solve_in_place(y.head(nf));
    for (int w = 0; w < nw; ++w) y(nf + w) /= model.wheels[w].mass;
    // Rayleigh quotient x^T K x / x^T M x
    rail.mass().multiply(x.head(nf), Mx);
    double xMx = x.head(nf).dot(Mx);
    for (int w = 0; w < nw; ++w) xMx += model.wheels[w].mass * x(nf + w) * x(nf + w);
    lam = x.dot(Kx) / xMx;
    x = y / y.norm();
  }
  return std::sqrt(std::max(lam, 0.0));
}

double explicit_stability_limit(double omega_max) { return 2.0 * std::sqrt(2.0) / omega_max; }

}  // namespace trackwheel
