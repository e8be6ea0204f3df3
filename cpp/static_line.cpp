#include "static_line.hpp"

#include <algorithm>
#include <stdexcept>

#include "linear_rail.hpp"
#include "linear_system.hpp"
#include "linear_track.hpp"
#include "sleepers.hpp"

namespace trackwheel {

BandInverse::BandInverse(const BandMatrix& lu, int m) : m_(m) {
  const int n = lu.size(), b = lu.half_bandwidth();
  if (m < b) throw std::invalid_argument("BandInverse: width below the half bandwidth");
  up_ = Eigen::MatrixXd::Zero(m + 1, n);
  for (int i = n - 1; i >= 0; --i) {
    const int kend = std::min(n - 1, i + b);
    const double uii = lu.at(i, i);
    for (int j = std::min(n - 1, i + m); j >= i; --j) {  // Z_ii last: it needs this row's Z_ik
      double sum = j == i ? 1.0 : 0.0;
      for (int k = i + 1; k <= kend; ++k) sum -= lu.at(i, k) * at(k, j);
      up_(j - i, i) = sum / uii;
    }
  }
}

namespace {

// The linear track's K with the sleepers condensed at rest, factorised (as LinearRest has it).
BandMatrix rest_stiffness(const LinearTrack& tr, const Sleepers& sl) {
  Sleepers at_rest(sl);
  at_rest.set_coefficients(0.0, 0.0, 1.0);
  BandMatrix K = tr.K;
  at_rest.condense_matrix(tr.y_of_full, K);
  if (!K.factorize()) throw std::runtime_error("rail stiffness is singular");
  return K;
}

// The y coordinates (-1: fixed) and w shape functions of the element under X.
struct ElementPoint {
  int k[4];
  double n[4];
  double xi;
};

ElementPoint element_point(const LinearTrack& tr, double X) {
  const BeamPoint bp = tr.point(X);
  ElementPoint p{};
  for (int a = 0; a < 4; ++a) {
    p.k[a] = tr.y_of_full[4 * bp.element + 2 * a + 1];
    p.n[a] = bp.n[a];
  }
  p.xi = bp.xi;
  return p;
}

// s(a)^T Z s(b) over the entries of Z within its width.
double flexibility(const BandInverse& Z, const ElementPoint& a, const ElementPoint& b) {
  double f = 0.0;
  for (int i = 0; i < 4; ++i) {
    if (a.k[i] < 0) continue;
    for (int j = 0; j < 4; ++j) {
      if (b.k[j] < 0) continue;
      if (!Z.covers(a.k[i], b.k[j]))
        throw std::logic_error("static line: a coordinate pair outside the selected inverse");
      f += a.n[i] * b.n[j] * Z.at(a.k[i], b.k[j]);
    }
  }
  return f;
}

}  // namespace

Eigen::VectorXd linear_static_line_selected(const RailModel& rail, const BeamParams& beam,
                                            double load, const std::vector<double>& x,
                                            bool element_compliance) {
  const Sleepers sl(rail);
  if (sl.unilateral()) return linear_static_line(rail, beam, load, x, 0, element_compliance);
  const LinearTrack tr(rail, 0, beam);
  LinearRest rest(tr, sl);
  Eigen::VectorXd q_g = tr.Qg, z;  // the track under its own weight
  rest.solve(q_g, z);
  const BandInverse Z(rest_stiffness(tr, sl), tr.K.half_bandwidth());
  const double l = rail.element_length();
  const double cs = beam.timoshenko() ? 1.0 / beam.shear_stiffness : 0.0;
  Eigen::VectorXd y(static_cast<Eigen::Index>(x.size()));
  for (std::size_t i = 0; i < x.size(); ++i) {
    const ElementPoint p = element_point(tr, x[i]);
    double yi = 0.0;  // s . q_g
    for (int a = 0; a < 4; ++a)
      if (p.k[a] >= 0) yi += p.n[a] * q_g(p.k[a]);
    yi -= load * flexibility(Z, p, p);  // s^T K^-1 s P
    if (element_compliance)             // the element's own deflection under the load
      yi -= load * fixed_end_compliance(rail.params().EI, cs, l, p.xi * l).G;
    y(static_cast<Eigen::Index>(i)) = yi;
  }
  return y;
}

Eigen::VectorXd linear_static_flexibility(const RailModel& rail, const BeamParams& beam,
                                          const std::vector<double>& xa,
                                          const std::vector<double>& xb) {
  if (xa.size() != xb.size())
    throw std::invalid_argument("linear_static_flexibility: xa and xb differ in length");
  const LinearTrack tr(rail, 0, beam);
  const Sleepers sl(rail);
  const BandMatrix K = rest_stiffness(tr, sl);
  std::vector<ElementPoint> pa, pb;
  int m = K.half_bandwidth();
  for (std::size_t i = 0; i < xa.size(); ++i) {
    pa.push_back(element_point(tr, xa[i]));
    pb.push_back(element_point(tr, xb[i]));
    for (int a = 0; a < 4; ++a)
      for (int c = 0; c < 4; ++c)
        if (pa.back().k[a] >= 0 && pb.back().k[c] >= 0)
          m = std::max(m, std::abs(pa.back().k[a] - pb.back().k[c]));
  }
  Eigen::VectorXd f(static_cast<Eigen::Index>(xa.size()));
  if (static_cast<double>(m + 1) * K.size() <= kMaxInverseEntries) {
    const BandInverse Z(K, m);
    for (std::size_t i = 0; i < xa.size(); ++i)
      f(static_cast<Eigen::Index>(i)) = flexibility(Z, pa[i], pb[i]);
    return f;
  }
  Eigen::VectorXd u(tr.nq);  // the band too wide to hold: K^-1 s(xb) per pair
  for (std::size_t i = 0; i < xa.size(); ++i) {
    u.setZero();
    for (int c = 0; c < 4; ++c)
      if (pb[i].k[c] >= 0) u(pb[i].k[c]) = pb[i].n[c];
    K.solve_in_place(u);
    double fi = 0.0;
    for (int a = 0; a < 4; ++a)
      if (pa[i].k[a] >= 0) fi += pa[i].n[a] * u(pa[i].k[a]);
    f(static_cast<Eigen::Index>(i)) = fi;
  }
  return f;
}

}  // namespace trackwheel
