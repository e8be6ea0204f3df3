#include "profile.hpp"

#include <cmath>
#include <stdexcept>
#include <utility>

namespace trackwheel {

Profile::Profile(double x0, double dx, std::vector<double> coefs) : x0_(x0), dx_(dx) {
  if (!std::isfinite(x0_)) throw std::invalid_argument("profile x0 must be finite");
  if (!(std::isfinite(dx_) && dx_ > 0)) throw std::invalid_argument("profile dx must be > 0 m");
  if (coefs.empty() || coefs.size() % 4 != 0)
    throw std::invalid_argument("profile coefficients must hold 4 values per interval (>= 1)");
  for (double c : coefs)
    if (!std::isfinite(c)) throw std::invalid_argument("profile coefficients must be finite");
  c_ = std::make_shared<const std::vector<double>>(std::move(coefs));
}

ProfileValue Profile::operator()(double x) const {
  ProfileValue v;
  if (!c_) return v;
  const int m = n_intervals();
  const double x_end = x0_ + m * dx_;
  const bool before = !(x >= x0_);  // also catches NaN
  const bool beyond = x > x_end;
  int i = before ? 0 : beyond ? m - 1 : static_cast<int>((x - x0_) / dx_);
  if (i > m - 1) i = m - 1;
  const double u = before ? 0.0 : beyond ? dx_ : x - (x0_ + i * dx_);
  const double* c = c_->data() + 4 * i;
  v.r = ((c[0] * u + c[1]) * u + c[2]) * u + c[3];
  if (before || beyond) return v;  // flat continuation
  v.rx = (3.0 * c[0] * u + 2.0 * c[1]) * u + c[2];
  v.rxx = 6.0 * c[0] * u + 2.0 * c[1];
  return v;
}

}  // namespace trackwheel
