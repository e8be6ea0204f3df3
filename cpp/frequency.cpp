#include "frequency.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <stdexcept>
#include <string>

#include "band_lu.hpp"
#include "eigen_analysis.hpp"
#include "linear_rail.hpp"

namespace trackwheel {

namespace {

using cd = std::complex<double>;

void require(bool ok, const std::string& msg) {
  if (!ok) throw std::invalid_argument(msg);
}

void check_position(const RailModel& rail, const char* name, double x) {
  const double L = rail.params().length;
  require(std::isfinite(x) && x >= 0.0 && x <= L, std::string(name) + " = " + std::to_string(x) +
                                                      " m is outside the rail; allowed range [0, " +
                                                      std::to_string(L) + "] m");
}

// The w shape functions at X as a sparse vector over the y coordinates: (index, value) pairs.
struct Coupling {
  int idx[4];
  double n[4];
};

Coupling coupling(const LinearTrack& tr, double X) {
  const BeamPoint bp = tr.point(X);
  Coupling c;
  for (int a = 0; a < 4; ++a) {
    c.idx[a] = tr.y_of_full[4 * bp.element + 2 * a + 1];
    c.n[a] = bp.n[a];
  }
  return c;
}

// The layered supports' sleeper correction, or none: (support coupling, m_s, k_b, c_b, k_p, c_p).
struct Layer {
  Coupling s;
  double ms, kb, cb, kp, cp;
};

std::vector<Layer> layers(const RailModel& rail, const LinearTrack& tr) {
  const SupportParams& sp = rail.supports();
  const size_t n = sp.position.size();
  std::vector<Layer> out;
  if (sp.sleeper_mass.empty()) return out;
  const std::vector<bool> closed = ballast_states(rail);  // open: no ballast
  require(sp.sleeper_mass.size() == n && sp.ballast_stiffness.size() == n &&
              sp.ballast_damping.size() == n,
          "sleeper_mass, ballast_stiffness and ballast_damping must have one entry per support");
  for (size_t j = 0; j < n; ++j) {
    require(std::isfinite(sp.sleeper_mass[j]) && sp.sleeper_mass[j] > 0.0,
            "sleeper_mass must be > 0 kg");
    require(std::isfinite(sp.ballast_stiffness[j]) && sp.ballast_stiffness[j] >= 0.0,
            "ballast_stiffness must be >= 0 N/m");
    require(std::isfinite(sp.ballast_damping[j]) && sp.ballast_damping[j] >= 0.0,
            "ballast_damping must be >= 0 N s/m");
    out.push_back({coupling(tr, sp.position[j]), sp.sleeper_mass[j],
                   closed[j] ? sp.ballast_stiffness[j] : 0.0,
                   closed[j] ? sp.ballast_damping[j] : 0.0, sp.stiffness[j], sp.damping[j]});
  }
  return out;
}

// Z(w) = K + i w C - w^2 M (+ the sleeper correction) into the pivoted band LU's storage.
void dynamic_stiffness(const LinearTrack& tr, const std::vector<Layer>& lay, double w,
                       BandLU<cd>& Z) {
  Z.set_zero();
  const int n = tr.nq;
  for (int i = 0; i < n; ++i)
    for (int j = std::max(0, i - 3); j <= std::min(n - 1, i + 3); ++j)
      Z.at(i, j) = cd(tr.K.at(i, j) - w * w * tr.M.at(i, j), w * tr.C.at(i, j));
  for (const Layer& l : lay) {
    const cd sp(l.kp, w * l.cp), sb(l.kb - l.ms * w * w, w * l.cb);
    const cd dk = sp * sb / (sp + sb) - sp;
    for (int a = 0; a < 4; ++a) {
      if (l.s.idx[a] < 0) continue;
      for (int b = 0; b < 4; ++b)
        if (l.s.idx[b] >= 0) Z.at(l.s.idx[a], l.s.idx[b]) += dk * l.s.n[a] * l.s.n[b];
    }
  }
}

}  // namespace

Eigen::MatrixXcd receptance(const RailModel& rail, const BeamParams& beam,
                            const std::vector<double>& x_force, const std::vector<double>& x_resp,
                            const std::vector<double>& freqs) {
  for (double x : x_force) check_position(rail, "x", x);
  for (double x : x_resp) check_position(rail, "x_response", x);
  for (double f : freqs)
    require(std::isfinite(f) && f >= 0.0,
            "freqs must be finite and >= 0 Hz, got " + std::to_string(f) + " Hz");
  const LinearTrack tr(rail, 0, beam);
  const std::vector<Layer> lay = layers(rail, tr);
  std::vector<Coupling> fe, re;
  for (double x : x_force) fe.push_back(coupling(tr, x));
  for (double x : x_resp) re.push_back(coupling(tr, x));
  BandLU<cd> Z;
  Z.resize(tr.nq, 3);
  Eigen::VectorXcd q(tr.nq);
  const auto n_resp = static_cast<Eigen::Index>(re.size());
  Eigen::MatrixXcd out(freqs.size(), fe.size() * re.size());
  for (size_t k = 0; k < freqs.size(); ++k) {
    dynamic_stiffness(tr, lay, 2.0 * M_PI * freqs[k], Z);
    if (!Z.factorize())
      throw std::runtime_error("the dynamic stiffness is singular at " + std::to_string(freqs[k]) +
                               " Hz (an undamped resonance): shift the frequency or add damping");
    for (size_t e = 0; e < fe.size(); ++e) {
      q.setZero();
      for (int a = 0; a < 4; ++a)
        if (fe[e].idx[a] >= 0) q(fe[e].idx[a]) += fe[e].n[a];
      Z.solve_in_place(q);
      for (size_t r = 0; r < re.size(); ++r) {
        cd y = 0.0;
        for (int a = 0; a < 4; ++a)
          if (re[r].idx[a] >= 0) y += re[r].n[a] * q(re[r].idx[a]);
        out(static_cast<Eigen::Index>(k),
            static_cast<Eigen::Index>(e) * n_resp + static_cast<Eigen::Index>(r)) = y;
      }
    }
  }
  return out;
}

Eigen::MatrixXd track_modes(const RailModel& rail, const BeamParams& beam, double wheel_mass,
                            double contact_stiffness, const std::vector<double>& positions,
                            int n_modes, std::vector<Eigen::MatrixXd>* shapes) {
  const LinearTrack tr(rail, 0, beam);
  require(rail.supports().sleeper_mass.empty(),
          "track_modes: layered supports are not in the linear track's eigen analysis");
  const bool with_wheel = wheel_mass > 0.0;
  const int ny = tr.ny, n = ny + (with_wheel ? 1 : 0);
  require(n_modes >= 1 && n_modes <= n, "n_modes must be in [1, " + std::to_string(n) + "]");
  require(n <= limits::kMaxDenseEigenDof, "track_modes: the dense eigen analysis takes at most " +
                                              std::to_string(limits::kMaxDenseEigenDof) +
                                              " coordinates, this mesh has " + std::to_string(n));
  Eigen::MatrixXd K0 = Eigen::MatrixXd::Zero(n, n), M0 = Eigen::MatrixXd::Zero(n, n);
  K0.topLeftCorner(ny, ny) = tr.K.dense();
  M0.topLeftCorner(ny, ny) = tr.M.dense();
  const int npos = with_wheel ? static_cast<int>(positions.size()) : 1;
  Eigen::MatrixXd freqs(npos, n_modes);
  for (int p = 0; p < npos; ++p) {
    Eigen::MatrixXd K = K0, M = M0;
    if (with_wheel) {
      check_position(rail, "positions", positions[p]);
      M(ny, ny) = wheel_mass;
      // k (Y_w - s^T q)^2 / 2
      Eigen::VectorXd g = Eigen::VectorXd::Zero(n);
      const Coupling c = coupling(tr, positions[p]);
      for (int a = 0; a < 4; ++a)
        if (c.idx[a] >= 0) g(c.idx[a]) = -c.n[a];
      g(ny) = 1.0;
      K += contact_stiffness * g * g.transpose();
    }
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(K, M);
    if (es.info() != Eigen::Success) throw std::runtime_error("eigenvalue solve failed");
    for (int k = 0; k < n_modes; ++k)
      freqs(p, k) = std::sqrt(std::max(es.eigenvalues()(k), 0.0)) / (2.0 * M_PI);
    if (shapes) shapes->push_back(es.eigenvectors().leftCols(n_modes));
  }
  return freqs;
}

}  // namespace trackwheel
