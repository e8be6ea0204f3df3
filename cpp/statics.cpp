#include "statics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "sleepers.hpp"

namespace trackwheel {

namespace {

// Newton's stopping tolerance on the corrections [m]. The coordinates are of size L, and the
// round-off of the residual and of the banded solve grows with the number of unknowns (the
// worst-case bound of a sum or an LU solve of n terms is n eps): measured, the corrections stall
// at ~5e-17 n_elements L on the 5 m rail (1e-12 L at 20000 elements), above the former fixed
// 1e-13 L beyond ~2000 elements. n_free eps L (4 coordinates per node) stays above that floor at
// every mesh, and 1e-13 L keeps the former tolerance, so the paper's meshes are unchanged. Newton
// converges quadratically, so the error left after the last correction is far below it.
double static_tolerance(const RailModel& rail) {
  const double eps = std::numeric_limits<double>::epsilon();
  return std::max(1e-13, rail.n_free() * eps) * rail.params().length;
}

// The bordered system of the static Newton iteration and its buffers.
struct StaticSystem {
  StaticSystem(int nf, int m) : K(nf, kHalfBandwidth), B(nf, m), C(m, nf), D(m, m), r1(nf), r2(m) {}
  BandMatrix K;
  Eigen::MatrixXd B, C, D;
  Eigen::VectorXd R, r1, r2;  // R: the rail's full residual
};

// Wheel w's contact at (X_A, Y_A) = (x, y) into the system: its force on the rail rows of R and
// their Jacobian K_c, the wheel's row r2(w) = -(P - F_y) and its border entries; the contact
// point and force into the result.
void add_wheel_rows(const RailModel& rail, const Eigen::VectorXd& e, const WheelParams& wheel,
                    const ContactParams& contact, double x, double y, double& s_guess, int w,
                    StaticSystem& sys, StaticResult& res) {
  const auto& f2f = rail.full_to_free();
  const ContactPoint pt = find_contact_point(rail, e, Eigen::Vector2d(x, y), s_guess);
  s_guess = pt.s;
  const ContactForce cf = contact_force(contact, pt, Vec10::Zero(), true);
  const int d0 = pt.mp.dof0();
  sys.R.segment<8>(d0) -= cf.F.segment<8>(2);
  sys.r2(w) = -(wheel.total_load() - cf.F(1));
  // Jacobian of residual: rail rows += K_c, wheel row: d(P - F_y)/dq = K_c(1, .)
  for (int a = 0; a < 8; ++a) {
    const int i = f2f[d0 + a];
    if (i < 0) continue;
    for (int b = 0; b < 8; ++b) {
      const int j = f2f[d0 + b];
      if (j >= 0) sys.K.add(i, j, cf.K(2 + a, 2 + b));
    }
    sys.B(i, w) = cf.K(2 + a, 1);
    sys.C(w, i) = cf.K(1, 2 + a);
  }
  sys.D(w, w) = cf.K(1, 1);
  if (!cf.active) throw std::runtime_error("static solve: the wheel lost contact with the rail");
  res.contact_s = pt.s;
  res.normal_force = cf.N;
  res.horizontal_reaction = -cf.F(0);
}

// The converged results: the rail and the sleepers in each, and each wheel's contact anew at
// its final height (the rail under the load: the element's own deflection included).
void finish(const RailModel& rail, const Eigen::VectorXd& e, const Eigen::VectorXd& z,
            const Sleepers& sl, const std::vector<ContactParams>& contacts,
            const std::vector<double>& xs, const std::vector<double>& ys,
            const std::vector<double>& s_guess, std::vector<StaticResult>& res) {
  const int m = static_cast<int>(xs.size());
  const Eigen::VectorXd ballast = sl.ballast_force(z);
  std::vector<bool> closed(sl.size());
  for (int j = 0; j < sl.size(); ++j) closed[j] = sl.closed(j);
  for (int w = 0; w < std::max(m, 1); ++w) {
    res[w].e = e;
    res[w].z = z;
    res[w].ballast_force = ballast;
    res[w].closed = closed;
  }
  for (int w = 0; w < m; ++w) {
    res[w].x_wheel = xs[w];
    res[w].y_wheel = ys[w];
    const ContactPoint pt = find_contact_point(rail, e, Eigen::Vector2d(xs[w], ys[w]), s_guess[w]);
    res[w].contact_s = pt.s;
    const ContactForce cf = contact_force(contacts[w], pt, Vec10::Zero(), false);
    res[w].y_contact = pt.r.y() - cf.deflection * pt.n.y();
    res[w].normal_force = cf.N;
    res[w].horizontal_reaction = -cf.F(0);
  }
}

// Newton over the free rail coordinates and the heights Y_A of the given wheels (none: the rail
// alone), each wheel w held at X_A = xs[w] under its load P_w = F_w + M_w g; sleepers (layered
// supports) are condensed into the rail's band (sleepers.hpp, at rest: (cm, cv, cq) = (0, 0, 1)).
// A unilateral ballast is an active set: each iteration sets the sleepers' states at its iterate
// (the first keeps those of the start, closed where a sleeper touches its bed) and takes the
// exact Jacobian of that state; converged when the correction is small and no state changed
// (a sleeper flipping back and forth is frozen after Sleepers::kMaxFlips flips). closed_start:
// every sleeper starts closed instead (see newton_static).
std::vector<StaticResult> newton_from(const RailModel& rail,
                                      const std::vector<const WheelParams*>& wheels,
                                      const std::vector<ContactParams>& contacts,
                                      const std::vector<double>& xs, Eigen::VectorXd e,
                                      std::vector<double> ys, bool closed_start) {
  const int nf = rail.n_free();
  const int m = static_cast<int>(wheels.size());
  StaticSystem sys(nf, m);
  BorderedSolver solver;
  Eigen::VectorXd Q, dx1, dx2;
  const Eigen::VectorXd& Qg = rail.gravity_force();
  const auto& f2f = rail.full_to_free();
  std::vector<double> s_guess = xs;
  std::vector<StaticResult> res(std::max(m, 1));
  const double tol = static_tolerance(rail);
  Sleepers sl(rail);
  sl.set_coefficients(0.0, 0.0, 1.0);
  std::vector<int> identity(rail.n_dof());
  for (int i = 0; i < rail.n_dof(); ++i) identity[i] = i;
  Eigen::VectorXd z = sl.static_z(e), rs, dz;
  if (closed_start)
    sl.init_states(Eigen::VectorXd::Constant(sl.size(), -std::numeric_limits<double>::infinity()));
  else
    sl.init_states(z);
  sl.begin_step();
  for (int it = 0; it < 60; ++it) {
    const int changed = it > 0 ? sl.update_states(z, nullptr) : 0;
    rail.internal_force(e, nullptr, Q);
    sys.R = Q - Qg;  // full residual of the rail
    sys.K.set_zero();
    rail.add_tangent(e, 1.0, sys.K);
    if (!sl.empty()) {
      sl.add_rail_force(z, nullptr, identity, sys.R);
      sl.condense_matrix(f2f, sys.K);
      sl.forces(e, nullptr, identity, z, nullptr, rs);
    }
    sys.B.setZero();
    sys.C.setZero();
    sys.D.setZero();
    sys.r2.setZero();
    for (int w = 0; w < m; ++w)
      add_wheel_rows(rail, e, *wheels[w], contacts[w], xs[w], ys[w], s_guess[w], w, sys, res[w]);
    for (int i = 0; i < nf; ++i) sys.r1(i) = -sys.R(rail.free_to_full()[i]);
    if (!sl.empty()) sl.condense_rhs(rs, f2f, sys.r1);
    if (!sys.r1.allFinite() || !sys.r2.allFinite())
      throw std::runtime_error("static solve: non-finite residual");
    if (!solver.factorize(sys.K, sys.B, sys.C, sys.D))
      throw std::runtime_error("static solve: singular stiffness (is the wheel off the rail?)");
    solver.solve(sys.r1, sys.r2, dx1, dx2);
    rail.add_from_free(dx1, e);
    double step = dx1.lpNorm<Eigen::Infinity>();
    if (!sl.empty()) {
      sl.back_substitute(rs, dx1, f2f, dz);
      z += dz;
      step = std::max(step, dz.lpNorm<Eigen::Infinity>());
    }
    for (int w = 0; w < m; ++w) {
      ys[w] += dx2(w);
      step = std::max(step, std::abs(dx2(w)));
    }
    for (StaticResult& r : res) r.iterations = it + 1;
    if (step <= tol && changed == 0) {
      finish(rail, e, z, sl, contacts, xs, ys, s_guess, res);
      return res;
    }
  }
  std::ostringstream msg;
  msg << "static solve did not converge in 60 Newton iterations (x_wheel = "
      << (xs.empty() ? 0.0 : xs[0]) << " m)";
  throw std::runtime_error(msg.str());
}

// newton_from with the states at rest; if that fails on a track with unilateral ballast, again
// from every sleeper closed (the intact track's stiffness). From the unloaded rail the states at
// rest leave the voided sleepers under a wheel open, and where several neighbours hang the first
// correction of a rail carried by no ballast there overshoots far (the wheel then misses the
// rail); the closed start's first iterate is the intact track's, and the sleepers that hang at
// the solution open in the next ones. The problem is convex but for the rail's small geometric
// nonlinearity, so both starts converge to the same state; the states at rest are tried first
// so that every solve that converged from them stays as it was.
std::vector<StaticResult> newton_static(const RailModel& rail,
                                        const std::vector<const WheelParams*>& wheels,
                                        const std::vector<ContactParams>& contacts,
                                        const std::vector<double>& xs, const Eigen::VectorXd& e,
                                        const std::vector<double>& ys) {
  try {
    return newton_from(rail, wheels, contacts, xs, e, ys, false);
  } catch (const std::runtime_error&) {
    if (!rail.supports().any_unilateral()) throw;
  }
  return newton_from(rail, wheels, contacts, xs, e, ys, true);
}

// Y_A of a wheel just touching the rail below, pressed in by its static load; the contact is
// sought from a centre one radius above the rail (far above, a corrugated surface can curve
// more than the distance: the foot of the normal is then a maximum of the distance). The
// radius is the contact's, rho0 + Delta rho at the start: a wheel flat in contact lowers the
// centre by its depth (with rho0, a flat deeper than the static compression left a gap).
double touching_height(const RailModel& rail, const Eigen::VectorXd& e, const WheelParams& wheel,
                       const ContactParams& contact, double x_wheel) {
  const double y_above = rail.position(e, rail.locate(x_wheel)).y() + contact.radius;
  const ContactPoint pt = find_contact_point(rail, e, Eigen::Vector2d(x_wheel, y_above), x_wheel);
  const double delta = static_compression(contact.law, contact.stiffness, wheel.total_load());
  return pt.p.y() + contact.radius - delta;
}

void check_on_rail(const RailModel& rail, double x_wheel) {
  const double L = rail.params().length;
  if (!(x_wheel >= 0.0 && x_wheel <= L)) {
    std::ostringstream msg;
    msg << "x_wheel = " << x_wheel << " m is outside the rail [0, " << L << "] m";
    throw std::invalid_argument(msg.str());
  }
}

}  // namespace

StaticResult solve_static(const RailModel& rail, const WheelParams& wheel,
                          const ContactParams& contact, double x_wheel,
                          const Eigen::VectorXd& e_guess, double y_guess) {
  check_on_rail(rail, x_wheel);
  Eigen::VectorXd e = e_guess.size() == rail.n_dof() ? e_guess : rail.reference();
  double y = y_guess;
  if (!std::isfinite(y)) y = touching_height(rail, e, wheel, contact, x_wheel);
  return newton_static(rail, {&wheel}, {contact}, {x_wheel}, e, {y})[0];
}

std::vector<StaticResult> solve_static_wheels(const RailModel& rail,
                                              const std::vector<WheelParams>& wheels,
                                              const std::vector<ContactParams>& contacts,
                                              const std::vector<double>& x_wheels) {
  if (wheels.empty() || wheels.size() != x_wheels.size() || wheels.size() != contacts.size())
    throw std::invalid_argument(
        "static solve: give one position and one contact per wheel (at least one)");
  const Eigen::VectorXd e = rail.reference();
  std::vector<const WheelParams*> ptrs;
  std::vector<double> ys;
  for (std::size_t w = 0; w < wheels.size(); ++w) {
    check_on_rail(rail, x_wheels[w]);
    ptrs.push_back(&wheels[w]);
    ys.push_back(touching_height(rail, e, wheels[w], contacts[w], x_wheels[w]));
  }
  return newton_static(rail, ptrs, contacts, x_wheels, e, ys);
}

Eigen::VectorXd solve_rail_static(const RailModel& rail) { return solve_track_static(rail).e; }

StaticResult solve_track_static(const RailModel& rail) {
  return newton_static(rail, {}, {}, {}, rail.reference(), {})[0];
}

std::vector<StaticResult> solve_quasi_static(const RailModel& rail, const WheelParams& wheel,
                                             const ContactParams& contact,
                                             const std::vector<double>& positions) {
  std::vector<StaticResult> out;
  out.reserve(positions.size());
  Eigen::VectorXd e;
  for (double x : positions) {
    // warm start from the previous rail shape; the wheel height is re-seeded from the rail
    out.push_back(solve_static(rail, wheel, contact, x, e, NAN));
    e = out.back().e;
  }
  return out;
}

}  // namespace trackwheel
