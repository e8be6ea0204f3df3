// The running-surface profile of the rail (docs: Model § Irregularities).
//
// r(X) [m] is the height of the running surface above the rail's centre line at the track
// coordinate X; positive r is a bump. It is fixed to the track: the contact sees the rail point
// at s lifted by r evaluated at that point's current horizontal position x(s), so the profile
// does not move with the rail's axial motion.
//
// The profile is a piecewise cubic on a uniform grid X_i = x0 + i dx (the Python side builds it
// with scipy's CubicSpline from samples of the user's profile, so it is C2 and its derivatives
// are exact for the spline). Outside [x0, x0 + m dx] the end values continue flat (r' = r'' =
// 0): the Python side makes the grid cover the whole rail.
#pragma once

#include <memory>
#include <vector>

namespace trackwheel {

struct ProfileValue {
  double r = 0.0;    // height [m]
  double rx = 0.0;   // dr/dX [-]
  double rxx = 0.0;  // d2r/dX2 [1/m]
};

class Profile {
 public:
  Profile() = default;  // no profile: r = 0 everywhere
  // coefs: 4 m values, interval i holding (c3, c2, c1, c0) of
  // r = c3 u^3 + c2 u^2 + c1 u + c0, u = X - X_i (scipy's PPoly order, interval-major).
  Profile(double x0, double dx, std::vector<double> coefs);

  bool empty() const { return !c_; }
  int n_intervals() const { return c_ ? static_cast<int>(c_->size() / 4) : 0; }
  double x0() const { return x0_; }
  double dx() const { return dx_; }
  ProfileValue operator()(double x) const;

 private:
  double x0_ = 0.0, dx_ = 1.0;
  // shared, never changed: a profile over kilometres (32 MB per km at 1 mm) is not copied
  // where the rail model takes its profile or a model is copied
  std::shared_ptr<const std::vector<double>> c_;
};

}  // namespace trackwheel
