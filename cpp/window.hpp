// The travelling window (docs: Model § The travelling window).
//
// A track periodic in its sleeper bay d_s is simulated on a fixed rail of n_b bays that travels
// with the wheels: the rail's local coordinate s in [0, L] is the track coordinate X = X_w + s,
// X_w the window origin (a multiple of d_s). When the rearmost wheel passes s = hold, the state
// moves one bay back in the rail (coordinate i takes the value of coordinate i + 4 n_e,bay, the
// same node one bay ahead; sleeper j that of the sleeper d_s ahead), the rear bay leaves, the
// front bay joins at zero and X_w grows by d_s. The stepper shifts departures from the track's
// rest state, so zero is the fresh bay at rest. The matrices over the window do not change: the
// rail, its supports and its end zones are the same after the shift.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "rail.hpp"
#include "state.hpp"

namespace trackwheel {

// The shift maps of one window over the indexing of a state vector (map: full rail index ->
// index in the vector, -1 fixed, as in sleepers.hpp) and of the sleepers.
class WindowShift {
 public:
  WindowShift() = default;
  // Throws std::invalid_argument unless the rail is a whole number of bays of whole elements
  // with its supports periodic in the bay and hold within the window.
  WindowShift(const RailModel& rail, const WindowParams& p, const std::vector<int>& map, int n,
              int n_sleepers);
  bool active() const { return p_.active(); }
  const WindowParams& params() const { return p_; }
  // v(k) <- v(source(k)), the value one bay ahead, or 0 where that is beyond the front; with
  // rest, the departure moves: v <- rest + shift(v - rest).
  void shift(Eigen::VectorXd& v, const Eigen::VectorXd* rest = nullptr) const {
    shift_departure(src_, v, rest);
  }
  void shift_sleepers(Eigen::VectorXd& z, const Eigen::VectorXd* rest = nullptr) const {
    if (z.size() > 0) shift_departure(zsrc_, z, rest);
  }

 private:
  void shift_departure(const std::vector<int>& src, Eigen::VectorXd& v,
                       const Eigen::VectorXd* rest) const {
    if (rest != nullptr) v -= *rest;
    apply(src, v, buf_);
    if (rest != nullptr) v += *rest;
  }

  WindowParams p_;
  std::vector<int> src_;   // per vector index: the index one bay ahead (-1: beyond the front)
  std::vector<int> zsrc_;  // per sleeper
  mutable Eigen::VectorXd buf_;
  static void apply(const std::vector<int>& src, Eigen::VectorXd& v, Eigen::VectorXd& buf);
};

}  // namespace trackwheel
