#include "profile.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace trackwheel {

namespace {

void check_grid(double x0, double dx) {
  if (!std::isfinite(x0)) throw std::invalid_argument("profile x0 must be finite");
  if (!(std::isfinite(dx) && dx > 0)) throw std::invalid_argument("profile dx must be > 0 m");
}

void check_coefficients(const std::vector<double>& coefs) {
  if (coefs.empty() || coefs.size() % 4 != 0)
    throw std::invalid_argument("profile coefficients must hold 4 values per interval (>= 1)");
  for (double c : coefs)
    if (!std::isfinite(c)) throw std::invalid_argument("profile coefficients must be finite");
}

// r, r', r'', r''' of the cubic c (c3, c2, c1, c0) at u = X - X_i
ProfileValue cubic(const double* c, double u) {
  ProfileValue v;
  v.r = ((c[0] * u + c[1]) * u + c[2]) * u + c[3];
  v.rx = (3.0 * c[0] * u + 2.0 * c[1]) * u + c[2];
  v.rxx = 6.0 * c[0] * u + 2.0 * c[1];
  v.rxxx = 6.0 * c[0];
  return v;
}

}  // namespace

Profile::Profile(double x0, double dx, std::vector<double> coefs) : x0_(x0), dx_(dx) {
  check_grid(x0_, dx_);
  check_coefficients(coefs);
  c_ = std::make_shared<const std::vector<double>>(std::move(coefs));
}

Profile::Profile(double x0, double dx, int n_intervals, ChunkOpener open, double retention,
                 bool rewind)
    : x0_(x0), dx_(dx) {
  check_grid(x0_, dx_);
  if (n_intervals < 1) throw std::invalid_argument("profile n_intervals must be >= 1");
  if (!open) throw std::invalid_argument("profile chunk source must be callable");
  if (!(std::isfinite(retention) && retention > 0))
    throw std::invalid_argument("profile retention must be finite > 0 m");
  s_ = std::make_shared<Stream>();
  s_->open = std::move(open);
  s_->rewind = rewind;
  s_->n_total = n_intervals;
  s_->retention = retention;
}

int Profile::n_intervals() const {
  if (s_) return s_->n_total;
  return c_ ? static_cast<int>(c_->size() / 4) : 0;
}

int Profile::loaded_intervals() const {
  if (!s_) return n_intervals();
  std::lock_guard<std::mutex> lock(s_->mutex);
  int n = 0;
  for (const auto& [id, c] : s_->cursors) n += c.loaded.load();
  return n;
}

int Profile::peak_loaded_intervals() const {
  if (!s_) return n_intervals();
  std::lock_guard<std::mutex> lock(s_->mutex);
  int n = 0;
  for (const auto& [id, c] : s_->cursors) n = std::max(n, c.peak.load());
  return n;
}

Profile::Cursor& Profile::cursor() const {
  Stream& s = *s_;
  bool fresh = false;
  Cursor* c = nullptr;
  {
    // the source is opened outside the lock: opening takes the GIL, which a thread waiting
    // here may hold
    std::lock_guard<std::mutex> lock(s.mutex);
    if (!s.rewind && !s.cursors.empty() && !s.cursors.count(std::this_thread::get_id()))
      throw std::runtime_error("a one-pass profile stream is read by one thread only");
    auto [it, inserted] = s.cursors.try_emplace(std::this_thread::get_id());
    c = &it->second;
    fresh = inserted;
  }
  if (fresh) c->furthest = -INFINITY;
  if (!c->next) c->next = s.open();  // also after an opening that threw
  return *c;
}

void Profile::load_through(Cursor& c, int i) const {
  const Stream& s = *s_;
  while (c.end <= i) {
    std::vector<double> v = c.next();
    if (v.empty())
      throw std::runtime_error("profile stream ended after " + std::to_string(c.end) +
                               " intervals, n_intervals = " + std::to_string(s.n_total));
    check_coefficients(v);
    const int m = static_cast<int>(v.size() / 4);
    if (m > s.n_total - c.end)
      throw std::runtime_error("profile stream holds more than n_intervals = " +
                               std::to_string(s.n_total) + " intervals");
    c.chunks.push_back(std::move(v));
    c.end += m;
    drop_behind(c);
    c.loaded = c.end - c.first;
    if (c.loaded > c.peak) c.peak = c.loaded.load();
  }
}

void Profile::drop_behind(Cursor& c) const {
  // a chunk ending behind furthest - retention goes; the newest one stays (it reaches there)
  while (c.chunks.size() > 1) {
    const int m = static_cast<int>(c.chunks.front().size() / 4);
    if (!(x0_ + (c.first + m) * dx_ < c.furthest - s_->retention)) break;
    c.chunks.pop_front();
    c.first += m;
  }
  c.loaded = c.end - c.first;
}

void Profile::reopen(Cursor& c, double x) const {
  c.chunks.clear();
  c.first = c.end = 0;
  c.loaded = 0;
  c.furthest = x >= x0_ ? x : -INFINITY;  // a new pass along the track
  c.next = nullptr;  // if opening throws, the next request opens again (never the old source)
  c.next = s_->open();
  ++s_->rewinds;
}

ProfileValue Profile::stream_value(int i, double u, double x) const {
  Cursor& c = cursor();
  // NaN never advances it; beyond the table's end (flat) counts as its end
  if (x > c.furthest) c.furthest = std::fmin(x, x0_ + s_->n_total * dx_);
  load_through(c, i);
  drop_behind(c);
  if (i < c.first && s_->rewind) {
    reopen(c, x);
    load_through(c, i);
  }
  if (i < c.first)
    throw std::runtime_error(
        "profile requested at X = " + std::to_string(x) + " m, behind the streamed profile's " +
        "kept range (from X = " + std::to_string(x0_ + c.first * dx_) + " m, " +
        std::to_string(s_->retention) + " m behind the furthest X requested, " +
        std::to_string(c.furthest) + " m): the stream reads the track forwards only");
  int k = c.first;
  for (const std::vector<double>& v : c.chunks) {
    const int m = static_cast<int>(v.size() / 4);
    if (i < k + m) return cubic(v.data() + 4 * (i - k), u);
    k += m;
  }
  throw std::logic_error("profile stream: interval not loaded");  // load_through loaded it
}

ProfileValue Profile::operator()(double x) const {
  if (empty()) return ProfileValue();
  const int m = n_intervals();
  const double x_end = x0_ + m * dx_;
  const bool before = !(x >= x0_);  // also catches NaN
  const bool beyond = x > x_end;
  int i = before ? 0 : beyond ? m - 1 : static_cast<int>((x - x0_) / dx_);
  if (i > m - 1) i = m - 1;
  const double u = before ? 0.0 : beyond ? dx_ : x - (x0_ + i * dx_);
  ProfileValue v = s_ ? stream_value(i, u, x) : cubic(c_->data() + 4 * i, u);
  if (before || beyond) v.rx = v.rxx = v.rxxx = 0.0;  // flat continuation
  return v;
}

}  // namespace trackwheel
