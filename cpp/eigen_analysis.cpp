#include "eigen_analysis.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <stdexcept>
#include <string>

#include "limits.hpp"
#include "sleepers.hpp"
#include "statics.hpp"

namespace trackwheel {

namespace {

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

// The sleepers' rows and columns from local index z0 on: the rail's band already holds the pads
// as springs and dampers to the ground, (k_p, c_p) s_j s_j^T; the pad's other end is z_j. A
// sleeper off its ballast (closed[j] false) has no ballast.
template <class Push>
void add_sleepers(const Sleepers& sl, const std::vector<bool>& closed,
                  const std::vector<int>& local, int z0, int ns, Push& push) {
  for (int j = 0; j < ns; ++j) {
    const int z = z0 + j;
    const double kp = sl.pad_stiffness(j), cp = sl.pad_damping(j);
    for (int a = 0; a < 4; ++a) {
      const int i = local[sl.index(j, a)];
      if (i < 0) continue;
      const double w = sl.weight(j, a);
      push(i, z, -kp * w, 0.0, -cp * w);
      push(z, i, -kp * w, 0.0, -cp * w);
    }
    if (closed[j])
      push(z, z, kp + sl.ballast_stiffness(j), sl.mass(j), cp + sl.ballast_damping(j));
    else
      push(z, z, kp, sl.mass(j), cp);
  }
}

void check_dense_size(int n, int n_modes) {
  if (n_modes < 1 || n_modes > n)
    throw std::invalid_argument("n_modes must be in [1, " + std::to_string(n) + "]");
  if (n > limits::kMaxDenseEigenDof)
    throw std::invalid_argument(
        "the dense eigen analysis takes at most " + std::to_string(limits::kMaxDenseEigenDof) +
        " coordinates, this mesh has " + std::to_string(n) + " (use the sparse method)");
}

void to_dense(const SparsePencil& p, Eigen::MatrixXd& K, Eigen::MatrixXd& M) {
  K = Eigen::MatrixXd::Zero(p.n, p.n);
  M = Eigen::MatrixXd::Zero(p.n, p.n);
  for (size_t t = 0; t < p.row.size(); ++t) {
    K(p.row[t], p.col[t]) += p.K[t];
    M(p.row[t], p.col[t]) += p.M[t];
  }
}

}  // namespace

std::vector<bool> ballast_states(const RailModel& rail) {
  const Sleepers sl(rail);
  if (!sl.unilateral()) return std::vector<bool>(sl.size(), true);
  return solve_track_static(rail).closed;
}

SparsePencil direction_pencil(const RailModel& rail, int component, double wheel_mass,
                              double contact_stiffness, double position) {
  if (component != 0 && component != 1) throw std::invalid_argument("component must be 0 or 1");
  const auto& f2f = rail.full_to_free();
  SparsePencil p;
  std::vector<int> local(rail.n_dof(), -1);
  for (int i = 0; i < rail.n_dof(); ++i)
    if (f2f[i] >= 0 && (i % 2) == component) {
      local[i] = static_cast<int>(p.dofs.size());
      p.dofs.push_back(i);
    }
  const int nr = static_cast<int>(p.dofs.size());
  const bool with_wheel = component == 1 && wheel_mass > 0.0;
  const Sleepers sl(rail);
  const int ns = component == 1 ? sl.size() : 0, z0 = nr + (with_wheel ? 1 : 0);
  p.n = z0 + ns;
  BandMatrix Kb(rail.n_free(), kHalfBandwidth);
  rail.add_tangent(rail.reference(), 1.0, Kb);
  const BandMatrix &Mb = rail.mass(), &Cb = rail.support_damping();
  // the wheel's coupling g: V = k/2 (g . [e; Y_w])^2, g = [-S_y(X) on the rail, 1]
  std::vector<double> g(p.n, 0.0);
  if (with_wheel) {
    const MeshPoint mp = rail.locate(position);
    for (int a = 0; a < 4; ++a) {
      const int j = local[mp.dof0() + 2 * a + 1];
      if (j >= 0) g[j] = -mp.h.n[a];
    }
    g[nr] = 1.0;
  }
  auto push = [&p](int a, int b, double k, double m, double c) {
    if (k == 0.0 && m == 0.0 && c == 0.0) return;
    p.row.push_back(a);
    p.col.push_back(b);
    p.K.push_back(k);
    p.M.push_back(m);
    p.C.push_back(c);
  };
  // a coordinate of one direction couples with those of its own and the two neighbouring nodes
  for (int a = 0; a < nr; ++a)
    for (int b = std::max(0, a - 4); b <= std::min(nr - 1, a + 4); ++b) {
      const int i = f2f[p.dofs[a]], j = f2f[p.dofs[b]];
      if (!Kb.in_band(i, j)) continue;
      push(a, b, Kb.at(i, j) + contact_stiffness * g[a] * g[b], Mb.at(i, j), Cb.at(i, j));
    }
  if (with_wheel) {  // the wheel's row and column: only the contact spring to the rail
    for (int a = 0; a < nr; ++a) {
      push(a, nr, contact_stiffness * g[a], 0.0, 0.0);
      push(nr, a, contact_stiffness * g[a], 0.0, 0.0);
    }
    push(nr, nr, contact_stiffness, wheel_mass, 0.0);
  }
  add_sleepers(sl, ballast_states(rail), local, z0, ns, push);
  return p;
}

ModalResult vertical_modes(const RailModel& rail, double wheel_mass, double contact_stiffness,
                           const std::vector<double>& positions, int n_modes) {
  const bool with_wheel = wheel_mass > 0.0;
  const int ns = Sleepers(rail).size();
  const int npos = with_wheel ? static_cast<int>(positions.size()) : 1;
  ModalResult out;
  out.frequencies.resize(npos, n_modes < 1 ? 0 : n_modes);
  for (int p = 0; p < npos; ++p) {
    const SparsePencil pen =
        direction_pencil(rail, 1, wheel_mass, contact_stiffness, with_wheel ? positions[p] : 0.0);
    check_dense_size(pen.n, n_modes);
    Eigen::MatrixXd K, M, V;
    to_dense(pen, K, M);
    Eigen::VectorXd f;
    solve_pencil(K, M, n_modes, f, V);
    out.frequencies.row(p) = f.transpose();
    // local order: rail coordinates, the wheel's Y_w, the sleepers' z (direction_pencil)
    const int nr = static_cast<int>(pen.dofs.size()), z0 = nr + (with_wheel ? 1 : 0);
    Eigen::MatrixXd S = Eigen::MatrixXd::Zero(rail.n_dof() + 1 + ns, n_modes);
    for (int a = 0; a < nr; ++a) S.row(pen.dofs[a]) = V.row(a);
    if (with_wheel) S.row(rail.n_dof()) = V.row(nr);
    for (int j = 0; j < ns; ++j) S.row(rail.n_dof() + 1 + j) = V.row(z0 + j);
    out.shapes.push_back(S);
  }
  return out;
}

ModalResult axial_modes(const RailModel& rail, int n_modes) {
  const SparsePencil pen = direction_pencil(rail, 0, 0.0, 0.0, 0.0);
  check_dense_size(pen.n, n_modes);
  Eigen::MatrixXd K, M, V;
  to_dense(pen, K, M);
  Eigen::VectorXd f;
  solve_pencil(K, M, n_modes, f, V);
  ModalResult out;
  out.frequencies = f.transpose();
  Eigen::MatrixXd S = Eigen::MatrixXd::Zero(rail.n_dof(), n_modes);
  for (int a = 0; a < pen.n; ++a) S.row(pen.dofs[a]) = V.row(a);
  out.shapes.push_back(S);
  return out;
}

}  // namespace trackwheel
