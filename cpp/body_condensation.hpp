// The vehicle's bodies condensed out of the iteration matrix's border (docs: Model § The
// vehicle). With the border D = [D_ww D_wb; D_bw D_bb] over the wheels' rows (mw) and the
// bodies' (mb), the bodies carry no rail coupling, so the wheels' border is
// D_ww - D_wb D_bb^-1 D_bw and a solve recovers the bodies' part after the wheels'. The
// assembled and the split factorisation each keep one (System).
#pragma once

#include <Eigen/Dense>
#include <cmath>

namespace trackwheel {

class BodyCondensation {
 public:
  // Factorises D_bb of D; false if it is singular. reduced() is then D_ww - D_wb D_bb^-1 D_bw.
  bool compute(const Eigen::MatrixXd& D, int mw, int mb) {
    mw_ = mw;
    mb_ = mb;
    lu_.compute(D.bottomRightCorner(mb, mb));
    const double det = lu_.determinant();
    if (!std::isfinite(det) || det == 0.0) return false;
    Dwb_ = D.topRightCorner(mw, mb);
    Dbw_ = D.bottomLeftCorner(mb, mw);
    Dred_ = D.topLeftCorner(mw, mw) - Dwb_ * lu_.solve(Dbw_);
    return true;
  }
  const Eigen::MatrixXd& reduced() const { return Dred_; }
  // x = A^-1 r over the whole border, given solve_wheels(r1, r2w, x1, x2w) of the system with
  // the reduced border.
  template <class SolveWheels>
  void solve(SolveWheels solve_wheels, const Eigen::VectorXd& r1, const Eigen::VectorXd& r2,
             Eigen::VectorXd& x1, Eigen::VectorXd& x2) const {
    r2b_ = r2.tail(mb_);
    r2w_ = r2.head(mw_) - Dwb_ * lu_.solve(r2b_);
    solve_wheels(r1, r2w_, x1, x2w_);
    x2.resize(mw_ + mb_);
    x2.head(mw_) = x2w_;
    x2.tail(mb_) = lu_.solve(r2b_ - Dbw_ * x2w_);
  }

 private:
  int mw_ = 0, mb_ = 0;
  Eigen::PartialPivLU<Eigen::MatrixXd> lu_;  // D_bb
  Eigen::MatrixXd Dwb_, Dbw_, Dred_;
  mutable Eigen::VectorXd r2w_, x2w_, r2b_;
};

}  // namespace trackwheel
