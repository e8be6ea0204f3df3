#include "banded.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace trackwheel {

void BandMatrix::resize(int n, int half_bandwidth) {
  n_ = n;
  b_ = half_bandwidth;
  data_ = Eigen::MatrixXd::Zero(2 * b_ + 1, n_);
}

void BandMatrix::multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  // column-oriented: column j of the band is contiguous in data_
  y.setZero(n_);
  const int w = 2 * b_ + 1;
  const double* d = data_.data();
  for (int j = 0; j < n_; ++j) {
    const int i0 = std::max(0, j - b_), i1 = std::min(n_ - 1, j + b_);
    const double xj = x(j);
    const double* col = d + static_cast<std::ptrdiff_t>(j) * w + b_ - j;  // col[i] = A(i, j)
    for (int i = i0; i <= i1; ++i) y(i) += col[i] * xj;
  }
}

Eigen::MatrixXd BandMatrix::dense() const {
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n_, n_);
  for (int j = 0; j < n_; ++j) {
    const int i0 = std::max(0, j - b_), i1 = std::min(n_ - 1, j + b_);
    for (int i = i0; i <= i1; ++i) A(i, j) = at(i, j);
  }
  return A;
}

bool BandMatrix::factorize() {
  for (int k = 0; k < n_; ++k) {
    const double piv = at(k, k);
    if (!(std::abs(piv) > 0.0) || !std::isfinite(piv)) return false;
    const int iend = std::min(n_ - 1, k + b_);
    for (int i = k + 1; i <= iend; ++i) {
      const double l = at(i, k) / piv;
      at(i, k) = l;
      if (l == 0.0) continue;
      for (int j = k + 1; j <= iend; ++j) at(i, j) -= l * at(k, j);
    }
  }
  return true;
}

void BandMatrix::solve_in_place(Eigen::Ref<Eigen::VectorXd> x) const {
  // column-oriented forward and back substitution (contiguous band columns)
  const int w = 2 * b_ + 1;
  const double* d = data_.data();
  double* xv = x.data();
  for (int j = 0; j < n_; ++j) {  // L y = x (unit lower)
    const double xj = xv[j];
    if (xj == 0.0) continue;
    const double* col = d + static_cast<std::ptrdiff_t>(j) * w + b_ - j;
    const int i1 = std::min(n_ - 1, j + b_);
    for (int i = j + 1; i <= i1; ++i) xv[i] -= col[i] * xj;
  }
  for (int j = n_ - 1; j >= 0; --j) {  // U x = y
    const double* col = d + static_cast<std::ptrdiff_t>(j) * w + b_ - j;
    const double xj = xv[j] / col[j];
    xv[j] = xj;
    const int i0 = std::max(0, j - b_);
    for (int i = i0; i < j; ++i) xv[i] -= col[i] * xj;
  }
}

std::pair<int, int> BandMatrix::solve_local(Eigen::Ref<Eigen::VectorXd> x, int first, int last,
                                            double negligible) const {
  const int w = 2 * b_ + 1;
  const double* d = data_.data();
  double* xv = x.data();
  double top = 0.0;
  int run = 0, hi = n_;
  for (int j = first; j < n_; ++j) {  // L y = x (unit lower), from the first non-zero
    const double xj = xv[j];
    top = std::max(top, std::abs(xj));
    run = (j > last && std::abs(xj) <= negligible * top) ? run + 1 : 0;
    if (run > b_) {  // the rest is fed by negligible entries only
      hi = j + 1;
      for (int i = j + 1; i <= std::min(n_ - 1, j + b_); ++i) xv[i] = 0.0;
      break;
    }
    if (xj == 0.0) continue;
    const double* col = d + static_cast<std::ptrdiff_t>(j) * w + b_ - j;
    const int i1 = std::min(n_ - 1, j + b_);
    for (int i = j + 1; i <= i1; ++i) xv[i] -= col[i] * xj;
  }
  top = 0.0;
  run = 0;
  int lo = 0;
  for (int j = hi - 1; j >= 0; --j) {  // U x = y
    const double* col = d + static_cast<std::ptrdiff_t>(j) * w + b_ - j;
    const double xj = xv[j] / col[j];
    xv[j] = xj;
    top = std::max(top, std::abs(xj));
    run = (j < first && std::abs(xj) <= negligible * top) ? run + 1 : 0;
    if (run > b_) {
      lo = j;
      for (int i = std::max(0, j - b_); i < j; ++i) xv[i] = 0.0;
      break;
    }
    const int i0 = std::max(0, j - b_);
    for (int i = i0; i < j; ++i) xv[i] -= col[i] * xj;
  }
  return {lo, hi};
}

void BandMatrix::set_linear_combination(double a, const BandMatrix& A, double b,
                                        const BandMatrix& B) {
  data_ = a * A.data_ + b * B.data_;
}

void BandMatrix::add_scaled(double a, const BandMatrix& A) { data_ += a * A.data_; }

void LocalColumns::resize(int n, int m) {
  M_.setZero(n, m);
  lo_.assign(m, 0);
  hi_.assign(m, 0);
}

void LocalColumns::solve(const BandMatrix& A, int k, int first, int last) {
  std::tie(lo_[k], hi_[k]) = A.solve_local(M_.col(k), first, last, kNegligible);
}

void LocalColumns::clear(int k) {
  M_.col(k).setZero();
  lo_[k] = hi_[k] = 0;
}

void LocalColumns::subtract(const Eigen::VectorXd& c, Eigen::VectorXd& x) const {
  for (int k = 0; k < static_cast<int>(M_.cols()); ++k)
    x.segment(lo_[k], hi_[k] - lo_[k]) -= c(k) * M_.col(k).segment(lo_[k], hi_[k] - lo_[k]);
}

bool BorderedSolver::factorize(BandMatrix& A, const Eigen::MatrixXd& B, const Eigen::MatrixXd& C,
                               const Eigen::MatrixXd& D) {
  if (!A.factorize()) return false;
  return factorize_border(A, B, C, D);
}

bool BorderedSolver::factorize_border(const BandMatrix& A, const Eigen::MatrixXd& B,
                                      const Eigen::MatrixXd& C, const Eigen::MatrixXd& D) {
  A_ = &A;
  m_ = static_cast<int>(D.rows());
  if (m_ == 0) return true;
  Z_.resize(static_cast<int>(B.rows()), m_);
  for (int k = 0; k < m_; ++k) {
    int first = 0, last = static_cast<int>(B.rows()) - 1;
    while (first <= last && B(first, k) == 0.0) ++first;
    while (last >= first && B(last, k) == 0.0) --last;
    if (first > last) continue;  // a zero column stays zero
    Z_.col(k) = B.col(k);
    Z_.solve(A, k, first, last);
  }
  c_row_.clear();
  c_col_.clear();
  c_val_.clear();
  for (int j = 0; j < C.cols(); ++j)
    for (int i = 0; i < m_; ++i)
      if (C(i, j) != 0.0) {
        c_row_.push_back(i);
        c_col_.push_back(j);
        c_val_.push_back(C(i, j));
      }
  Eigen::MatrixXd S = D;  // D - C Z over C's non-zeros
  for (std::size_t k = 0; k < c_val_.size(); ++k)
    S.row(c_row_[k]) -= c_val_[k] * Z_.matrix().row(c_col_[k]);
  if (!S.allFinite()) return false;
  schur_.compute(S);
  const double det = schur_.determinant();
  return std::isfinite(det) && det != 0.0;
}

void BorderedSolver::solve(const Eigen::VectorXd& r1, const Eigen::VectorXd& r2,
                           Eigen::VectorXd& x1, Eigen::VectorXd& x2) const {
  x1 = r1;
  A_->solve_in_place(x1);
  if (m_ == 0) {
    x2.resize(0);
    return;
  }
  // the products into buffers (no allocation per solve)
  rhs_ = r2;
  for (std::size_t k = 0; k < c_val_.size(); ++k) rhs_(c_row_[k]) -= c_val_[k] * x1(c_col_[k]);
  x2 = schur_.solve(rhs_);
  Z_.subtract(x2, x1);
}

void SplitBorderedSolver::resize(int n, int n_groups, int group_size, int m) {
  n_ = n;
  gs_ = group_size;
  r_ = n_groups * group_size;
  m_ = m;
  idx_.assign(r_, -1);
  fresh_.assign(n_groups, 0);
  W_.resize(n_, r_);
  PW_.setZero(r_, r_);
}

void SplitBorderedSolver::set_band(const BandMatrix& A) {
  A_ = &A;
  std::fill(fresh_.begin(), fresh_.end(), 0);
}

void SplitBorderedSolver::set_group(int g, const int* idx) {
  int* mine = idx_.data() + static_cast<std::ptrdiff_t>(g) * gs_;
  if (fresh_[g] && std::equal(idx, idx + gs_, mine)) return;
  std::copy(idx, idx + gs_, mine);
  fresh_[g] = 0;
}

bool SplitBorderedSolver::factorize(const Eigen::MatrixXd& E, const Eigen::MatrixXd& F,
                                    const Eigen::MatrixXd& G, const Eigen::MatrixXd& D) {
  bool moved = false;
  for (int g = 0; g < static_cast<int>(fresh_.size()); ++g) {
    if (fresh_[g]) continue;
    for (int k = g * gs_; k < (g + 1) * gs_; ++k) {
      W_.clear(k);
      if (idx_[k] < 0) continue;
      W_.col(k)(idx_[k]) = 1.0;
      W_.solve(*A_, k, idx_[k], idx_[k]);
      ++band_solves_;
    }
    fresh_[g] = 1;
    moved = true;
  }
  if (moved)
    for (int j = 0; j < r_; ++j)
      for (int i = 0; i < r_; ++i) PW_(i, j) = idx_[i] < 0 ? 0.0 : W_.at(idx_[i], j);
  const int k = r_ + m_;
  S_.resize(k, k);
  EF_.resize(r_, k);
  EF_.leftCols(r_) = E;
  EF_.rightCols(m_) = F;
  S_.topRows(r_).noalias() = PW_ * EF_;
  S_.topLeftCorner(r_, r_).diagonal().array() += 1.0;
  S_.bottomLeftCorner(m_, r_) = G;
  S_.bottomRightCorner(m_, m_) = D;
  if (!S_.allFinite()) return false;
  lu_.compute(S_);
  const double det = lu_.determinant();
  return std::isfinite(det) && det != 0.0;
}

void SplitBorderedSolver::solve(const Eigen::VectorXd& r1, const Eigen::VectorXd& r2,
                                Eigen::VectorXd& x1, Eigen::VectorXd& x2) const {
  x1 = r1;
  A_->solve_in_place(x1);
  rhs_.resize(r_ + m_);
  for (int i = 0; i < r_; ++i) rhs_(i) = idx_[i] < 0 ? 0.0 : x1(idx_[i]);
  rhs_.tail(m_) = r2;
  sol_ = lu_.solve(rhs_);
  u_.noalias() = EF_ * sol_;
  W_.subtract(u_, x1);
  x2 = sol_.tail(m_);
}

}  // namespace trackwheel
