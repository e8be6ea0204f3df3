#include "eigen_analysis.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <stdexcept>

#include "sleepers.hpp"

namespace trackwheel {

namespace {

// Free coordinates of one direction (component 0: x, 1: y) in full numbering.
std::vector<int> direction_dofs(const RailModel& rail, int component) {
  std::vector<int> idx;
  for (int i = 0; i < rail.n_dof(); ++i)
    if (rail.full_to_free()[i] >= 0 && (i % 2) == component) idx.push_back(i);
  return idx;
}

// The sleepers' rows and columns from index z0 on: RailModel's tangent already holds the pads as
// springs to the ground, k_p s_j s_j^T; the pad's other end is z_j.
void add_sleepers(const RailModel& rail, const std::vector<int>& local, int z0, Eigen::MatrixXd& K,
                  Eigen::MatrixXd& M) {
  const Sleepers sl(rail);
  for (int j = 0; j < sl.size(); ++j) {
    const int z = z0 + j;
    M(z, z) = sl.mass(j);
    K(z, z) = sl.pad_stiffness(j) + sl.ballast_stiffness(j);
    for (int a = 0; a < 4; ++a) {
      const int i = local[sl.index(j, a)];
      if (i < 0) continue;
      K(i, z) -= sl.pad_stiffness(j) * sl.weight(j, a);
      K(z, i) -= sl.pad_stiffness(j) * sl.weight(j, a);
    }
  }
}

void solve_pencil(const Eigen::MatrixXd& K, const Eigen::MatrixXd& M, int n_modes,
                  Eigen::VectorXd& f, Eigen::MatrixXd& V) {
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(
      K, M, Eigen::ComputeEigenvectors | Eigen::Ax_lBx);
  if (es.info() != Eigen::Success) throw std::runtime_error("eigenvalue solve failed");
  const Eigen::VectorXd w2 = es.eigenvalues();
  f.resize(n_modes);
  for (int k = 0; k < n_modes; ++k) f(k) = std::sqrt(std::max(w2(k), 0.0)) / (2.0 * M_PI);
  V = es.eigenvectors().leftCols(n_modes);
}

}  // namespace

ModalResult vertical_modes(const RailModel& rail, double wheel_mass, double contact_stiffness,
                           const std::vector<double>& positions, int n_modes) {
  const std::vector<int> ydofs = direction_dofs(rail, 1);
  const int ny = static_cast<int>(ydofs.size());
  const bool with_wheel = wheel_mass > 0.0;
  const int ns = Sleepers(rail).size(), z0 = ny + (with_wheel ? 1 : 0);
  const int n = z0 + ns;
  if (n_modes < 1 || n_modes > n)
    throw std::invalid_argument("n_modes must be in [1, " + std::to_string(n) + "]");
  const Eigen::MatrixXd Kfull = rail.tangent_dense(rail.reference());
  const Eigen::MatrixXd Mfull = rail.mass_dense();
  Eigen::MatrixXd K0 = Eigen::MatrixXd::Zero(n, n), M0 = Eigen::MatrixXd::Zero(n, n);
  for (int a = 0; a < ny; ++a)
    for (int b = 0; b < ny; ++b) {
      K0(a, b) = Kfull(ydofs[a], ydofs[b]);
      M0(a, b) = Mfull(ydofs[a], ydofs[b]);
    }
  std::vector<int> local(rail.n_dof(), -1);
  for (int a = 0; a < ny; ++a) local[ydofs[a]] = a;
  add_sleepers(rail, local, z0, K0, M0);

  ModalResult out;
  const int npos = with_wheel ? static_cast<int>(positions.size()) : 1;
  out.frequencies.resize(npos, n_modes);
  for (int p = 0; p < npos; ++p) {
    Eigen::MatrixXd K = K0, M = M0;
    if (with_wheel) {
      M(ny, ny) = wheel_mass;
      // k (Y_w - s^T e)^2 / 2 with s the y-row of S(X) on the y coordinates
      Eigen::VectorXd g = Eigen::VectorXd::Zero(n);
      const MeshPoint mp = rail.locate(positions[p]);
      for (int a = 0; a < 4; ++a) {
        const int j = local[mp.dof0() + 2 * a + 1];
        if (j >= 0) g(j) = -mp.h.n[a];
      }
      g(ny) = 1.0;
      K += contact_stiffness * g * g.transpose();
    }
    Eigen::VectorXd f;
    Eigen::MatrixXd V;
    solve_pencil(K, M, n_modes, f, V);
    out.frequencies.row(p) = f.transpose();
    Eigen::MatrixXd S = Eigen::MatrixXd::Zero(rail.n_dof() + 1 + ns, n_modes);
    for (int a = 0; a < ny; ++a) S.row(ydofs[a]) = V.row(a);
    if (with_wheel) S.row(rail.n_dof()) = V.row(ny);
    for (int j = 0; j < ns; ++j) S.row(rail.n_dof() + 1 + j) = V.row(z0 + j);
    out.shapes.push_back(S);
  }
  return out;
}

ModalResult axial_modes(const RailModel& rail, int n_modes) {
  const std::vector<int> xdofs = direction_dofs(rail, 0);
  const int nx = static_cast<int>(xdofs.size());
  if (n_modes < 1 || n_modes > nx)
    throw std::invalid_argument("n_modes must be in [1, " + std::to_string(nx) + "]");
  const Eigen::MatrixXd Kfull = rail.tangent_dense(rail.reference());
  const Eigen::MatrixXd Mfull = rail.mass_dense();
  Eigen::MatrixXd K(nx, nx), M(nx, nx);
  for (int a = 0; a < nx; ++a)
    for (int b = 0; b < nx; ++b) {
      K(a, b) = Kfull(xdofs[a], xdofs[b]);
      M(a, b) = Mfull(xdofs[a], xdofs[b]);
    }
  Eigen::VectorXd f;
  Eigen::MatrixXd V;
  solve_pencil(K, M, n_modes, f, V);
  ModalResult out;
  out.frequencies = f.transpose();
  Eigen::MatrixXd S = Eigen::MatrixXd::Zero(rail.n_dof(), n_modes);
  for (int a = 0; a < nx; ++a) S.row(xdofs[a]) = V.row(a);
  out.shapes.push_back(S);
  return out;
}

}  // namespace trackwheel
