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
#include <initializer_list>
#include <utility>
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

// A stepper's travelling window (both paths): the shift maps and the rest state whose departures
// move, the track at rest under its own weight without a wheel (so the fresh bay joins at rest
// and the window's ends keep their own sag).
class WindowFollower {
 public:
  WindowFollower() = default;
  WindowFollower(WindowShift shift, Eigen::VectorXd e_rest, Eigen::VectorXd z_rest)
      : shift_(std::move(shift)), e_rest_(std::move(e_rest)), z_rest_(std::move(z_rest)) {}
  bool active() const { return shift_.active(); }
  // While the rearmost wheel, at the track coordinate rear_x [m], is at or past the hold point
  // of the window of origin X_w = origin [m]: moves the state one bay back (the departures of e
  // and z from rest, their rates, each wheel's contact warm start s), each of accs likewise (e''
  // and z'' as they are) and origin one bay on. True if it moved.
  bool follow(double rear_x, double& origin, SimState& st,
              std::initializer_list<Accel*> accs) const;

 private:
  WindowShift shift_;
  Eigen::VectorXd e_rest_, z_rest_;
};

}  // namespace trackwheel
