#include "window.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "time_loop.hpp"

namespace trackwheel {

namespace {

// The number of whole bays of the rail, checked.
int bays_of(const RailModel& rail, const WindowParams& p) {
  const double L = rail.params().length;
  const int nb = static_cast<int>(std::lround(L / p.bay));
  if (nb < 3 || std::abs(nb * p.bay - L) > 1e-9 * L)
    throw std::invalid_argument("window: the rail length " + format3(L) +
                                " m must be a whole number (>= 3) of bays of " + format3(p.bay) +
                                " m");
  if (p.elements_per_bay < 1 || nb * p.elements_per_bay != rail.params().n_elements)
    throw std::invalid_argument("window: n_elements = " + std::to_string(rail.params().n_elements) +
                                " must be " + std::to_string(nb) +
                                " bays x elements_per_bay (>= 1)");
  // hold = (bays behind + 1) bays may equal L - bay (one bay ahead): compared with a tolerance,
  // since L = n_bays x bay and the hold are rounded differently
  const double tol = 1e-9 * L;
  if (!(p.hold >= p.bay - tol && p.hold <= L - p.bay + tol))
    throw std::invalid_argument("window: hold = " + format3(p.hold) + " m must be in [" +
                                format3(p.bay) + ", " + format3(L - p.bay) + "] m");
  return nb;
}

}  // namespace

WindowShift::WindowShift(const RailModel& rail, const WindowParams& p, const std::vector<int>& map,
                         int n, int n_sleepers)
    : p_(p) {
  if (!p.active()) return;
  bays_of(rail, p);
  const int step = 4 * p.elements_per_bay;
  src_.assign(n, -1);
  const int nd = static_cast<int>(map.size());
  for (int i = 0; i < nd; ++i) {
    const int k = map[i];
    if (k < 0) continue;
    if (i + step < nd) src_[k] = map[i + step];
  }
  const std::vector<double>& x = rail.supports().position;
  if (static_cast<int>(x.size()) != n_sleepers && n_sleepers > 0)
    throw std::invalid_argument("window: sleepers and supports differ in number");
  const double tol = 1e-9 * p.bay;
  for (std::size_t j = 1; j < x.size(); ++j)
    if (std::abs(x[j] - x[j - 1] - p.bay) > tol)
      throw std::invalid_argument("window: the supports must be equally spaced at the bay " +
                                  format3(p.bay) + " m (supports " + std::to_string(j - 1) +
                                  " and " + std::to_string(j) + " are " + format3(x[j] - x[j - 1]) +
                                  " m apart)");
  zsrc_.assign(n_sleepers, -1);
  for (int j = 0; j + 1 < n_sleepers; ++j) zsrc_[j] = j + 1;
}

void WindowShift::apply(const std::vector<int>& src, Eigen::VectorXd& v, Eigen::VectorXd& buf) {
  buf = v;
  for (std::size_t k = 0; k < src.size(); ++k)
    v(static_cast<Eigen::Index>(k)) = src[k] >= 0 ? buf(src[k]) : 0.0;
}

bool WindowFollower::follow(double rear_x, double& origin, SimState& st,
                            std::initializer_list<Accel*> accs) const {
  if (!active()) return false;
  const WindowParams& wp = shift_.params();
  bool moved = false;
  while (rear_x - origin >= wp.hold) {
    shift_.shift(st.e, &e_rest_);
    shift_.shift(st.edot);
    shift_.shift_sleepers(st.z, &z_rest_);
    shift_.shift_sleepers(st.zdot);
    for (WheelState& ws : st.wheels) ws.s -= wp.bay;
    for (Accel* a : accs) {
      shift_.shift(a->edd);
      shift_.shift_sleepers(a->zdd);
    }
    origin += wp.bay;
    moved = true;
  }
  return moved;
}

}  // namespace trackwheel
