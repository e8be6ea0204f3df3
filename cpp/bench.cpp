#include "bench.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "banded.hpp"

namespace trackwheel {

double time_band_factor_solve(const RailModel& rail, double cq, double cv, int repeats,
                              bool bordered) {
  if (repeats < 1) throw std::invalid_argument("repeats must be >= 1");
  const int nf = rail.n_free();
  BandMatrix J0(nf, kHalfBandwidth), J;
  J0.set_linear_combination(1.0, rail.mass(), cv, rail.support_damping());
  rail.add_tangent(rail.reference(), cq, J0);
  // border: the wheel couples to the 8 coordinates of one element in the middle of the rail
  constexpr int m = 3;
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(nf, m), C = Eigen::MatrixXd::Zero(m, nf);
  Eigen::MatrixXd D = Eigen::MatrixXd::Identity(m, m);
  const int i0 = std::max(0, nf / 2 - 4);
  for (int a = 0; a < 8 && i0 + a < nf; ++a) {
    B(i0 + a, 0) = 1e-3 * (a + 1);
    B(i0 + a, 2) = -0.5 + 0.1 * a;
    C(2, i0 + a) = 0.5 - 0.1 * a;
  }
  const Eigen::VectorXd r1 = Eigen::VectorXd::LinSpaced(nf, 1.0, 2.0);
  const Eigen::VectorXd r2 = Eigen::VectorXd::Ones(m);
  Eigen::VectorXd x1 = r1, x2;
  BorderedSolver solver;
  double sink = 0.0;  // keeps the optimiser from dropping the work
  const auto t0 = std::chrono::steady_clock::now();
  for (int k = 0; k < repeats; ++k) {
    J = J0;
    if (bordered) {
      if (!solver.factorize(J, B, C, D)) throw std::runtime_error("singular matrix");
      solver.solve(r1, r2, x1, x2);
    } else {
      if (!J.factorize()) throw std::runtime_error("singular matrix");
      x1 = r1;
      J.solve_in_place(x1);
    }
    sink += x1(k % nf);
  }
  const auto t1 = std::chrono::steady_clock::now();
  if (!std::isfinite(sink)) throw std::runtime_error("non-finite solution");
  return std::chrono::duration<double>(t1 - t0).count() / repeats;
}

}  // namespace trackwheel
