#include "profile.hpp"

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
  s_->furthest = -INFINITY;
  s_->next = s_->open();
}

int Profile::n_intervals() const {
  if (s_) return s_->n_total;
  return c_ ? static_cast<int>(c_->size() / 4) : 0;
}

int Profile::loaded_intervals() const {
  if (!s_) return n_intervals();
  return s_->end - s_->first;
}

int Profile::peak_loaded_intervals() const { return s_ ? s_->peak : n_intervals(); }

void Profile::load_through(int i) const {
  Stream& s = *s_;
  while (s.end <= i) {
    std::vector<double> c = s.next();
    if (c.empty())
      throw std::runtime_error("profile stream ended after " + std::to_string(s.end) +
                               " intervals, n_intervals = " + std::to_string(s.n_total));
    check_coefficients(c);
    const int m = static_cast<int>(c.size() / 4);
    if (m > s.n_total - s.end)
      throw std::runtime_error("profile stream holds more than n_intervals = " +
                               std::to_string(s.n_total) + " intervals");
    s.chunks.push_back(std::move(c));
    s.end += m;
    drop_behind(s.furthest);
    if (s.end - s.first > s.peak) s.peak = s.end - s.first;
  }
}

void Profile::drop_behind(double x) const {
  Stream& s = *s_;
  // a chunk ending behind x - retention goes; the newest one stays (it reaches up to x)
  while (s.chunks.size() > 1) {
    const int m = static_cast<int>(s.chunks.front().size() / 4);
    if (!(x0_ + (s.first + m) * dx_ < x - s.retention)) break;
    s.chunks.pop_front();
    s.first += m;
  }
}

void Profile::reopen(double x) const {
  Stream& s = *s_;
  s.chunks.clear();
  s.first = s.end = 0;
  s.furthest = x >= x0_ ? x : -INFINITY;  // a new pass along the track
  s.next = s.open();
  ++s.rewinds;
}

const double* Profile::interval(int i, double x) const {
  Stream& s = *s_;
  // NaN never advances it; beyond the table's end (flat) counts as its end
  if (x > s.furthest) s.furthest = std::fmin(x, x0_ + s.n_total * dx_);
  load_through(i);
  drop_behind(s.furthest);
  if (i < s.first && s.rewind) {
    reopen(x);
    load_through(i);
  }
  if (i < s.first)
    throw std::runtime_error(
        "profile requested at X = " + std::to_string(x) + " m, behind the streamed profile's " +
        "kept range (from X = " + std::to_string(x0_ + s.first * dx_) + " m, " +
        std::to_string(s.retention) + " m behind the furthest X requested, " +
        std::to_string(s.furthest) + " m): the stream reads the track forwards only");
  int k = s.first;
  for (const std::vector<double>& c : s.chunks) {
    const int m = static_cast<int>(c.size() / 4);
    if (i < k + m) return c.data() + 4 * (i - k);
    k += m;
  }
  throw std::logic_error("profile stream: interval not loaded");  // load_through loaded it
}

ProfileValue Profile::operator()(double x) const {
  ProfileValue v;
  if (empty()) return v;
  const int m = n_intervals();
  const double x_end = x0_ + m * dx_;
  const bool before = !(x >= x0_);  // also catches NaN
  const bool beyond = x > x_end;
  int i = before ? 0 : beyond ? m - 1 : static_cast<int>((x - x0_) / dx_);
  if (i > m - 1) i = m - 1;
  const double u = before ? 0.0 : beyond ? dx_ : x - (x0_ + i * dx_);
  const double* c = s_ ? interval(i, x) : c_->data() + 4 * i;
  v.r = ((c[0] * u + c[1]) * u + c[2]) * u + c[3];
  if (before || beyond) return v;  // flat continuation
  v.rx = (3.0 * c[0] * u + 2.0 * c[1]) * u + c[2];
  v.rxx = 6.0 * c[0] * u + 2.0 * c[1];
  return v;
}

}  // namespace trackwheel
