#include "static_line.hpp"

#include <algorithm>
#include <stdexcept>

#include "linear_rail.hpp"
#include "linear_system.hpp"
#include "linear_track.hpp"
#include "sleepers.hpp"

namespace trackwheel {

BandMatrix band_selected_inverse(const BandMatrix& lu) {
  const int n = lu.size(), b = lu.half_bandwidth();
  BandMatrix Z(n, b);
  for (int i = n - 1; i >= 0; --i) {
    const int kend = std::min(n - 1, i + b);
    const double uii = lu.at(i, i);
    for (int j = kend; j >= i; --j) {  // Z_ii last: it needs this row's Z_ik, k > i
      double sum = j == i ? 1.0 : 0.0;
      for (int k = i + 1; k <= kend; ++k) sum -= lu.at(i, k) * (k <= j ? Z.at(k, j) : Z.at(j, k));
      Z.at(i, j) = sum / uii;
      Z.at(j, i) = Z.at(i, j);
    }
  }
  return Z;
}

Eigen::VectorXd linear_static_line_selected(const RailModel& rail, const BeamParams& beam,
                                            double load, const std::vector<double>& x,
                                            bool element_compliance) {
  const Sleepers sl(rail);
  if (sl.unilateral()) return linear_static_line(rail, beam, load, x, 0, element_compliance);
  const LinearTrack tr(rail, 0, beam);
  LinearRest rest(tr, sl);
  Eigen::VectorXd q_g = tr.Qg, z;  // the track under its own weight
  rest.solve(q_g, z);
  // K with the sleepers condensed at rest, as LinearRest factorises it
  Sleepers at_rest(sl);
  at_rest.set_coefficients(0.0, 0.0, 1.0);
  BandMatrix K = tr.K;
  at_rest.condense_matrix(tr.y_of_full, K);
  if (!K.factorize()) throw std::runtime_error("rail stiffness is singular");
  const BandMatrix Z = band_selected_inverse(K);
  const double l = rail.element_length();
  const double cs = beam.timoshenko() ? 1.0 / beam.shear_stiffness : 0.0;
  Eigen::VectorXd y(static_cast<Eigen::Index>(x.size()));
  for (std::size_t i = 0; i < x.size(); ++i) {
    const BeamPoint bp = tr.point(x[i]);
    int k[4];
    for (int a = 0; a < 4; ++a) k[a] = tr.y_of_full[4 * bp.element + 2 * a + 1];
    double yi = 0.0, flex = 0.0;  // s . q_g and s^T K^-1 s
    for (int a = 0; a < 4; ++a) {
      if (k[a] < 0) continue;  // a fixed end
      yi += bp.n[a] * q_g(k[a]);
      for (int c = 0; c < 4; ++c) {
        if (k[c] < 0) continue;
        if (!Z.in_band(k[a], k[c]))  // the element's coordinates are neighbours in K's band
          throw std::logic_error("linear_static_line_selected: element outside the band");
        flex += bp.n[a] * bp.n[c] * Z.at(k[a], k[c]);
      }
    }
    yi -= load * flex;
    if (element_compliance)  // the element's own deflection under the load
      yi -= load * fixed_end_compliance(rail.params().EI, cs, l, bp.xi * l).G;
    y(static_cast<Eigen::Index>(i)) = yi;
  }
  return y;
}

}  // namespace trackwheel
