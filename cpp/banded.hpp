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
  // Combine: this = a*A + b*B (same shape).
  void set_linear_combination(double a, const BandMatrix& A, double b, const BandMatrix& B);
  void add_scaled(double a, const BandMatrix& A);

 private:
  int n_ = 0, b_ = 0;
  Eigen::MatrixXd data_;  // (2b+1) x n, column-major band storage
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
  Eigen::MatrixXd Z_;  // A^-1 B
  Eigen::MatrixXd C_;
  Eigen::PartialPivLU<Eigen::MatrixXd> schur_;
  int m_ = 0;
  mutable Eigen::VectorXd cx_, rhs_, zx_;  // buffers of solve
};

}  // namespace trackwheel
