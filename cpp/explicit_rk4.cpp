#include "explicit_rk4.hpp"

#include "slip.hpp"

namespace trackwheel {

void ExplicitRK4::derivative(double t, const SimState& s, Accel& a) {
  sys_.evaluate(t, s, true, scratch_);
  sys_.accelerations(s, scratch_, a);
}

// k = st + c h (rates of from_rate, accelerations a)
void ExplicitRK4::stage(double c, const Accel& a, const SimState& from_rate, SimState& k) const {
  const double h = sys_.settings().dt;
  k.e = st_.e + c * h * from_rate.edot;
  k.edot = st_.edot + c * h * a.edd;
  if (st_.z.size() > 0) {
    k.z = st_.z + c * h * from_rate.zdot;
    k.zdot = st_.zdot + c * h * a.zdd;
  }
  for (int w = 0; w < sys_.n_wheels(); ++w) {
    const int o = kBorderPerWheel * w;
    const WheelState& s = st_.wheels[w];
    k.wheels[w].y = s.y + c * h * from_rate.wheels[w].ydot;
    k.wheels[w].ydot = s.ydot + c * h * a.x(o + kY);
    k.wheels[w].theta = s.theta + c * h * from_rate.wheels[w].thetadot;
    k.wheels[w].thetadot = s.thetadot + c * h * a.x(o + kTheta);
  }
  const int ob = kBorderPerWheel * sys_.n_wheels(), m = 2 * sys_.n_bodies();
  if (m == 0) return;
  k.body = st_.body + c * h * from_rate.bodydot;
  k.bodydot = st_.bodydot + c * h * a.x.segment(ob, m);
}

void ExplicitRK4::step(long n) {
  const SimSettings& set = sys_.settings();
  const double h = set.dt, t1 = n * h, t0 = t1 - h;
  // the window moved: the accelerations at the start are evaluated anew at the shifted state
  if (shift_window(t1, {})) start_ready_ = false;
  if (!start_ready_) {
    sys_.evaluate(t0, st_, true, ev_);
    sys_.accelerations(st_, ev_, acc_);
  }
  start_ready_ = false;
  int n_changed = 0, n_locked = 0;
  for (int w = 0; w < sys_.n_wheels(); ++w) {
    st_.wheels[w].s = ev_.w[w].pt.s;
    const double lambda = acc_.x(kBorderPerWheel * w + kLambda);
    n_changed += update_slip_state(set.rolling, sys_.model().contact.friction, set.speed,
                                   st_.wheels[w], ev_.w[w], lambda);
    const bool was_locked = st_.wheels[w].locked;
    n_changed += update_brake_state(sys_.model().wheels[w], st_.wheels[w], ev_.w[w], lambda);
    n_locked += !was_locked && st_.wheels[w].locked;
  }
  if (n_changed > 0) {
    out_.state_changes += n_changed;
    // locking set theta' = 0, on which the slip velocity and contact damping depend
    if (n_locked > 0) sys_.contact_terms(st_, true, ev_);
    sys_.accelerations(st_, ev_, acc_);
  }
  k1_ = st_;
  k2_ = st_;
  stage(0.5, acc_, k1_, k2_);
  derivative(t0 + 0.5 * h, k2_, a2_);
  k3_ = st_;
  stage(0.5, a2_, k2_, k3_);
  derivative(t0 + 0.5 * h, k3_, a3_);
  k4_ = st_;
  stage(1.0, a3_, k3_, k4_);
  derivative(t1, k4_, a4_);
  const double wt = h / 6.0;
  st_.e += wt * (k1_.edot + 2.0 * k2_.edot + 2.0 * k3_.edot + k4_.edot);
  st_.edot += wt * (acc_.edd + 2.0 * a2_.edd + 2.0 * a3_.edd + a4_.edd);
  if (st_.z.size() > 0) {
    st_.z += wt * (k1_.zdot + 2.0 * k2_.zdot + 2.0 * k3_.zdot + k4_.zdot);
    st_.zdot += wt * (acc_.zdd + 2.0 * a2_.zdd + 2.0 * a3_.zdd + a4_.zdd);
  }
  for (int w = 0; w < sys_.n_wheels(); ++w) {
    const int o = kBorderPerWheel * w, ty = o + kY, tt = o + kTheta;
    WheelState& s = st_.wheels[w];
    s.y += wt * (k1_.wheels[w].ydot + 2.0 * k2_.wheels[w].ydot + 2.0 * k3_.wheels[w].ydot +
                 k4_.wheels[w].ydot);
    s.ydot += wt * (acc_.x(ty) + 2.0 * a2_.x(ty) + 2.0 * a3_.x(ty) + a4_.x(ty));
    s.theta += wt * (k1_.wheels[w].thetadot + 2.0 * k2_.wheels[w].thetadot +
                     2.0 * k3_.wheels[w].thetadot + k4_.wheels[w].thetadot);
    s.thetadot += wt * (acc_.x(tt) + 2.0 * a2_.x(tt) + 2.0 * a3_.x(tt) + a4_.x(tt));
  }
  const int ob = kBorderPerWheel * sys_.n_wheels(), m = 2 * sys_.n_bodies();
  if (m > 0) {
    st_.body += wt * (k1_.bodydot + 2.0 * k2_.bodydot + 2.0 * k3_.bodydot + k4_.bodydot);
    st_.bodydot += wt * (acc_.x.segment(ob, m) + 2.0 * a2_.x.segment(ob, m) +
                         2.0 * a3_.x.segment(ob, m) + a4_.x.segment(ob, m));
  }
  if (!finite_state(st_)) div_.fail(n, "non-finite state");
  // a unilateral ballast's states at the step's end: the law, as at every stage
  sys_.sleepers().update_states(st_.z, &st_.zdot, false);
  sys_.sleepers().commit(h);
}

void ExplicitRK4::record(long n) {
  const double t1 = n * sys_.settings().dt;
  sys_.evaluate(t1, st_, true, ev_);
  sys_.accelerations(st_, ev_, acc_);
  start_ready_ = true;
  record_sample(t1);
}

}  // namespace trackwheel
