#include "periodic.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

namespace trackwheel {

namespace {

using cd = std::complex<double>;
constexpr double kPi = 3.14159265358979323846;

// 15-point Kronrod abscissae (positive half, descending) and weights, and the embedded 7-point
// Gauss weights on xgk[1], xgk[3], xgk[5], xgk[7] (QUADPACK qk15; Piessens et al. 1983).
constexpr double kXgk[8] = {
    0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
    0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
    0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
    0.207784955007898467600689403773245, 0.0};
constexpr double kWgk[8] = {
    0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
    0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
    0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
    0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
constexpr double kWg[4] = {0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
                           0.381830050505118944950369775488975,
                           0.417959183673469387755102040816327};

constexpr int kExtraZones = 4;      // zones beyond the highest harmonic in [-K, K]
constexpr int kScanPerPanel = 4;    // scan points per half zone for the minima of |1 + s S|
constexpr double kPoleStrip = 0.5;  // poles kept within this many half zones of the real axis
constexpr int kSecantSteps = 30;
constexpr double kCancellation = 1e3;  // |s h_m| above which the diagonal avoids cancelling
constexpr int kMaxRounds = 40;
constexpr std::size_t kMaxPanels = 20000;

struct Rule {
  double x[15], wk[15], wd[15];  // nodes on [-1, 1], Kronrod weights, Kronrod - Gauss
  Rule() {
    for (int i = 0; i < 7; ++i) {
      x[i] = -kXgk[i];
      x[14 - i] = kXgk[i];
      wk[i] = wk[14 - i] = kWgk[i];
    }
    x[7] = 0.0;
    wk[7] = kWgk[7];
    double wg[15] = {0};
    for (int j = 0; j < 4; ++j) {
      const int i = 2 * j + 1;  // xgk[1], [3], [5], [7]
      wg[i] = kWg[j];
      wg[14 - i] = kWg[j];
    }
    for (int i = 0; i < 15; ++i) wd[i] = wk[i] - wg[i];
  }
};
const Rule kRule;

// cot(x + i y) = (sin 2x - i sinh 2y) / (cosh 2y - cos 2x), written with exp(-2|y|) so that it
// does not overflow: (2 e sin 2x - i sign(y) (1 - e^2)) / (1 + e^2 - 2 e cos 2x), e = exp(-2|y|)
cd cot(cd z) {
  const double e = std::exp(-2.0 * std::abs(z.imag()));
  const double s2 = std::sin(2.0 * z.real()), c2 = std::cos(2.0 * z.real());
  const double den = 1.0 + e * e - 2.0 * e * c2;
  return cd(2.0 * e * s2, -std::copysign(1.0 - e * e, z.imag())) / den;
}

// g(z) = cot z - 1/z, smooth at 0: its Taylor series near 0, else directly
cd cot_minus_inverse(cd z) {
  static const double b[7] = {1.0 / 3.0,     1.0 / 45.0,           2.0 / 945.0,     1.0 / 4725.0,
                              2.0 / 93555.0, 1382.0 / 638512875.0, 4.0 / 18243225.0};
  if (std::abs(z) < 0.3) {
    const cd z2 = z * z;
    cd acc = 0.0;
    for (int i = 6; i >= 0; --i) acc = acc * z2 + b[i];
    return -z * acc;
  }
  return cot(z) - 1.0 / z;
}

class Track {
 public:
  explicit Track(const PeriodicTrackParams& p) : p_(p), timo_(p.shear > 0.0) {}
  double bay() const { return p_.bay; }

  // 1 / D(k, w) [m^2/N]
  cd inverse_stiffness(cd k, cd w) const {
    const cd w2 = w * w, k2 = k * k;
    if (!timo_) return 1.0 / (p_.EI * k2 * k2 - p_.mass * w2);
    const double G = p_.shear, J = p_.rotary, EI = p_.EI, m = p_.mass;
    const cd q = G * EI * k2 * k2 - (G * J + m * EI) * w2 * k2 - m * w2 * (G - J * w2);
    return (EI * k2 + G - J * w2) / q;
  }

  // 1/D = c1 / (k^2 - a1^2) + c2 / (k^2 - a2^2) at w != 0
  void fractions(cd w, cd a2[2], cd c[2]) const {
    const cd w2 = w * w;
    const double EI = p_.EI, m = p_.mass;
    if (!timo_) {
      const cd lam2 = std::sqrt(m * w2 / EI);
      a2[0] = lam2;
      a2[1] = -lam2;
      c[0] = 1.0 / (2.0 * EI * lam2);
      c[1] = -c[0];
      return;
    }
    const double G = p_.shear, J = p_.rotary;
    const double alpha = G * EI;
    const cd beta = (G * J + m * EI) * w2, gamma = m * w2 * (G - J * w2);
    cd root = std::sqrt(beta * beta + 4.0 * alpha * gamma);
    if (std::abs(beta - root) > std::abs(beta + root)) root = -root;
    a2[0] = (beta + root) / (2.0 * alpha);
    a2[1] = -gamma / (alpha * a2[0]);
    const cd rest = G - J * w2;
    c[0] = (EI * a2[0] + rest) / (alpha * (a2[0] - a2[1]));
    c[1] = (EI * a2[1] + rest) / (alpha * (a2[1] - a2[0]));
  }

  // S(k, w) [m/N]
  cd lattice_sum(cd k, cd w) const {
    cd a2[2], c[2];
    fractions(w, a2, c);
    const cd x = 0.5 * p_.bay * k;
    cd out = 0.0;
    for (int r = 0; r < 2; ++r) {
      const cd a = std::sqrt(a2[r]), y = 0.5 * p_.bay * a;
      out += c[r] / (4.0 * a) * (cot(x - y) - cot(x + y));
    }
    return out;
  }

  // S(k, w) without its term q = shift [m/N]
  cd lattice_sum_excluding(cd k, cd w, double shift) const {
    cd a2[2], c[2];
    fractions(w, a2, c);
    const cd x = 0.5 * p_.bay * (k + 2.0 * kPi * shift / p_.bay);
    cd out = 0.0;
    for (int r = 0; r < 2; ++r) {
      const cd a = std::sqrt(a2[r]), y = 0.5 * p_.bay * a;
      out += c[r] / (4.0 * a) * (cot_minus_inverse(x - y) - cot_minus_inverse(x + y));
    }
    return out;
  }

  // 1 / D(k, w) [m^2/N] for real k and w: real (the rail is undamped)
  double inverse_stiffness(double k, double w) const {
    const double w2 = w * w, k2 = k * k;
    if (!timo_) return 1.0 / (p_.EI * k2 * k2 - p_.mass * w2);
    const double G = p_.shear, J = p_.rotary, EI = p_.EI, m = p_.mass;
    const double q = G * EI * k2 * k2 - (G * J + m * EI) * w2 * k2 - m * w2 * (G - J * w2);
    return (EI * k2 + G - J * w2) / q;
  }

  // S(k, w) [m/N] for real k and w != 0: real. Per root a^2 of the partial fractions: a real
  // root gives c / (4a) (cot(x - y) - cot(x + y)), an imaginary one a = i alpha gives
  // c sinh(2y) / (2 alpha (cosh 2y - cos 2x)) (x = k d/2, y = |a| d/2), written with
  // exp(-2y) so that it does not overflow.
  double lattice_sum(double k, double w) const {
    double a2[2], c[2];
    const double w2 = w * w, EI = p_.EI, m = p_.mass;
    if (!timo_) {
      const double lam2 = std::sqrt(m * w2 / EI);
      a2[0] = lam2;
      a2[1] = -lam2;
      c[0] = 1.0 / (2.0 * EI * lam2);
      c[1] = -c[0];
    } else {
      const double G = p_.shear, J = p_.rotary, alpha = G * EI;
      const double beta = (G * J + m * EI) * w2, gamma = m * w2 * (G - J * w2);
      const double root = std::sqrt(beta * beta + 4.0 * alpha * gamma);  // real for w != 0
      a2[0] = (beta + root) / (2.0 * alpha);
      a2[1] = -gamma / (alpha * a2[0]);
      const double rest = G - J * w2;
      c[0] = (EI * a2[0] + rest) / (alpha * (a2[0] - a2[1]));
      c[1] = (EI * a2[1] + rest) / (alpha * (a2[1] - a2[0]));
    }
    const double x = 0.5 * p_.bay * k;
    double out = 0.0;
    for (int r = 0; r < 2; ++r) {
      if (a2[r] >= 0.0) {
        const double a = std::sqrt(a2[r]), y = 0.5 * p_.bay * a;
        out += c[r] / (4.0 * a) * (1.0 / std::tan(x - y) - 1.0 / std::tan(x + y));
      } else {
        const double al = std::sqrt(-a2[r]), y = 0.5 * p_.bay * al;
        const double e2 = std::exp(-2.0 * y), e4 = e2 * e2;
        out += c[r] / (2.0 * al) * (1.0 - e4) / (1.0 + e4 - 2.0 * std::cos(2.0 * x) * e2);
      }
    }
    return out;
  }

  // s(w) [N/m]
  cd support(cd w) const {
    const cd sp = p_.pad_stiffness + cd(0.0, 1.0) * w * p_.pad_damping;
    if (p_.sleeper_mass <= 0.0) return sp;
    const cd sb =
        p_.ballast_stiffness + cd(0.0, 1.0) * w * p_.ballast_damping - p_.sleeper_mass * w * w;
    return sp * sb / (sp + sb);
  }

  const PeriodicTrackParams& params() const { return p_; }
  bool timoshenko() const { return timo_; }

 private:
  PeriodicTrackParams p_;
  bool timo_;
};

// The integrand along the line w' = Omega - k v for the harmonics -n..n
class Line {
 public:
  Line(const Track& tr, double speed, double omega, int n)
      : tr_(tr), v_(speed), om_(omega), n_(n), M_(2 * n + 1) {}
  int size() const { return M_; }
  double speed() const { return v_; }
  double omega() const { return om_; }
  const Track& track() const { return tr_; }

  // k moved by a relative 1e-12 where w' is exactly 0 (a removable point of the integrand)
  template <class T>
  T off_static(T k) const {
    if (v_ > 0.0 && om_ - k * v_ == T(0.0)) return k * (1.0 + 1e-12) + 1e-12;
    return k;
  }

  cd den(cd k) const {
    k = off_static(k);
    const cd w = om_ - k * v_;
    return 1.0 + tr_.support(w) * tr_.lattice_sum(k, w);
  }

  // 1 + s S at real k (the real lattice sum)
  cd den_real(double k) const {
    k = off_static(k);
    const double w = om_ - k * v_;
    return 1.0 + tr_.support(w) * tr_.lattice_sum(k, w);
  }

  // d(1 + s S)/dk by the fourth-order central difference
  cd den_slope(cd k, double step) const {
    return (den(k - 2.0 * step) - 8.0 * den(k - step) + 8.0 * den(k + step) - den(k + 2.0 * step)) /
           (12.0 * step);
  }

  // h (M, real: the free rail is undamped), c and the diagonal (M) at real k (docs of
  // periodic.hpp). Where |s h_m| is large the diagonal's two terms d h_m and c h_m^2 nearly
  // cancel: there it is d h_m (1 + s S_m') / (1 + s S), S_m' the lattice sum without term m.
  void parts(double k, double* h, cd& c, cd* diag) const {
    k = off_static(k);
    const double d = tr_.bay(), w = om_ - k * v_;
    const cd s = tr_.support(w);
    const double abs_s = std::abs(s);
    const cd den = 1.0 + s * tr_.lattice_sum(k, w);
    const cd inv_den = std::conj(den) / std::norm(den);
    c = -d * s * inv_den;
    const double g = 2.0 * kPi / d, k0 = k - n_ * g;
    for (int q = 0; q < M_; ++q) h[q] = tr_.inverse_stiffness(k0 + q * g, w) / d;  // vectorised
    for (int q = 0; q < M_; ++q) {
      if (abs_s * std::abs(h[q]) > kCancellation) {
        const cd excl = tr_.lattice_sum_excluding(cd(k), cd(w), q - n_);
        diag[q] = d * h[q] * (1.0 + s * excl) * inv_den;
      } else {
        diag[q] = d * h[q] + c * (h[q] * h[q]);
      }
    }
  }

  // h (M) at complex k (the poles' residues)
  void h_at(cd k, cd* h) const {
    k = off_static(k);
    const cd w = om_ - k * v_;
    for (int q = 0; q < M_; ++q)
      h[q] = tr_.inverse_stiffness(k + 2.0 * kPi * (q - n_) / tr_.bay(), w) / tr_.bay();
  }

 private:
  const Track& tr_;
  double v_, om_;
  int n_, M_;
};

struct Pole {
  cd k, rho;
  Eigen::VectorXcd h;
};

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

struct Panel {
  double a, b;
  int kind;  // 0 central (k), 1 right tail, 2 left tail (u, k = +-K / u)
};

struct PanelResult {
  std::vector<Eigen::MatrixXcd> rank;   // per offset: Kronrod sum of w c h h^T (upper triangle)
  std::vector<Eigen::VectorXcd> diag;   // per offset: Kronrod sum of w diag
  std::vector<std::pair<int, cd>> fix;  // (pole, exact - Kronrod integral of 1/(k - k_c))
  double err = 0.0;
};

}  // namespace

std::complex<double> periodic_lattice_sum(const PeriodicTrackParams& track, std::complex<double> k,
                                          std::complex<double> w) {
  return Track(track).lattice_sum(k, w);
}

std::vector<Eigen::MatrixXcd> periodic_receptance_matrix(const PeriodicTrackParams& p, double speed,
                                                         double omega, int n,
                                                         const std::vector<double>& offsets,
                                                         double rtol, PeriodicStats* stats) {
  auto finite_pos = [](double x) { return std::isfinite(x) && x > 0.0; };
  if (!finite_pos(p.bay) || !finite_pos(p.EI) || !finite_pos(p.mass) || p.shear < 0.0 ||
      p.rotary < 0.0 || !finite_pos(p.pad_stiffness) || p.pad_damping < 0.0 || p.sleeper_mass < 0.0)
    throw std::invalid_argument("periodic track: bay, EI, mass, pad stiffness must be > 0");
  if (!(speed >= 0.0) || !std::isfinite(omega) || (speed == 0.0 && omega == 0.0))
    throw std::invalid_argument("periodic receptance: speed >= 0 and omega != 0 when speed = 0");
  if (n < 0 || n > 200) throw std::invalid_argument("periodic receptance: n in [0, 200]");
  const Track tr(p);
  const Line line(tr, speed, omega, n);
  const int M = line.size(), n_off = static_cast<int>(offsets.size()), i0 = n;
  const double d = tr.bay(), half = kPi / d;
  const int zones = n + kExtraZones;
  const double K = 2.0 * kPi * zones / d;
  std::vector<double> edges;
  for (int j = -2 * zones; j <= 2 * zones; ++j) edges.push_back(j * half);
  if (speed > 0.0 && std::abs(omega / speed) < K) {
    const double k0 = omega / speed;
    if (std::find(edges.begin(), edges.end(), k0) == edges.end()) {
      edges.push_back(k0);
      std::sort(edges.begin(), edges.end());
    }
  }
  PeriodicStats local;
  PeriodicStats& st = stats ? *stats : local;
  st = PeriodicStats();
  const std::vector<Pole> poles = find_poles(line, edges, st.den_evaluations);
  st.poles = static_cast<int>(poles.size());
  const int nc = static_cast<int>(poles.size());
  // pole amplitudes rho e^{i k_c Delta} and their error proxies (diagonal, column 0)
  Eigen::MatrixXcd amp(n_off, nc);
  for (int j = 0; j < n_off; ++j)
    for (int c = 0; c < nc; ++c)
      amp(j, c) = poles[c].rho * std::exp(cd(0.0, 1.0) * poles[c].k * offsets[j]);

  std::vector<Panel> panels;
  for (std::size_t e = 0; e + 1 < edges.size(); ++e) panels.push_back({edges[e], edges[e + 1], 0});
  const double tails[5] = {0.0, 0.125, 0.25, 0.5, 1.0};
  for (int kind = 1; kind <= 2; ++kind)
    for (int i = 0; i < 4; ++i) panels.push_back({tails[i], tails[i + 1], kind});

  std::vector<Eigen::MatrixXcd> rank(n_off, Eigen::MatrixXcd::Zero(M, M));
  std::vector<Eigen::VectorXcd> diag(n_off, Eigen::VectorXcd::Zero(M));
  Eigen::VectorXcd fix = Eigen::VectorXcd::Zero(nc);
  double scale = 0.0;
  std::vector<cd> dg(M);
  Eigen::MatrixXd H(M, 15), Wr(15, n_off), Wi(15, n_off), Rr(M, M), Ri(M, M);
  for (int round = 0; round < kMaxRounds; ++round) {
    const std::size_t P = panels.size();
    st.rounds = round + 1;
    st.points += 15 * static_cast<long>(P);
    std::vector<PanelResult> res(P);
    double err_sum = 0.0;
    Eigen::VectorXcd est = Eigen::VectorXcd::Zero(M);  // the diagonal so far, for the scale
    for (int j = 0; j < n_off && j < 1; ++j) est = diag[j];
    for (std::size_t ip = 0; ip < P; ++ip) {
      const Panel& pn = panels[ip];
      PanelResult& r = res[ip];
      r.rank.assign(n_off, Eigen::MatrixXcd(M, M));
      r.diag.assign(n_off, Eigen::VectorXcd::Zero(M));
      std::vector<Eigen::VectorXcd> ed(n_off, Eigen::VectorXcd::Zero(M)),
          ec(n_off, Eigen::VectorXcd::Zero(M));
      // the poles subtracted here: within one panel width of the (central) panel
      std::vector<int> near;
      if (pn.kind == 0)
        for (int c = 0; c < nc; ++c) {
          const cd kc = poles[c].k;
          const double dx = std::max({pn.a - kc.real(), kc.real() - pn.b, 0.0});
          const double width = pn.b - pn.a;
          if (dx * dx + kc.imag() * kc.imag() < width * width) near.push_back(c);
        }
      std::vector<cd> lk(near.size(), 0.0), ld(near.size(), 0.0);
      const double mid = 0.5 * (pn.a + pn.b), hw = 0.5 * (pn.b - pn.a);
      for (int i = 0; i < 15; ++i) {
        const double t = mid + hw * kRule.x[i];
        double k = t, jac = hw;
        if (pn.kind > 0) {
          k = (pn.kind == 2 ? -K : K) / t;
          jac = hw * K / (t * t);
        }
        cd c;
        line.parts(k, H.col(i).data(), c, dg.data());
        const double wk = jac * kRule.wk[i] / (2.0 * kPi), wd = jac * kRule.wd[i] / (2.0 * kPi);
        for (std::size_t a = 0; a < near.size(); ++a) {
          const cd z = k - poles[near[a]].k;
          const cd inv = std::conj(z) / std::norm(z);
          lk[a] += wk * inv;
          ld[a] += wd * inv;
        }
        for (int j = 0; j < n_off; ++j) {
          const cd ph = offsets[j] == 0.0 ? cd(1.0) : std::exp(cd(0.0, k * offsets[j]));
          const cd wck = wk * c * ph, wkp = wk * ph, wdp = wd * ph;
          Wr(i, j) = wck.real();
          Wi(i, j) = wck.imag();
          const cd wdc = wdp * c * H(i0, i);
          for (int b = 0; b < M; ++b) {
            r.diag[j](b) += wkp * dg[b];
            ed[j](b) += wdp * dg[b];
            ec[j](b) += (b == i0 ? wdp * dg[b] : wdc * H(b, i));
          }
        }
      }
      // the rank-one part: sum_i w_i c_i h_i h_i^T, h real (upper triangle suffices)
      for (int j = 0; j < n_off; ++j) {
        Rr.noalias() = H * Wr.col(j).asDiagonal() * H.transpose();
        Ri.noalias() = H * Wi.col(j).asDiagonal() * H.transpose();
        r.rank[j].real() = Rr;
        r.rank[j].imag() = Ri;
      }
      // exact integrals of the subtracted pole terms over this panel
      for (std::size_t a = 0; a < near.size(); ++a) {
        const cd kc = poles[near[a]].k;
        const cd exact = (std::log(pn.b - kc) - std::log(pn.a - kc)) / (2.0 * kPi);
        r.fix.emplace_back(near[a], exact - lk[a]);
      }
      double err = 0.0;
      for (int j = 0; j < n_off; ++j) {
        for (std::size_t a = 0; a < near.size(); ++a) {
          const Pole& pl = poles[near[a]];
          const cd f = ld[a] * amp(j, near[a]);
          for (int b = 0; b < M; ++b) {
            ed[j](b) -= f * pl.h(b) * pl.h(b);
            ec[j](b) -= f * pl.h(b) * pl.h(i0);
          }
        }
        err = std::max({err, ed[j].cwiseAbs().maxCoeff(), ec[j].cwiseAbs().maxCoeff()});
      }
      r.err = std::isfinite(err) ? err : std::numeric_limits<double>::infinity();
      err_sum += r.err;
      est += r.diag[0];
    }
    scale = std::max(scale, est.cwiseAbs().maxCoeff());
    const double tol = rtol * scale;
    std::vector<char> accept(P, 1);
    if (err_sum > tol) {
      std::vector<std::size_t> order(P);
      std::iota(order.begin(), order.end(), 0);
      std::sort(order.begin(), order.end(),
                [&](std::size_t x, std::size_t y) { return res[x].err > res[y].err; });
      double rest = err_sum;
      for (std::size_t i = 0; i < P; ++i) {
        accept[order[i]] = 0;
        rest -= res[order[i]].err;
        if (rest <= 0.5 * tol) break;
      }
    }
    std::vector<Panel> next;
    for (std::size_t ip = 0; ip < P; ++ip) {
      if (accept[ip]) {
        for (int j = 0; j < n_off; ++j) {
          rank[j] += res[ip].rank[j];
          diag[j] += res[ip].diag[j];
        }
        for (const auto& [c, v] : res[ip].fix) fix(c) += v;
      } else {
        const Panel& pn = panels[ip];
        const double m = 0.5 * (pn.a + pn.b);
        next.push_back({pn.a, m, pn.kind});
        next.push_back({m, pn.b, pn.kind});
      }
    }
    if (next.empty()) {
      std::vector<Eigen::MatrixXcd> out(n_off);
      for (int j = 0; j < n_off; ++j) {
        Eigen::MatrixXcd A = rank[j];
        for (int b = 0; b < M; ++b) A(b, b) = diag[j](b);  // the stable diagonal
        if (nc > 0) {  // the poles' exact-minus-Kronrod terms: sum_c f_c h_c h_c^T
          Eigen::MatrixXcd Hc(M, nc);
          Eigen::VectorXcd f(nc);
          for (int c = 0; c < nc; ++c) {
            Hc.col(c) = poles[c].h;
            f(c) = fix(c) * amp(j, c);
          }
          A.noalias() += Hc * f.asDiagonal() * Hc.transpose();
        }
        out[j] = A;
      }
      return out;
    }
    if (next.size() > kMaxPanels) break;
    panels.swap(next);
  }
  throw std::runtime_error(
      "the k quadrature of the moving-load receptance did not converge to rtol = " +
      std::to_string(rtol) + " (speed " + std::to_string(speed) + " m/s, frequency " +
      std::to_string(omega / (2.0 * kPi)) +
      " Hz): the tolerance is below the integrand's round-off, or the track is nearly undamped "
      "at a wave the wheel excites (a larger rtol, or more support damping)");
}

}  // namespace trackwheel
