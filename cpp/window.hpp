// The travelling window (docs: Model § The travelling window).
//
// A track with a constant sleeper bay d_s is simulated on a fixed rail of n_b bays that travels
// with the wheels: the rail's local coordinate s in [0, L] is the track coordinate X = X_w + s,
// X_w the window origin (a multiple of d_s). When the rearmost wheel passes s = hold, the state
// moves one bay back in the rail (coordinate i takes the value of coordinate i + 4 n_e,bay, the
// same node one bay ahead; sleeper j that of the sleeper d_s ahead), the rear bay leaves, the
// front bay joins at rest and X_w grows by d_s. The stepper shifts departures from the track's
// rest state, so zero is the fresh bay at rest. On a track periodic in its bay the matrices over
// the window do not change. A track whose supports differ from bay to bay streams them in
// (SupportFeed): after each shift support j takes the properties of the physical sleeper now
// at its place, the rail's support bands and the sleepers' rows are re-assembled and the rest
// state is solved again; where no property changed nothing is rebuilt. A void streams in like
// any property and stays with its physical sleeper: the sleepers' ballast states shift with the
// state (Sleepers::shift), the properties stream in, the rest is solved again (its sleepers by
// their active set) and the fresh front sleeper joins on or off its bed as it stands at that
// rest (Sleepers::join_at_rest).
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <functional>
#include <initializer_list>
#include <utility>
#include <vector>

#include "rail.hpp"
#include "sleepers.hpp"
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

// The supports' properties streamed into a travelling window: the track's supports one per
// physical sleeper k (WindowParams::supports, k = 0 the start window's rear support), set on
// the run's own rail, whose support j is physical sleeper first + j.
class SupportFeed {
 public:
  SupportFeed() = default;
  // Throws std::invalid_argument unless the stream's supports are spaced by the bay from the
  // rail's rear support at X = origin + X_0, carry the rail's layers and valid values, and
  // cover the start window. Sets the start window's properties on rail.
  SupportFeed(const WindowParams& p, RailModel& rail);
  bool active() const { return rail_ != nullptr; }
  // Sets the properties of the window whose rear support is physical sleeper `first` on the
  // rail; true if any changed. Throws std::runtime_error beyond the stream's end.
  bool feed(long first);

 private:
  SupportParams stream_, window_;
  RailModel* rail_ = nullptr;
};

// A stepper's travelling window (both paths): the shift maps and the rest state whose departures
// move, the track at rest under its own weight without a wheel (so the fresh bay joins at rest
// and the window's ends keep their own sag).
class WindowFollower {
 public:
  // Called after each shift with the physical index of the rail's support 0: sets the moved
  // window's supports (SupportFeed) and, if any property changed, the rest state of the
  // changed track (e_rest, z_rest), returning true; false leaves the rest state.
  using Restream =
      std::function<bool(long first, Eigen::VectorXd& e_rest, Eigen::VectorXd& z_rest)>;
  WindowFollower() = default;
  // sleepers: the run's (their ballast states and record move with the window), or null.
  WindowFollower(WindowShift shift, Eigen::VectorXd e_rest, Eigen::VectorXd z_rest,
                 Sleepers* sleepers, Restream restream = nullptr)
      : shift_(std::move(shift)),
        e_rest_(std::move(e_rest)),
        z_rest_(std::move(z_rest)),
        sleepers_(sleepers),
        restream_(std::move(restream)) {}
  bool active() const { return shift_.active(); }
  void set_restream(Restream r) { restream_ = std::move(r); }
  // The physical index of the rail's support 0: the shifts so far (0 on a fixed rail).
  long first() const { return first_; }
  // While the rearmost wheel, at the track coordinate rear_x [m], is at or past the hold point
  // of the window of origin X_w = origin [m]: moves the state one bay back (the departures of e
  // and z from rest, their rates, each wheel's contact warm start s, the sleepers' ballast
  // states), each of accs likewise (e'' and z'' as they are) and origin one bay on, streaming
  // the supports in after each shift and joining the fresh sleeper at the rest. True if it
  // moved; changed: whether a support's properties changed.
  bool follow(double rear_x, double& origin, SimState& st, std::initializer_list<Accel*> accs,
              bool* changed = nullptr);
  // follow() for the workspace sys (System or LinearSystem) at time t [s]: its rearmost wheel
  // and its origin, moved with the window.
  template <class Sys>
  bool follow_wheels(Sys& sys, double t, SimState& st, std::initializer_list<Accel*> accs,
                     bool* changed = nullptr) {
    double rear = sys.x_at(0, t);
    for (int w = 1; w < sys.n_wheels(); ++w) rear = std::min(rear, sys.x_at(w, t));
    double origin = sys.origin();
    const bool moved = follow(rear, origin, st, accs, changed);
    sys.set_origin(origin);
    return moved;
  }

 private:
  WindowShift shift_;
  Eigen::VectorXd e_rest_, z_rest_;
  Sleepers* sleepers_ = nullptr;
  Restream restream_;
  long first_ = 0;
};

}  // namespace trackwheel
