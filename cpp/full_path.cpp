#include "full_path.hpp"

#include <algorithm>
#include <cmath>

#include "statics.hpp"

namespace trackwheel {

// The window's shift maps over the full rail coordinates (a fixed coordinate has no departure:
// it maps nowhere and stays at rest) and its rest state, the nonlinear rail at rest under its
// own weight on its supports, computed once.
FullStepper::FullStepper(System& sys, SimState& st, Eval& ev, Accel& acc, SimOutput& out,
                         const Divergence& div)
    : sys_(sys), st_(st), ev_(ev), acc_(acc), out_(out), div_(div) {
  const RailModel& rail = sys.rail();
  std::vector<int> identity(rail.n_dof());
  for (int i = 0; i < rail.n_dof(); ++i) identity[i] = i;
  supports_ = SupportRecorder(rail, identity);
  sys.sleepers().reset_record();  // the start state's ballast states: no event
  const WindowParams& wp = sys.settings().window;
  if (!wp.active()) return;
  std::vector<int> map(rail.n_dof());
  for (int i = 0; i < rail.n_dof(); ++i) map[i] = rail.full_to_free()[i] >= 0 ? i : -1;
  const StaticResult rest = solve_track_static(rail);
  win_ = WindowFollower(WindowShift(rail, wp, map, rail.n_dof(), sys.sleepers().size()), rest.e,
                        rest.z, &sys.sleepers());
}

void FullStepper::stream_supports(SupportFeed& feed) {
  if (!feed.active() || !win_.active()) return;
  win_.set_restream([this, &feed](long first, Eigen::VectorXd& e_rest, Eigen::VectorXd& z_rest) {
    if (!feed.feed(first)) return false;
    sys_.supports_changed();
    StaticResult rest = solve_track_static(sys_.rail());
    e_rest = std::move(rest.e);
    z_rest = std::move(rest.z);
    return true;
  });
}

// What moves is the departure from the rest state (the ANCF x coordinates: the displacement,
// not the position); the wheels' rail coordinates and warm starts drop by a bay with the
// origin's step, a unilateral ballast's states with their sleepers (WindowFollower).
bool FullStepper::shift_window(double t1, std::initializer_list<Accel*> accs) {
  if (!win_.active()) return false;
  return win_.follow_wheels(sys_, t1, st_, accs);
}

void FullStepper::record_sample(double t) {
  Recording& rec = out_.rec;
  const double v = sys_.settings().speed;
  rec.push(Field::t, t);
  if (rec.wants(Field::energy)) rec.push(Field::energy, total_energy(sys_.model(), st_, ev_));
  for (int w = 0; w < sys_.n_wheels(); ++w) {
    const WheelEval& we = ev_.w[w];
    const WheelState& ws = st_.wheels[w];
    const ContactPoint& pt = we.pt;
    const double lambda = acc_.x(kBorderPerWheel * w + kLambda);
    rec.push(Field::x_wheel, we.x);
    rec.push(Field::y_wheel, ws.y);
    rec.push(Field::ydot_wheel, ws.ydot);
    rec.push(Field::theta, ws.theta);
    rec.push(Field::thetadot, ws.thetadot);
    rec.push(Field::contact_s, pt.s + sys_.origin());  // X of the contact point
    // the rail under the load: the element's own deflection (element compliance) included
    rec.push(Field::y_contact, pt.r.y() - we.cf.deflection * pt.n.y());
    rec.push(Field::normal_force, we.cf.N);
    rec.push(Field::tangential_force, lambda);
    rec.push(Field::slip, we.rk.g);
    rec.push(Field::slip_state, static_cast<int>(ws.state));
    rec.push(Field::penetration, we.cf.compression);
    // the rolling radius (rho + G N_e with the element compliance: rk.b(10) = -rho_r)
    rec.push(Field::v_error, v != 0.0 ? (v + we.rk.b(10) * ws.thetadot) / v * 100.0 : 0.0);
    // obliquity phi = atan2(y_s, x_s), its slope along s and its rate at fixed s
    Eigen::Vector2d Se_dd = Eigen::Vector2d::Zero(), Ssedot = Eigen::Vector2d::Zero();
    for (int a = 0; a < 4; ++a) {
      Ssedot += pt.mp.h.ns[a] * st_.edot.segment<2>(pt.mp.dof0() + 2 * a);
      Se_dd += pt.mp.h.n[a] * acc_.edd.segment<2>(pt.mp.dof0() + 2 * a);
    }
    const double gg = pt.rs.squaredNorm();
    const double phi_s = (pt.rs.x() * pt.rss.y() - pt.rs.y() * pt.rss.x()) / gg;
    const double phi_t = (pt.rs.x() * Ssedot.y() - pt.rs.y() * Ssedot.x()) / gg;
    rec.push(Field::phi, pt.phi);
    record_acc_terms(rec, pt.rho * std::cos(pt.phi), ws.thetadot, v, phi_s, phi_t);
    // total vertical acceleration of the contact point y_B(t) = y(s*(t), t), with s'' ~ 0
    const double sd = we.rk.s_dot;
    rec.push(Field::acc_contact, Se_dd.y() + 2.0 * sd * Ssedot.y() + sd * sd * pt.rss.y());
    // driving reaction holding X_A: M X'' = 0 = R + N n_x + lambda t_x
    rec.push(Field::reaction, -(we.cf.F(0) + lambda * we.rk.b(0)));
  }
  for (int b = 0; b < sys_.n_bodies(); ++b) rec.push_body(st_.body(2 * b), st_.body(2 * b + 1));
  const SimSettings& set = sys_.settings();
  supports_.record(sys_.rail(), st_.e, st_.edot, st_.z, st_.zdot, sys_.sleepers(), win_.first(),
                   sys_.origin(), set.output_every * set.dt, rec, out_.envelope);
}

}  // namespace trackwheel
