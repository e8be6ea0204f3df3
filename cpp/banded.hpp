// Banded matrices and a bordered banded solver.
//
// The rail's free coordinates are numbered node by node, so every element couples indices
// within a half bandwidth of 7. Wheel coordinates and constraint multipliers are appended as a
// few dense border rows/columns. The solver factorises the band (LU without pivoting: the
// matrices met here -- stiffness, or mass/(beta h^2) + damping + stiffness -- are positive
// definite or close to it) and eliminates the border by a small dense Schur complement:
// O(n b^2 + n m b) per factorisation, never a dense n x n factorisation.
#pragma once

#include <Eigen/Dense>
#include <utility>
#include <vector>

namespace trackwheel {

class BandMatrix {
 public:
  BandMatrix() = default;
  BandMatrix(int n, int half_bandwidth) { resize(n, half_bandwidth); }
  void resize(int n, int half_bandwidth);
  void set_zero() { data_.setZero(); }
  int size() const { return n_; }
  int half_bandwidth() const { return b_; }
  // (i, j) with |i - j| <= b
  double& at(int i, int j) { return data_(b_ + i - j, j); }
  double at(int i, int j) const { return data_(b_ + i - j, j); }
  bool in_band(int i, int j) const { return i - j <= b_ && j - i <= b_; }
  void add(int i, int j, double v) { data_(b_ + i - j, j) += v; }
  // y = A x
  void multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const;
  Eigen::MatrixXd dense() const;
  bool is_zero() const { return data_.isZero(0.0); }  // every stored entry exactly 0
  // In-place LU (no pivoting). Returns false on a zero or non-finite pivot.
  bool factorize();
  void solve_in_place(Eigen::Ref<Eigen::VectorXd> x) const;  // after factorize()
  // The same for an x whose non-zeros lie in [first, last], where A^-1 decays away from them
  // (a mass-dominated iteration matrix): each sweep stops once more than a bandwidth of
  // consecutive entries past them is below `negligible` of the largest entry so far, the rest
  // left zero. Returns [lo, hi), outside which x is zero.
  std::pair<int, int> solve_local(Eigen::Ref<Eigen::VectorXd> x, int first, int last,
                                  double negligible) const;
  // Combine: this = a*A + b*B (same shape).
  void set_linear_combination(double a, const BandMatrix& A, double b, const BandMatrix& B);
  void add_scaled(double a, const BandMatrix& A);

 private:
  int n_ = 0, b_ = 0;
  Eigen::MatrixXd data_;  // (2b+1) x n, column-major band storage
};

// Columns A^-1 b_k of a factorised band matrix for right-hand sides b_k with clustered
// non-zeros, each kept over the rows [lo_k, hi_k) where it is not negligible
// (BandMatrix::solve_local: entries below kNegligible of the column's largest left out, a change
// below round-off), so that products with them cost what the columns' supports do.
class LocalColumns {
 public:
  static constexpr double kNegligible = 1e-17;
  void resize(int n, int m);  // n x m columns, all zero
  // Column k := A^-1 b, b = e_first + ... given in place by the caller (col(k)) with its
  // non-zeros in [first, last].
  void solve(const BandMatrix& A, int k, int first, int last);
  void clear(int k);  // column k := 0
  Eigen::MatrixXd::ColXpr col(int k) { return M_.col(k); }
  const Eigen::MatrixXd& matrix() const { return M_; }
  // entry (i, k) of the kept column (0 outside its rows)
  double at(int i, int k) const { return i >= lo_[k] && i < hi_[k] ? M_(i, k) : 0.0; }
  // x -= sum_k c_k column_k, column by column over each column's rows
  void subtract(const Eigen::VectorXd& c, Eigen::VectorXd& x) const;

 private:
  Eigen::MatrixXd M_;
  std::vector<int> lo_, hi_;
};

// Solves [A B; C D] [x1; x2] = [r1; r2] with A banded (n x n), B (n x m), C (m x n), D (m x m).
class BorderedSolver {
 public:
  // Factorises; A is overwritten by its LU. Returns false if singular.
  bool factorize(BandMatrix& A, const Eigen::MatrixXd& B, const Eigen::MatrixXd& C,
                 const Eigen::MatrixXd& D);
  // Same with A already factorised (A.factorize() called by the owner, e.g. a constant mass).
  bool factorize_border(const BandMatrix& A_factored, const Eigen::MatrixXd& B,
                        const Eigen::MatrixXd& C, const Eigen::MatrixXd& D);
  void solve(const Eigen::VectorXd& r1, const Eigen::VectorXd& r2, Eigen::VectorXd& x1,
             Eigen::VectorXd& x2) const;

 private:
  const BandMatrix* A_ = nullptr;
  LocalColumns Z_;  // A^-1 B
  // C's non-zeros (a wheel's rows touch the 8 coordinates of its contact element): C x1 in
  // O(non-zeros) rather than O(m n)
  std::vector<int> c_row_, c_col_;
  std::vector<double> c_val_;
  Eigen::PartialPivLU<Eigen::MatrixXd> schur_;
  int m_ = 0;
  mutable Eigen::VectorXd rhs_;  // a buffer of solve
};

// Solves [A + P E P^T, P F; G P^T, D] [x1; x2] = [r1; r2]: a bordered band system whose border
// couples with a few band coordinates only (the wheels' contacts with the rail), with the part of
// those couplings that falls inside the band (E) kept out of the band. A (n x n, banded) is
// factorised by its owner and kept; P's r columns are unit vectors e_idx (a zero column for
// idx = -1), given in groups (one per wheel) so that a group's columns are redone alone; E
// (r x r), F (r x m), G (m x r) and D (m x m) are small, dense and may change at every
// factorize(). With W = A^-1 P (cached while A and the group's indices stay), x0 = A^-1 r1 and
// y = P^T x1, the system is exactly
//   [I + (P^T W) E, (P^T W) F; G, D] [y; x2] = [P^T x0; r2],   x1 = x0 - W (E y + F x2):
// a new E, F, G, D costs an (r + m)-square LU, not a band factorisation, and a solve one band
// solve plus O(n r).
class SplitBorderedSolver {
 public:
  // n band unknowns, n_groups groups of group_size columns of P, m border unknowns.
  void resize(int n, int n_groups, int group_size, int m);
  // The factorised A (kept by reference: call again after refactorising it).
  void set_band(const BandMatrix& A_factored);
  // Group g's band indices (group_size of them, -1: none).
  void set_group(int g, const int* idx);
  int rank() const { return r_; }
  // False if the small system is singular (then so is the whole).
  bool factorize(const Eigen::MatrixXd& E, const Eigen::MatrixXd& F, const Eigen::MatrixXd& G,
                 const Eigen::MatrixXd& D);
  void solve(const Eigen::VectorXd& r1, const Eigen::VectorXd& r2, Eigen::VectorXd& x1,
             Eigen::VectorXd& x2) const;
  // Band solves spent on W's columns so far (each a new group position or a new A).
  long band_solves() const { return band_solves_; }

 private:
  const BandMatrix* A_ = nullptr;
  int n_ = 0, gs_ = 0, r_ = 0, m_ = 0;
  std::vector<int> idx_;     // P's indices (r)
  std::vector<char> fresh_;  // per group: W's columns are those of idx_ and A
  LocalColumns W_;           // A^-1 P (n x r)
  Eigen::MatrixXd PW_;       // P^T W (r x r)
  Eigen::MatrixXd EF_;       // [E F] (r x (r + m))
  Eigen::MatrixXd S_;
  Eigen::PartialPivLU<Eigen::MatrixXd> lu_;
  long band_solves_ = 0;
  mutable Eigen::VectorXd rhs_, sol_, u_;
};

}  // namespace trackwheel
