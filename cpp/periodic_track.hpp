// The periodic track's building blocks for the moving-load receptance (periodic.hpp; docs:
// Model § The periodic level): the free rail's dynamic stiffness D(k, w), the supports' s(w) and
// the lattice sum S(k, w) in closed form (Track), and the integrand along the line
// w' = Omega - k v for the harmonics -n..n (Line). Internal to periodic*.cpp; defined inline, as
// the quadrature evaluates them at every point.
#pragma once

#include <cmath>
#include <complex>

#include "periodic.hpp"

namespace trackwheel::periodic {

using cd = std::complex<double>;
constexpr double kPi = 3.14159265358979323846;
constexpr double kCancellation = 1e3;  // |s h_m| above which the diagonal avoids cancelling

// cot(x + i y) = (sin 2x - i sinh 2y) / (cosh 2y - cos 2x), written with exp(-2|y|) so that it
// does not overflow: (2 e sin 2x - i sign(y) (1 - e^2)) / (1 + e^2 - 2 e cos 2x), e = exp(-2|y|)
inline cd cot(cd z) {
  const double e = std::exp(-2.0 * std::abs(z.imag()));
  const double s2 = std::sin(2.0 * z.real()), c2 = std::cos(2.0 * z.real());
  const double den = 1.0 + e * e - 2.0 * e * c2;
  return cd(2.0 * e * s2, -std::copysign(1.0 - e * e, z.imag())) / den;
}

// g(z) = cot z - 1/z, smooth at 0: its Taylor series near 0, else directly
inline cd cot_minus_inverse(cd z) {
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

}  // namespace trackwheel::periodic
