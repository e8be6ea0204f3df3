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

SupportFeed::SupportFeed(const WindowParams& p, RailModel& rail) : stream_(p.supports) {
  if (!p.streams()) return;
  const SupportParams& sup = rail.supports();
  const std::size_t ns = sup.position.size(), nk = stream_.position.size();
  const double tol = 1e-9 * p.bay;
  if (ns == 0) throw std::invalid_argument("window: a support stream needs a rail with supports");
  if (nk < ns)
    throw std::invalid_argument("window: the support stream has " + std::to_string(nk) +
                                " supports, fewer than the window's " + std::to_string(ns));
  for (std::size_t k = 0; k < nk; ++k) {
    const double X = p.origin + sup.position[0] + static_cast<double>(k) * p.bay;
    if (std::abs(stream_.position[k] - X) > tol * (1.0 + static_cast<double>(k)))
      throw std::invalid_argument("window: support stream entry " + std::to_string(k) +
                                  " is at X = " + format3(stream_.position[k]) +
                                  " m; the window's supports stand at X = " + format3(X) + " m");
  }
  if (stream_.tensionless != sup.tensionless)
    throw std::invalid_argument(
        "window: the support stream and the rail's supports must agree on tensionless");
  // A stream with voids gives the window's supports a void field even where the start window
  // has none (g = 0 there: the linear ballast), so that every sleeper it meets can take one.
  window_ = sup;
  const bool add_voids = !stream_.void_gap.empty() && window_.void_gap.empty();
  if (add_voids) window_.void_gap.assign(ns, 0.0);
  // each property the rail has, the stream has for every support, and no other
  std::vector<std::size_t> sizes;
  for_each_support_property(window_,
                            [&](const std::vector<double>& v) { sizes.push_back(v.size()); });
  std::size_t i = 0;
  for_each_support_property(stream_, [&](const std::vector<double>& v) {
    if (v.size() != (sizes[i++] > 0 ? nk : 0))
      throw std::invalid_argument(
          "window: the support stream must give each property of the rail's supports (and no "
          "other: sleepers on both or neither) once per support position");
  });
  // the values in the rail's ranges (rail.cpp), the first bad one named by its X
  auto check = [&](const std::vector<double>& v, const char* name, bool positive) {
    for (std::size_t k = 0; k < v.size(); ++k)
      if (!(std::isfinite(v[k]) && (positive ? v[k] > 0.0 : v[k] >= 0.0)))
        throw std::invalid_argument("window: support stream " + std::string(name) + " = " +
                                    format3(v[k]) + " at X = " + format3(stream_.position[k]) +
                                    " m (entry " + std::to_string(k) + ") must be " +
                                    (positive ? "> 0" : ">= 0"));
  };
  check(stream_.stiffness, "stiffness", false);
  check(stream_.damping, "damping", false);
  check(stream_.sleeper_mass, "sleeper_mass", true);
  check(stream_.ballast_stiffness, "ballast_stiffness", true);
  check(stream_.ballast_damping, "ballast_damping", false);
  check(stream_.void_gap, "void_gap", false);
  // as rail.cpp asks of its own supports: a sleeper that can lose its ballast hangs on its pad
  if (!stream_.sleeper_mass.empty())
    for (std::size_t k = 0; k < nk; ++k)
      if ((stream_.unilateral(k) || stream_.ballast_stiffness[k] == 0.0) &&
          !(stream_.stiffness[k] > 0.0))
        throw std::invalid_argument(
            "window: support stream entry " + std::to_string(k) +
            " at X = " + format3(stream_.position[k]) +
            " m: a sleeper that can lose its ballast (void_gap > 0, tensionless or "
            "ballast_stiffness = 0) needs a pad stiffness > 0 N/m to hang on");
  rail_ = &rail;
  if (add_voids) rail.set_support_properties(window_);
  feed(0);
}

bool SupportFeed::feed(long first) {
  if (!active()) return false;
  const std::size_t ns = window_.position.size(), k0 = static_cast<std::size_t>(first);
  if (k0 + ns > stream_.position.size())
    throw std::runtime_error(
        "window: the support stream ends at X = " + format3(stream_.position.back()) +
        " m, before the window's front support");
  bool changed = false;
  std::vector<const std::vector<double>*> from;
  for_each_support_property(stream_, [&](const std::vector<double>& v) { from.push_back(&v); });
  std::size_t i = 0;
  for_each_support_property(window_, [&](std::vector<double>& v) {
    const std::vector<double>& src = *from[i++];
    for (std::size_t j = 0; j < v.size() && j < ns; ++j) {
      const double x = src[k0 + j];
      if (v[j] != x) {
        v[j] = x;
        changed = true;
      }
    }
  });
  if (changed) rail_->set_support_properties(window_);
  return changed;
}

bool WindowFollower::follow(double rear_x, double& origin, SimState& st,
                            std::initializer_list<Accel*> accs, bool* changed) {
  if (!active()) return false;
  const WindowParams& wp = shift_.params();
  bool moved = false;
  while (rear_x - origin >= wp.hold) {
    // the departures from rest move; the state then stands on the rest of the moved window
    st.e -= e_rest_;
    shift_.shift(st.e);
    shift_.shift(st.edot);
    if (st.z.size() > 0) st.z -= z_rest_;
    shift_.shift_sleepers(st.z);
    shift_.shift_sleepers(st.zdot);
    for (WheelState& ws : st.wheels) ws.s -= wp.bay;
    for (Accel* a : accs) {
      shift_.shift(a->edd);
      shift_.shift_sleepers(a->zdd);
    }
    origin += wp.bay;
    ++first_;
    // the ballast states move before the properties stream in: the rest's active set starts
    // from them and each sleeper's void meets its own state
    if (sleepers_ != nullptr) sleepers_->shift(1);
    if (restream_ && restream_(first_, e_rest_, z_rest_) && changed != nullptr) *changed = true;
    if (sleepers_ != nullptr) sleepers_->join_at_rest(z_rest_);
    st.e += e_rest_;
    if (st.z.size() > 0) st.z += z_rest_;
    moved = true;
  }
  return moved;
}

}  // namespace trackwheel
