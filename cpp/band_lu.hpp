// LU with partial pivoting of a square band matrix of half bandwidth b, for any scalar type
// (used complex for the dynamic stiffness K + i w C - w^2 M, which is indefinite above the first
// resonance, so pivoting is needed where banded.hpp's LU without pivoting suffices). Row
// interchanges widen the upper band to 2b (as in LAPACK's gbtrf): O(n b^2) per factorisation,
// O(n b) per solve.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <vector>

namespace trackwheel {

template <class T>
class BandLU {
 public:
  // An n x n zero matrix of half bandwidth b (entries |i - j| <= b may be set before factorize).
  void resize(int n, int b) {
    n_ = n;
    b_ = b;
    a_.setZero(n, 3 * b + 1);
    l_.setZero(n, std::max(b, 1));
    piv_.assign(n, 0);
  }
  void set_zero() { a_.setZero(); }
  int size() const { return n_; }
  // (i, j) with -b <= j - i <= 2 b (the fill-in of the interchanges included)
  T& at(int i, int j) { return a_(i, j - i + b_); }
  T at(int i, int j) const { return a_(i, j - i + b_); }

  // In place; false on a zero or non-finite pivot (a singular matrix).
  bool factorize() {
    for (int k = 0; k < n_; ++k) {
      const int last = std::min(n_ - 1, k + b_), cmax = std::min(n_ - 1, k + 2 * b_);
      int p = k;
      for (int i = k + 1; i <= last; ++i)
        if (std::abs(at(i, k)) > std::abs(at(p, k))) p = i;
      piv_[k] = p;
      const T pivot = at(p, k);
      if (!(std::abs(pivot) > 0.0) || !std::isfinite(std::abs(pivot))) return false;
      if (p != k)
        for (int c = k; c <= cmax; ++c) std::swap(at(k, c), at(p, c));
      for (int i = k + 1; i <= last; ++i) {
        const T m = at(i, k) / at(k, k);
        l_(k, i - k - 1) = m;
        at(i, k) = T(0);
        for (int c = k + 1; c <= cmax; ++c) at(i, c) -= m * at(k, c);
      }
    }
    return true;
  }

  // x <- A^-1 x, after factorize(): the interchanges and eliminations in their order, then
  // back substitution.
  void solve_in_place(Eigen::Matrix<T, Eigen::Dynamic, 1>& x) const {
    for (int k = 0; k < n_; ++k) {
      if (piv_[k] != k) std::swap(x(k), x(piv_[k]));
      const int last = std::min(n_ - 1, k + b_);
      for (int i = k + 1; i <= last; ++i) x(i) -= l_(k, i - k - 1) * x(k);
    }
    for (int k = n_ - 1; k >= 0; --k) {
      const int cmax = std::min(n_ - 1, k + 2 * b_);
      T s = x(k);
      for (int c = k + 1; c <= cmax; ++c) s -= at(k, c) * x(c);
      x(k) = s / at(k, k);
    }
  }

 private:
  int n_ = 0, b_ = 0;
  Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> a_;  // n x (3b + 1)
  Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> l_;  // multipliers
  std::vector<int> piv_;
};

}  // namespace trackwheel
