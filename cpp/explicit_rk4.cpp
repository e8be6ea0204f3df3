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
  for (int w = 0; w < sys_.n_wheels(); ++w) {
    const int o = kBorderPerWheel * w;
    const WheelState& s = st_.wheels[w];
    k.wheels[w].y = s.y + c * h * from_rate.wheels[w].ydot;
    k.wheels[w].ydot = s.ydot + c * h * a.x(o + kY);
    k.wheels[w].theta = s.theta + c * h * from_rate.wheels[w].thetadot;
    k.wheels[w].thetadot = s.thetadot + c * h * a.x(o + kTheta);
  }
}

void ExplicitRK4::step(long n) {
  const SimSettings& set = sys_.settings();
  const double h = set.dt, t1 = n * h, t0 = t1 - h;
  if (!start_ready_) {
    sys_.evaluate(t0, st_, true, ev_);
    sys_.accelerations(st_, ev_, acc_);
  }
  start_ready_ = false;
  int n_changed = 0;
  for (int w = 0; w < sys_.n_wheels(); ++w) {
    st_.wheels[w].s = ev_.w[w].pt.s;
    n_changed += update_slip_state(set.rolling, sys_.model().contact.friction, set.speed,
                                   st_.wheels[w], ev_.w[w], acc_.x(kBorderPerWheel * w + kLambda));
  }
  if (n_changed > 0) {
    out_.state_changes += n_changed;
    sys_.accelerations(st_, ev_, acc_);
  }
  const SimState k1 = st_;
  SimState k = st_;
  Accel a2, a3, a4;
  stage(0.5, acc_, k1, k);
  const SimState k2 = k;
  derivative(t0 + 0.5 * h, k2, a2);
  stage(0.5, a2, k2, k);
  const SimState k3 = k;
  derivative(t0 + 0.5 * h, k3, a3);
  stage(1.0, a3, k3, k);
  const SimState k4 = k;
  derivative(t1, k4, a4);
  const double wt = h / 6.0;
  st_.e += wt * (k1.edot + 2.0 * k2.edot + 2.0 * k3.edot + k4.edot);
  st_.edot += wt * (acc_.edd + 2.0 * a2.edd + 2.0 * a3.edd + a4.edd);
  for (int w = 0; w < sys_.n_wheels(); ++w) {
    const int o = kBorderPerWheel * w, ty = o + kY, tt = o + kTheta;
    WheelState& s = st_.wheels[w];
    s.y += wt * (k1.wheels[w].ydot + 2.0 * k2.wheels[w].ydot + 2.0 * k3.wheels[w].ydot +
                 k4.wheels[w].ydot);
    s.ydot += wt * (acc_.x(ty) + 2.0 * a2.x(ty) + 2.0 * a3.x(ty) + a4.x(ty));
    s.theta += wt * (k1.wheels[w].thetadot + 2.0 * k2.wheels[w].thetadot +
                     2.0 * k3.wheels[w].thetadot + k4.wheels[w].thetadot);
    s.thetadot += wt * (acc_.x(tt) + 2.0 * a2.x(tt) + 2.0 * a3.x(tt) + a4.x(tt));
  }
  if (!finite_state(st_)) div_.fail(n, "non-finite state");
}

void ExplicitRK4::record(long n) {
  const double t1 = n * sys_.settings().dt;
  sys_.evaluate(t1, st_, true, ev_);
  sys_.accelerations(st_, ev_, acc_);
  start_ready_ = true;
  record_sample(t1);
}

}  // namespace trackwheel
