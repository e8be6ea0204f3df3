#include "linear_path.hpp"

#include <algorithm>
#include <cmath>

namespace trackwheel {

// The window's rest state is the linear track at rest under its own weight (no wheel).
LinearStepper::LinearStepper(LinearSystem& sys, SimState& st, Accel& acc, SimOutput& out,
                             const Divergence& div)
    : sys_(sys),
      st_(st),
      acc_(acc),
      out_(out),
      div_(div),
      supports_(sys.model().rail, sys.track().y_of_full),
      delta_(sys.n_wheels()) {
  sys.sleepers().reset_record();  // the start state's ballast states: no event
  const WindowParams& wp = sys.settings().window;
  if (!wp.active()) return;
  const LinearTrack& tr = sys.track();
  Eigen::VectorXd q = tr.Qg, z;
  LinearRest(tr, sys.sleepers()).solve(q, z);
  win_ =
      WindowFollower(WindowShift(sys.model().rail, wp, tr.y_of_full, tr.nq, sys.sleepers().size()),
                     q, z, &sys.sleepers());
}

void LinearStepper::stream_supports(SupportFeed& feed) {
  if (!feed.active() || !win_.active()) return;
  win_.set_restream([this, &feed](long first, Eigen::VectorXd& e_rest, Eigen::VectorXd& z_rest) {
    if (!feed.feed(first)) return false;
    sys_.supports_changed();
    ++out_.factorizations;
    e_rest = sys_.track().Qg;
    LinearRest(sys_.track(), sys_.sleepers()).solve(e_rest, z_rest);
    return true;
  });
}

bool LinearStepper::shift_window(double t1, std::initializer_list<Accel*> accs) {
  if (!win_.active()) return false;
  const bool moved = win_.follow_wheels(sys_, t1, st_, accs);
  if (!moved) return false;
  sys_.drop_cached_columns();
  // the ballast states moved with their sleepers (WindowFollower), the fresh one joined at rest
  if (sys_.sync_ballast()) ++out_.factorizations;
  return true;
}

bool LinearStepper::finite() const {
  if (!st_.e.allFinite() || !st_.z.allFinite() || !st_.body.allFinite()) return false;
  for (const WheelState& ws : st_.wheels)
    if (!std::isfinite(ws.y)) return false;
  return true;
}

double LinearStepper::vibration_energy() const {
  Eigen::VectorXd Mqd;
  sys_.track().M.multiply(st_.edot, Mqd);
  double E = 0.5 * st_.edot.dot(Mqd) + vertical_kinetic_energy(sys_.model(), st_);
  if (!sys_.sleepers().empty()) E += sys_.sleepers().kinetic_energy(st_.zdot);
  return E;
}

void LinearStepper::record_sample(double t) {
  Recording& rec = out_.rec;
  rec.push(Field::t, t);
  for (int w = 0; w < sys_.n_wheels(); ++w) record_wheel(w, t, delta_[w]);
  for (int b = 0; b < sys_.n_bodies(); ++b) rec.push_body(st_.body(2 * b), st_.body(2 * b + 1));
  if (rec.wants(Field::energy)) rec.push(Field::energy, total_energy(t, delta_));
  const SimSettings& set = sys_.settings();
  supports_.record(sys_.model().rail, st_.e, st_.edot, st_.z, st_.zdot, sys_.sleepers(),
                   win_.first(), sys_.origin(), set.output_every * set.dt, rec, out_.envelope);
}

// The contact stays vertical at X_A: no obliquity at the wheel, the rail's slope y_s enters the
// outputs' phi only; theta = v t / rho0 (rolling without slip).
void LinearStepper::record_wheel(int w, double t, double& delta) {
  Recording& rec = out_.rec;
  const LinearTrack& tr = sys_.track();
  const Model& model = sys_.model();
  const double v = sys_.settings().speed, r0 = model.wheels[w].radius, Xw = sys_.x_at(w, t);
  const double Y = st_.wheels[w].y, N = acc_.x(sys_.layout().y(w) + 1);
  const WheelCoupling& s = at_;
  at_.set(tr, tr.point(Xw - sys_.origin()), Xw - sys_.origin());
  const ElementCompliance g = sys_.compliance_at(Xw - sys_.origin());
  const double ys = s.dot_s(st_.e), yss = s.dot_ss(st_.e), yst = s.dot_s(st_.edot);
  double rate;
  // approach, and the law's compression and force in series with the element's compliance
  delta = sys_.rigid() ? 0.0 : r0 + sys_.excitation(w, t, rate) - Y + s.dot(st_.e);
  double compression = delta, Ne = N;
  if (!sys_.rigid() && model.contact.element_compliance) {
    const SeriesForce sf = series_normal_force(sys_.law(), model.contact.stiffness, g.G, delta);
    compression = sf.compression;
    Ne = sf.N;
  }
  // the rail under the load: the element's own deflection G N_e included
  const double yc = s.dot(st_.e) - g.G * Ne;
  rec.push(Field::x_wheel, Xw);
  rec.push(Field::y_wheel, Y);
  rec.push(Field::ydot_wheel, st_.wheels[w].ydot);
  rec.push(Field::theta, v * t / r0);
  rec.push(Field::thetadot, v / r0);
  rec.push(Field::contact_s, Xw);
  rec.push(Field::y_contact, yc);
  rec.push(Field::normal_force, N);
  rec.push(Field::tangential_force, 0.0);
  rec.push(Field::slip, 0.0);
  rec.push(Field::v_error, 0.0);
  const double phi = std::atan(ys), gg = 1.0 + ys * ys;
  const double phi_s = yss / gg, phi_t = yst / gg;
  rec.push(Field::phi, phi);
  record_acc_terms(rec, (r0 - delta) * std::cos(phi), v / r0, v, phi_s, phi_t);
  rec.push(Field::acc_contact, s.dot(acc_.edd) + 2.0 * v * s.dot_s(st_.edot) + v * v * yss);
  rec.push(Field::reaction, 0.0);
  rec.push(Field::penetration, compression);
  rec.push(Field::slip_state, N > 0.0 ? 1 : 0);
}

double LinearStepper::total_energy(double t, const std::vector<double>& delta) const {
  const LinearTrack& tr = sys_.track();
  const Model& model = sys_.model();
  const ContactParams& cp = model.contact;
  Eigen::VectorXd Mqd, Kq;
  tr.M.multiply(st_.edot, Mqd);
  tr.K.multiply(st_.e, Kq);
  double E = 0.5 * st_.edot.dot(Mqd) + 0.5 * st_.e.dot(Kq) - tr.Qg.dot(st_.e);
  if (!sys_.sleepers().empty()) E += sys_.sleepers().energy(st_.e, tr.y_of_full, st_.z, st_.zdot);
  for (int w = 0; w < sys_.n_wheels(); ++w) {
    const WheelParams& p = model.wheels[w];
    const WheelState& ws = st_.wheels[w];
    const double N = acc_.x(sys_.layout().y(w) + 1);
    E += 0.5 * p.mass * ws.ydot * ws.ydot;
    E += p.total_load() * ws.y;
    if (!sys_.rigid())
      E += cp.element_compliance ? series_potential(sys_.law(), cp.stiffness,
                                                    sys_.compliance_at(sys_.s_at(w, t)).G, delta[w])
                                 : contact_potential(sys_.law(), cp.stiffness, delta[w]);
    else if (sys_.options().wheel_model == WheelModel::MovingMass && cp.element_compliance)
      E += 0.5 * sys_.compliance_at(sys_.s_at(w, t)).G * N * N;  // the element's
  }
  if (sys_.n_bodies() > 0) E += sys_.vehicle().energy(st_);
  return E;
}

}  // namespace trackwheel
