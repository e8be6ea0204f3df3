// The linear vertical rail of the fast path (docs: Model § Rail (linearised), § Eigen analysis):
// the Euler-Bernoulli Hermite beam in y (exactly the ANCF element linearised about the straight
// rail, its y coordinates only) or the Timoshenko beam of linear_beam.hpp on linear supports, with
// constant band matrices M, C, K over generalised coordinates q: the y coordinates, or the lowest
// n_modes mass-normalised modes (q = Phi z).
#pragma once

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "banded.hpp"
#include "limits.hpp"
#include "linear_beam.hpp"
#include "rail.hpp"

namespace trackwheel {

// The linear vertical track in generalised coordinates q (y coordinates, or modal).
struct LinearTrack {
  int ny = 0, nq = 0, bw = 3;
  bool modal = false;
  std::vector<int> full_of_y;  // y coordinate -> full ANCF index
  std::vector<int> y_of_full;  // full -> y coordinate (-1)
  BandMatrix M, C, K;          // over q
  Eigen::VectorXd Qg;          // over q
  Eigen::MatrixXd Phi;         // ny x nq (modal only)
  const RailModel* rail = nullptr;

  BeamParams beam;  // Euler-Bernoulli (default) or Timoshenko

  LinearTrack(const RailModel& r, int n_modes, const BeamParams& beam_params = BeamParams())
      : rail(&r), beam(beam_params) {
    const auto& f2f = r.full_to_free();
    y_of_full.assign(r.n_dof(), -1);
    for (int i = 0; i < r.n_dof(); ++i)
      if (f2f[i] >= 0 && i % 2 == 1) {
        y_of_full[i] = static_cast<int>(full_of_y.size());
        full_of_y.push_back(i);
      }
    ny = static_cast<int>(full_of_y.size());
    BandMatrix My, Cy, Ky;
    Eigen::VectorXd Qgy;
    linear_beam(r, beam, full_of_y, y_of_full, My, Cy, Ky, Qgy);
    if (n_modes <= 0) {
      nq = ny;
      M = My;
      C = Cy;
      K = Ky;
      Qg = Qgy;
      return;
    }
    if (n_modes > ny)
      throw std::invalid_argument("n_modes must be in [1, " + std::to_string(ny) + "]");
    // the reduction is a dense generalised eigenproblem: O(ny^2) memory, O(ny^3) time
    if (ny > limits::kMaxDenseEigenDof)
      throw std::invalid_argument("modal reduction (n_modes) takes at most " +
                                  std::to_string(limits::kMaxDenseEigenDof) +
                                  " vertical coordinates, this mesh has " + std::to_string(ny) +
                                  " (use all coordinates: n_modes = None)");
    modal = true;
    nq = n_modes;
    bw = nq - 1;
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(Ky.dense(), My.dense());
    if (es.info() != Eigen::Success) throw std::runtime_error("modal reduction failed");
    Phi = es.eigenvectors().leftCols(nq);  // mass-normalised
    const Eigen::MatrixXd Cm = Phi.transpose() * Cy.dense() * Phi;
    M.resize(nq, bw);
    C.resize(nq, bw);
    K.resize(nq, bw);
    for (int a = 0; a < nq; ++a) {
      M.at(a, a) = 1.0;
      K.at(a, a) = es.eigenvalues()(a);
      for (int b = 0; b < nq; ++b) C.at(a, b) = Cm(a, b);
    }
    Qg = Phi.transpose() * Qgy;
  }

  // The generalised-coordinate vector of the y coordinate with full ANCF index i (zero if fixed):
  // a unit vector, or a row of Phi.
  Eigen::VectorXd basis(int i) const {
    const int k = y_of_full[i];
    if (k < 0) return Eigen::VectorXd::Zero(nq);
    if (modal) return Phi.row(k).transpose();
    Eigen::VectorXd e = Eigen::VectorXd::Zero(nq);
    e(k) = 1.0;
    return e;
  }

  // The element under X and its w shape functions (Hermite for Euler-Bernoulli).
  BeamPoint point(double X) const { return beam_point(*rail, beam, X); }

  // s(X), s_s(X), s_ss(X) over q: y(X) = s . q etc. Over the y coordinates the vectors are
  // filled in place (the time loop calls this every step: no allocation once they are sized).
  void coupling(double X, Eigen::VectorXd& s, Eigen::VectorXd& ss, Eigen::VectorXd& sss) const {
    const BeamPoint bp = point(X);
    if (modal) {
      Eigen::VectorXd y, ys, yss;
      y_coupling(bp, y, ys, yss);
      s = Phi.transpose() * y;
      ss = Phi.transpose() * ys;
      sss = Phi.transpose() * yss;
    } else {
      y_coupling(bp, s, ss, sss);
    }
  }

 private:
  // The w shape functions of the element at bp over the y coordinates.
  void y_coupling(const BeamPoint& bp, Eigen::VectorXd& y, Eigen::VectorXd& ys,
                  Eigen::VectorXd& yss) const {
    y.setZero(ny);
    ys.setZero(ny);
    yss.setZero(ny);
    for (int a = 0; a < 4; ++a) {
      const int k = y_of_full[4 * bp.element + 2 * a + 1];
      if (k < 0) continue;
      y(k) = bp.n[a];
      ys(k) = bp.ns[a];
      yss(k) = bp.nss[a];
    }
  }
};

}  // namespace trackwheel
