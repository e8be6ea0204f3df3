#include "periodic_poles.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace trackwheel::periodic {

namespace {

constexpr int kScanPerPanel = 4;    // scan points per half zone for the minima of |1 + s S|
constexpr double kPoleStrip = 0.5;  // poles kept within this many half zones of the real axis
constexpr int kSecantSteps = 30;

// real roots in (lo, hi) of D(k + 2 pi q / d, Omega - k v) = 0 over q, with their q
void free_poles(const Line& line, double lo, double hi, std::vector<double>& ks,
                std::vector<int>& qs) {
  const Track& tr = line.track();
  const PeriodicTrackParams& p = tr.params();
  const double d = tr.bay(), g = 2.0 * kPi / d, v = line.speed(), om = line.omega();
  const int q0 = static_cast<int>(std::floor(-hi / g)) - 3;
  const int q1 = static_cast<int>(std::ceil(-lo / g)) + 3;
  for (int q = q0; q <= q1; ++q) {
    const double W = om + v * g * q;  // w' = W - v x, x = k_q
    cd roots[4];
    int nr = 0;
    if (!tr.timoshenko()) {
      // EI x^4 - m (W - v x)^2 = (a x^2 - c (W - v x)) (a x^2 + c (W - v x))
      const double a = std::sqrt(p.EI), c = std::sqrt(p.mass);
      for (double sg : {1.0, -1.0}) {
        const cd disc = std::sqrt(cd((c * v) * (c * v) + 4.0 * a * sg * c * W, 0.0));
        roots[nr++] = (-sg * c * v + disc) / (2.0 * a);
        roots[nr++] = (-sg * c * v - disc) / (2.0 * a);
      }
    } else {
      // G EI x^4 - (G J + m EI) w^2 x^2 - m G w^2 + m J w^4, w = W - v x: a quartic in x
      const double G = p.shear, J = p.rotary, EI = p.EI, m = p.mass;
      // w^2 = W^2 - 2 W v x + v^2 x^2 (coefficients by power of x)
      const double w2[3] = {W * W, -2.0 * W * v, v * v};
      double w4[5] = {0, 0, 0, 0, 0};
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) w4[i + j] += w2[i] * w2[j];
      double poly[5] = {0, 0, 0, 0, G * EI};
      for (int i = 0; i < 3; ++i) poly[i + 2] -= (G * J + m * EI) * w2[i];
      for (int i = 0; i < 3; ++i) poly[i] -= m * G * w2[i];
      for (int i = 0; i < 5; ++i) poly[i] += m * J * w4[i];
      int deg = 4;
      while (deg > 0 && poly[deg] == 0.0) --deg;
      if (deg < 1) continue;
      Eigen::MatrixXd comp = Eigen::MatrixXd::Zero(deg, deg);
      for (int i = 1; i < deg; ++i) comp(i, i - 1) = 1.0;
      for (int i = 0; i < deg; ++i) comp(i, deg - 1) = -poly[i] / poly[deg];
      Eigen::EigenSolver<Eigen::MatrixXd> es(comp, false);
      for (int i = 0; i < deg; ++i) roots[nr++] = es.eigenvalues()(i);
    }
    for (int i = 0; i < nr; ++i) {
      const cd k = roots[i] - g * q;
      if (!std::isfinite(k.real()) || std::abs(k.imag()) > 1e-9 * (1.0 + std::abs(k.real())))
        continue;
      if (k.real() <= lo || k.real() >= hi || om - k.real() * v == 0.0) continue;
      ks.push_back(k.real());
      qs.push_back(q);
    }
  }
}

}  // namespace

std::vector<Pole> find_poles(const Line& line, const std::vector<double>& edges, long& evals) {
  const Track& tr = line.track();
  const double d = tr.bay(), half = kPi / d, lo = edges.front(), hi = edges.back();
  std::vector<cd> starts;
  // the local minima of |1 + s S| on a scan
  std::vector<double> scan;
  for (std::size_t e = 0; e + 1 < edges.size(); ++e)
    for (int i = 0; i < kScanPerPanel; ++i)
      scan.push_back(edges[e] + (edges[e + 1] - edges[e]) * (i + 0.5) / kScanPerPanel);
  std::vector<double> mag(scan.size());
  for (std::size_t i = 0; i < scan.size(); ++i) mag[i] = std::abs(line.den_real(scan[i]));
  evals += static_cast<long>(scan.size());
  for (std::size_t i = 1; i + 1 < scan.size(); ++i)
    if (mag[i] < mag[i - 1] && mag[i] < mag[i + 1]) starts.emplace_back(scan[i], 0.0);
  // next to the free rail's poles: 1 + s S = 0 at first order where
  // k - k_p = -s / (d D' (1 + s S_q')), D' = dD(k_q, Omega - k v)/dk along the line
  std::vector<double> kp;
  std::vector<int> qp;
  free_poles(line, lo, hi, kp, qp);
  const double v = line.speed(), om = line.omega(), g = 2.0 * kPi / d;
  for (std::size_t i = 0; i < kp.size(); ++i) {
    const double k = kp[i], w = om - k * v, eps = 1e-6 * (1.0 + std::abs(k));
    const cd s = tr.support(w);
    const cd excl = tr.lattice_sum_excluding(k, w, qp[i]);
    const cd Dp = 1.0 / tr.inverse_stiffness(k + eps + g * qp[i], w - eps * v);
    const cd Dm = 1.0 / tr.inverse_stiffness(k - eps + g * qp[i], w + eps * v);
    const cd start = k - s / (d * (Dp - Dm) / (2.0 * eps) * (1.0 + s * excl));
    if (std::isfinite(start.real()) && std::isfinite(start.imag())) starts.push_back(start);
  }
  // secant iterations, steps limited to a quarter half zone
  std::vector<cd> found;
  const double limit = 0.25 * half;
  for (cd k : starts) {
    cd k_old = k + 1e-4 * half * cd(1.0, 1.0);
    cd f_old = line.den(k_old), f = line.den(k);
    bool ok = std::isfinite(std::abs(f));
    for (int it = 0; ok && it < kSecantSteps; ++it) {
      cd dk = f * (k - k_old) / (f - f_old);
      if (!std::isfinite(dk.real()) || !std::isfinite(dk.imag())) dk = 0.0;
      const double n2 = std::norm(dk);
      if (n2 > limit * limit) dk *= limit / std::sqrt(n2);
      k_old = k;
      f_old = f;
      k -= dk;
      f = line.den(k);
      ++evals;
      const double fn = std::norm(f);
      if (!std::isfinite(fn)) ok = false;
      if (std::norm(dk) < 1e-22 * half * half) break;
      // a start without a zero nearby wanders with |1 + s S| ~ 1 (a shallow minimum of the
      // scan, far from any resonance): give it up
      if ((it >= 8 && fn > 0.5) || std::abs(k.imag()) > 4.0 * kPoleStrip * half) ok = false;
    }
    if (ok && std::abs(f) < 1e-9 && std::abs(k.imag()) < kPoleStrip * half && k.real() > lo &&
        k.real() < hi)
      found.push_back(k);
  }
  std::sort(found.begin(), found.end(), [](cd a, cd b) {
    return a.real() < b.real() || (a.real() == b.real() && a.imag() < b.imag());
  });
  std::vector<Pole> poles;
  for (std::size_t i = 0; i < found.size(); ++i) {
    bool dup = false;
    for (const Pole& p : poles)
      if (std::abs(p.k - found[i]) <= 1e-8 * half) dup = true;
    if (dup) continue;
    Pole p;
    p.k = found[i];
    const double step = std::clamp(1e-2 * std::abs(p.k.imag()), 1e-9, 1e-4) * half;
    const cd slope = line.den_slope(p.k, step);
    p.h.resize(line.size());
    line.h_at(p.k, p.h.data());
    const cd w = om - p.k * v;
    p.rho = -d * tr.support(w) / slope;
    if (std::isfinite(std::abs(p.rho)) && p.h.allFinite()) poles.push_back(std::move(p));
  }
  return poles;
}

}  // namespace trackwheel::periodic
