#include "ga_scheme.hpp"

namespace trackwheel {

GACoefficients::GACoefficients(double ri, double step) {
  am = (2.0 * ri - 1.0) / (ri + 1.0);
  af = ri / (ri + 1.0);
  gam = 0.5 - am + af;
  bet = 0.25 * (1.0 - am + af) * (1.0 - am + af);
  bp = bet * (1.0 - af) / (1.0 - am);
  gp = gam * (1.0 - af) / (1.0 - am);
  h = step;
  cq = bp * h * h;
  cv = gp * h;
}

namespace {

// One coordinate of the border (a wheel's Y_A or theta, a body's z or phi) at the iterate: the
// state entries q1, v1 and the algorithmic a1 from the step's start.
void advance(const GACoefficients& c, double q0, double v0, double a0, double qdd0, double qdd1,
             double& q1, double& v1, double& a1) {
  a1 = c.algorithmic(qdd1, qdd0, a0);
  c.newmark(q0, v0, a0, a1, q1, v1);
}

// The same at x = 0 (the predictor).
void start(const GACoefficients& c, double q0, double v0, double a0, double qdd0, double& q1,
           double& v1, double& a1) {
  a1 = c.algorithmic_start(qdd0, a0);
  c.newmark(q0, v0, a0, a1, q1, v1);
}

}  // namespace

void ga_state_at(const GACoefficients& c, const BorderLayout& b, const SimState& s0,
                 const Accel& acc0, const Accel& alg0, const Accel& x, SimState& s1, Accel& alg1) {
  alg1.edd = c.algorithmic(x.edd, acc0.edd, alg0.edd);
  c.newmark(s0.e, s0.edot, alg0.edd, alg1.edd, s1.e, s1.edot);
  if (alg0.zdd.size() > 0) {
    alg1.zdd = c.algorithmic(x.zdd, acc0.zdd, alg0.zdd);
    c.newmark(s0.z, s0.zdot, alg0.zdd, alg1.zdd, s1.z, s1.zdot);
  }
  alg1.x.resize(alg0.x.size());
  for (int w = 0; w < b.n_wheels; ++w) {
    const WheelState& w0 = s0.wheels[w];
    WheelState& w1 = s1.wheels[w];
    const int iy = b.y(w);
    advance(c, w0.y, w0.ydot, alg0.x(iy), acc0.x(iy), x.x(iy), w1.y, w1.ydot, alg1.x(iy));
    if (b.theta >= 0) {
      const int it = iy + b.theta;
      advance(c, w0.theta, w0.thetadot, alg0.x(it), acc0.x(it), x.x(it), w1.theta, w1.thetadot,
              alg1.x(it));
    }
    alg1.x(iy + b.multiplier) = 0.0;
  }
  for (int k = 0; k < 2 * b.n_bodies; ++k) {  // the vehicle's bodies: z, phi
    const int i = b.body(k);
    advance(c, s0.body(k), s0.bodydot(k), alg0.x(i), acc0.x(i), x.x(i), s1.body(k), s1.bodydot(k),
            alg1.x(i));
  }
}

void ga_predictor(const GACoefficients& c, const BorderLayout& b, const SimState& s0,
                  const Accel& acc0, const Accel& alg0, SimState& p, Accel& algp) {
  algp.edd = c.algorithmic_start(acc0.edd, alg0.edd);
  c.newmark(s0.e, s0.edot, alg0.edd, algp.edd, p.e, p.edot);
  if (p.wheels.size() != s0.wheels.size()) p.wheels = s0.wheels;
  algp.x.setZero(alg0.x.size());
  for (int w = 0; w < b.n_wheels; ++w) {
    const WheelState& w0 = s0.wheels[w];
    WheelState& w1 = p.wheels[w];
    const int iy = b.y(w);
    start(c, w0.y, w0.ydot, alg0.x(iy), acc0.x(iy), w1.y, w1.ydot, algp.x(iy));
    if (b.theta >= 0) {
      const int it = iy + b.theta;
      start(c, w0.theta, w0.thetadot, alg0.x(it), acc0.x(it), w1.theta, w1.thetadot, algp.x(it));
    }
  }
  p.body.resize(s0.body.size());
  p.bodydot.resize(s0.body.size());
  for (int k = 0; k < 2 * b.n_bodies; ++k) {
    const int i = b.body(k);
    start(c, s0.body(k), s0.bodydot(k), alg0.x(i), acc0.x(i), p.body(k), p.bodydot(k), algp.x(i));
  }
  if (s0.z.size() > 0) {
    algp.zdd = c.algorithmic_start(acc0.zdd, alg0.zdd);
    c.newmark(s0.z, s0.zdot, alg0.zdd, algp.zdd, p.z, p.zdot);
  }
}

void ga_corrector(const GACoefficients& c, const BorderLayout& b, const SimState& p, const Accel& x,
                  SimState& s1) {
  const double cq = c.cq, cv = c.cv;
  s1.e = p.e + cq * x.edd;
  s1.edot = p.edot + cv * x.edd;
  if (s1.wheels.size() != p.wheels.size()) s1.wheels = p.wheels;
  for (int w = 0; w < b.n_wheels; ++w) {
    const WheelState& w0 = p.wheels[w];
    WheelState& w1 = s1.wheels[w];
    const int iy = b.y(w);
    w1.y = w0.y + cq * x.x(iy);
    w1.ydot = w0.ydot + cv * x.x(iy);
    if (b.theta >= 0) {
      w1.theta = w0.theta + cq * x.x(iy + b.theta);
      w1.thetadot = w0.thetadot + cv * x.x(iy + b.theta);
    }
  }
  s1.body.resize(p.body.size());
  s1.bodydot.resize(p.body.size());
  for (int k = 0; k < 2 * b.n_bodies; ++k) {
    s1.body(k) = p.body(k) + cq * x.x(b.body(k));
    s1.bodydot(k) = p.bodydot(k) + cv * x.x(b.body(k));
  }
  if (p.z.size() > 0) {
    s1.z = p.z + cq * x.zdd;
    s1.zdot = p.zdot + cv * x.zdd;
  }
}

void ga_corrected_alg(const GACoefficients& c, const BorderLayout& b, const Accel& algp,
                      const Accel& x, Accel& alg1) {
  const double f = c.corrector();
  alg1.edd = algp.edd + f * x.edd;
  alg1.x.setZero(algp.x.size());
  for (int w = 0; w < b.n_wheels; ++w) {
    const int iy = b.y(w);
    alg1.x(iy) = algp.x(iy) + f * x.x(iy);
    if (b.theta >= 0) alg1.x(iy + b.theta) = algp.x(iy + b.theta) + f * x.x(iy + b.theta);
  }
  for (int k = 0; k < 2 * b.n_bodies; ++k)
    alg1.x(b.body(k)) = algp.x(b.body(k)) + f * x.x(b.body(k));
  if (algp.zdd.size() > 0) alg1.zdd = algp.zdd + f * x.zdd;
}

}  // namespace trackwheel
