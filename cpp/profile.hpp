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
//
// Over kilometres (a travelling window's run: 30 MiB per km at 1 mm) the table is streamed:
// chunks of consecutive intervals come from a source on demand as X advances, and chunks
// ending more than a retention distance behind the furthest X requested so far are dropped,
// so memory does not grow with the distance. The contact only moves forwards along the track,
// at most the vehicle's span behind its leading wheel; a request behind the kept range throws.
#pragma once

#include <atomic>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

namespace trackwheel {

struct ProfileValue {
  double r = 0.0;     // height [m]
  double rx = 0.0;    // dr/dX [-]
  double rxx = 0.0;   // d2r/dX2 [1/m]
  double rxxx = 0.0;  // d3r/dX3 [1/m^2] (piecewise constant)
};

class Profile {
 public:
  Profile() = default;  // no profile: r = 0 everywhere
  // coefs: 4 m values, interval i holding (c3, c2, c1, c0) of
  // r = c3 u^3 + c2 u^2 + c1 u + c0, u = X - X_i (scipy's PPoly order, interval-major).
  Profile(double x0, double dx, std::vector<double> coefs);

  // The next chunk's coefficients (interval-major as above), chunks consecutive from
  // interval 0; an empty vector when there are no more.
  using ChunkSource = std::function<std::vector<double>()>;
  // Opens the chunk source at interval 0.
  using ChunkOpener = std::function<ChunkSource()>;
  // Streamed: n_intervals in all, loaded from the source `open` returns as X advances; chunks
  // ending more than `retention` [m] behind the furthest X requested are dropped. A request
  // behind the kept range re-opens the source and reads forwards again to it if `rewind` (a
  // second run on the same rail model starts behind where the first one ended), else throws
  // std::runtime_error. Each thread reading the profile makes its own pass, opening a source
  // at its first request; with `rewind` false the one source serves one thread only.
  Profile(double x0, double dx, int n_intervals, ChunkOpener open, double retention, bool rewind);

  bool empty() const { return !c_ && !s_; }
  bool streamed() const { return static_cast<bool>(s_); }
  int n_intervals() const;
  double x0() const { return x0_; }
  double dx() const { return dx_; }
  // intervals held now (by all threads' passes), and the most one pass ever held at once (the
  // eager table: all of them)
  int loaded_intervals() const;
  int peak_loaded_intervals() const;
  int rewinds() const { return s_ ? s_->rewinds.load() : 0; }  // times a source was re-opened
  ProfileValue operator()(double x) const;

 private:
  // One thread's pass along the stream: the chunks it holds. Each thread reads its own (runs
  // in concurrent threads on one rail model do not undo each other's chunks); a thread's
  // successive runs share it.
  struct Cursor {
    ChunkSource next;
    std::deque<std::vector<double>> chunks;
    int first = 0;  // interval index of chunks.front()'s first interval
    int end = 0;    // one past the last loaded interval
    double furthest = 0.0;
    std::atomic<int> loaded{0}, peak{0};  // read by other threads' counters
  };
  struct Stream {
    ChunkOpener open;
    bool rewind = false;
    int n_total = 0;
    double retention = 0.0;
    std::atomic<int> rewinds{0};
    std::mutex mutex;  // guards the map only; a cursor is its thread's alone
    std::map<std::thread::id, Cursor> cursors;
  };
  Cursor& cursor() const;  // the calling thread's
  ProfileValue stream_value(int i, double u, double x) const;
  void load_through(Cursor& c, int i) const;
  void drop_behind(Cursor& c) const;
  void reopen(Cursor& c, double x) const;

  double x0_ = 0.0, dx_ = 1.0;
  // shared, never changed: a profile over kilometres (32 MB per km at 1 mm) is not copied
  // where the rail model takes its profile or a model is copied
  std::shared_ptr<const std::vector<double>> c_;
  // the streamed table's state, shared by the copies (the rail model copies its profile),
  // advanced by the const evaluation
  std::shared_ptr<Stream> s_;
};

}  // namespace trackwheel
