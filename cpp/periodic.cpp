#include "periodic.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

#include "limits.hpp"
#include "periodic_poles.hpp"
#include "periodic_track.hpp"

namespace trackwheel {

namespace {

using periodic::cd;
using periodic::kPi;
using periodic::Line;
using periodic::Pole;
using periodic::Track;

// 15-point Kronrod abscissae (positive half, descending) and weights, and the embedded 7-point
// Gauss weights on xgk[1], xgk[3], xgk[5], xgk[7] (QUADPACK qk15; Piessens et al. 1983).
constexpr double kXgk[8] = {
    0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
    0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
    0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
    0.207784955007898467600689403773245, 0.0};
constexpr double kWgk[8] = {
    0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
    0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
    0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
    0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
constexpr double kWg[4] = {0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
                           0.381830050505118944950369775488975,
                           0.417959183673469387755102040816327};

constexpr int kExtraZones = 4;  // zones beyond the highest harmonic in [-K, K]
constexpr int kMaxRounds = 40;
constexpr std::size_t kMaxPanels = 20000;

struct Rule {
  double x[15], wk[15], wd[15];  // nodes on [-1, 1], Kronrod weights, Kronrod - Gauss
  Rule() {
    for (int i = 0; i < 7; ++i) {
      x[i] = -kXgk[i];
      x[14 - i] = kXgk[i];
      wk[i] = wk[14 - i] = kWgk[i];
    }
    x[7] = 0.0;
    wk[7] = kWgk[7];
    double wg[15] = {0};
    for (int j = 0; j < 4; ++j) {
      const int i = 2 * j + 1;  // xgk[1], [3], [5], [7]
      wg[i] = kWg[j];
      wg[14 - i] = kWg[j];
    }
    for (int i = 0; i < 15; ++i) wd[i] = wk[i] - wg[i];
  }
};
const Rule kRule;

struct Panel {
  double a, b;
  int kind;  // 0 central (k), 1 right tail, 2 left tail (u, k = +-K / u)
};

struct PanelResult {
  std::vector<Eigen::MatrixXcd> rank;   // per offset: Kronrod sum of w c h h^T (upper triangle)
  std::vector<Eigen::VectorXcd> diag;   // per offset: Kronrod sum of w diag
  std::vector<std::pair<int, cd>> fix;  // (pole, exact - Kronrod integral of 1/(k - k_c))
  double err = 0.0;
};

// One call's integral: the integrand's line, its poles and their amplitudes at the offsets,
// and the buffers of a panel's evaluation.
struct Quadrature {
  Quadrature(const Line& l, const std::vector<Pole>& p, const std::vector<double>& o, double k_tail)
      : line(l),
        poles(p),
        offsets(o),
        K(k_tail),
        M(l.size()),
        n_off(static_cast<int>(o.size())),
        i0((l.size() - 1) / 2),
        dg(M),
        H(M, 15),
        Wr(15, n_off),
        Wi(15, n_off),
        Rr(M, M),
        Ri(M, M) {
    const int nc = static_cast<int>(poles.size());
    amp.resize(n_off, nc);
    for (int j = 0; j < n_off; ++j)
      for (int c = 0; c < nc; ++c)
        amp(j, c) = poles[c].rho * std::exp(cd(0.0, 1.0) * poles[c].k * offsets[j]);
  }
  const Line& line;
  const std::vector<Pole>& poles;
  const std::vector<double>& offsets;
  double K;              // the tails are |k| > K [1/m]
  int M, n_off, i0;      // harmonics, offsets, the index of harmonic 0
  Eigen::MatrixXcd amp;  // (n_off, n_poles): the pole amplitudes rho e^{i k_c Delta}
  std::vector<cd> dg;    // buffers
  Eigen::MatrixXd H, Wr, Wi, Rr, Ri;
};

void check_input(const PeriodicTrackParams& p, double speed, double omega, int n) {
  auto finite_pos = [](double x) { return std::isfinite(x) && x > 0.0; };
  if (!finite_pos(p.bay) || !finite_pos(p.EI) || !finite_pos(p.mass) || p.shear < 0.0 ||
      p.rotary < 0.0 || !finite_pos(p.pad_stiffness) || p.pad_damping < 0.0 || p.sleeper_mass < 0.0)
    throw std::invalid_argument("periodic track: bay, EI, mass, pad stiffness must be > 0");
  if (!(speed >= 0.0) || !std::isfinite(omega) || (speed == 0.0 && omega == 0.0))
    throw std::invalid_argument("periodic receptance: speed >= 0 and omega != 0 when speed = 0");
  if (n < 0 || n > limits::kMaxPeriodicHarmonics)
    throw std::invalid_argument("periodic receptance: n in [0, " +
                                std::to_string(limits::kMaxPeriodicHarmonics) + "]");
}

// The central panels' edges: half Brillouin zones over [-K, K], and the static point
// k0 = Omega / v where the line crosses w' = 0.
std::vector<double> central_edges(double d, int zones, double K, double speed, double omega) {
  const double half = kPi / d;
  std::vector<double> edges;
  for (int j = -2 * zones; j <= 2 * zones; ++j) edges.push_back(j * half);
  if (speed > 0.0 && std::abs(omega / speed) < K) {
    const double k0 = omega / speed;
    if (std::find(edges.begin(), edges.end(), k0) == edges.end()) {
      edges.push_back(k0);
      std::sort(edges.begin(), edges.end());
    }
  }
  return edges;
}

// The poles subtracted on a panel: within one panel width of a central panel.
std::vector<int> near_poles(const Quadrature& q, const Panel& pn) {
  std::vector<int> near;
  if (pn.kind != 0) return near;
  for (int c = 0; c < static_cast<int>(q.poles.size()); ++c) {
    const cd kc = q.poles[c].k;
    const double dx = std::max({pn.a - kc.real(), kc.real() - pn.b, 0.0});
    const double width = pn.b - pn.a;
    if (dx * dx + kc.imag() * kc.imag() < width * width) near.push_back(c);
  }
  return near;
}

// The panel's 15 Kronrod points: the diagonal (r.diag), the Kronrod - Gauss differences of the
// diagonal and of column i0 (ed, ec), the integrals of 1/(k - k_c) of the near poles (lk, ld)
// and q.H, q.Wr, q.Wi for the rank-one part.
void evaluate_points(Quadrature& q, const Panel& pn, const std::vector<int>& near, PanelResult& r,
                     std::vector<Eigen::VectorXcd>& ed, std::vector<Eigen::VectorXcd>& ec,
                     std::vector<cd>& lk, std::vector<cd>& ld) {
  const double mid = 0.5 * (pn.a + pn.b), hw = 0.5 * (pn.b - pn.a);
  for (int i = 0; i < 15; ++i) {
    const double t = mid + hw * kRule.x[i];
    double k = t, jac = hw;
    if (pn.kind > 0) {
      k = (pn.kind == 2 ? -q.K : q.K) / t;
      jac = hw * q.K / (t * t);
    }
    cd c;
    q.line.parts(k, q.H.col(i).data(), c, q.dg.data());
    const double wk = jac * kRule.wk[i] / (2.0 * kPi), wd = jac * kRule.wd[i] / (2.0 * kPi);
    for (std::size_t a = 0; a < near.size(); ++a) {
      const cd z = k - q.poles[near[a]].k;
      const cd inv = std::conj(z) / std::norm(z);
      lk[a] += wk * inv;
      ld[a] += wd * inv;
    }
    for (int j = 0; j < q.n_off; ++j) {
      const cd ph = q.offsets[j] == 0.0 ? cd(1.0) : std::exp(cd(0.0, k * q.offsets[j]));
      const cd wck = wk * c * ph, wkp = wk * ph, wdp = wd * ph;
      q.Wr(i, j) = wck.real();
      q.Wi(i, j) = wck.imag();
      const cd wdc = wdp * c * q.H(q.i0, i);
      for (int b = 0; b < q.M; ++b) {
        r.diag[j](b) += wkp * q.dg[b];
        ed[j](b) += wdp * q.dg[b];
        ec[j](b) += (b == q.i0 ? wdp * q.dg[b] : wdc * q.H(b, i));
      }
    }
  }
}

// One panel's Kronrod sums, the exact-minus-Kronrod integrals of its near poles' terms and its
// error estimate (the Kronrod - Gauss difference with the pole terms taken out).
void integrate_panel(Quadrature& q, const Panel& pn, PanelResult& r) {
  const int M = q.M, n_off = q.n_off;
  r.rank.assign(n_off, Eigen::MatrixXcd(M, M));
  r.diag.assign(n_off, Eigen::VectorXcd::Zero(M));
  std::vector<Eigen::VectorXcd> ed(n_off, Eigen::VectorXcd::Zero(M)),
      ec(n_off, Eigen::VectorXcd::Zero(M));
  const std::vector<int> near = near_poles(q, pn);
  std::vector<cd> lk(near.size(), 0.0), ld(near.size(), 0.0);
  evaluate_points(q, pn, near, r, ed, ec, lk, ld);
  // the rank-one part: sum_i w_i c_i h_i h_i^T, h real (upper triangle suffices)
  for (int j = 0; j < n_off; ++j) {
    q.Rr.noalias() = q.H * q.Wr.col(j).asDiagonal() * q.H.transpose();
    q.Ri.noalias() = q.H * q.Wi.col(j).asDiagonal() * q.H.transpose();
    r.rank[j].real() = q.Rr;
    r.rank[j].imag() = q.Ri;
  }
  // exact integrals of the subtracted pole terms over this panel
  for (std::size_t a = 0; a < near.size(); ++a) {
    const cd kc = q.poles[near[a]].k;
    const cd exact = (std::log(pn.b - kc) - std::log(pn.a - kc)) / (2.0 * kPi);
    r.fix.emplace_back(near[a], exact - lk[a]);
  }
  double err = 0.0;
  for (int j = 0; j < n_off; ++j) {
    for (std::size_t a = 0; a < near.size(); ++a) {
      const Pole& pl = q.poles[near[a]];
      const cd f = ld[a] * q.amp(j, near[a]);
      for (int b = 0; b < M; ++b) {
        ed[j](b) -= f * pl.h(b) * pl.h(b);
        ec[j](b) -= f * pl.h(b) * pl.h(q.i0);
      }
    }
    err = std::max({err, ed[j].cwiseAbs().maxCoeff(), ec[j].cwiseAbs().maxCoeff()});
  }
  r.err = std::isfinite(err) ? err : std::numeric_limits<double>::infinity();
}

// Which panels are accepted: all when the summed error is within tol, else all but the worst
// ones, bisected until the rest is within half the tolerance.
std::vector<char> accepted(const std::vector<PanelResult>& res, double err_sum, double tol) {
  const std::size_t P = res.size();
  std::vector<char> accept(P, 1);
  if (err_sum <= tol) return accept;
  std::vector<std::size_t> order(P);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&](std::size_t x, std::size_t y) { return res[x].err > res[y].err; });
  double rest = err_sum;
  for (std::size_t i = 0; i < P; ++i) {
    accept[order[i]] = 0;
    rest -= res[order[i]].err;
    if (rest <= 0.5 * tol) break;
  }
  return accept;
}

// The matrices from the accepted sums: the rank-one part with the stable diagonal, plus the
// poles' exact-minus-Kronrod terms sum_c f_c h_c h_c^T.
std::vector<Eigen::MatrixXcd> assemble(const Quadrature& q,
                                       const std::vector<Eigen::MatrixXcd>& rank,
                                       const std::vector<Eigen::VectorXcd>& diag,
                                       const Eigen::VectorXcd& fix) {
  const int M = q.M, nc = static_cast<int>(q.poles.size());
  std::vector<Eigen::MatrixXcd> out(q.n_off);
  for (int j = 0; j < q.n_off; ++j) {
    Eigen::MatrixXcd A = rank[j];
    for (int b = 0; b < M; ++b) A(b, b) = diag[j](b);
    if (nc > 0) {
      Eigen::MatrixXcd Hc(M, nc);
      Eigen::VectorXcd f(nc);
      for (int c = 0; c < nc; ++c) {
        Hc.col(c) = q.poles[c].h;
        f(c) = fix(c) * q.amp(j, c);
      }
      A.noalias() += Hc * f.asDiagonal() * Hc.transpose();
    }
    out[j] = A;
  }
  return out;
}

}  // namespace

std::complex<double> periodic_lattice_sum(const PeriodicTrackParams& track, std::complex<double> k,
                                          std::complex<double> w) {
  return Track(track).lattice_sum(k, w);
}

std::vector<Eigen::MatrixXcd> periodic_receptance_matrix(const PeriodicTrackParams& p, double speed,
                                                         double omega, int n,
                                                         const std::vector<double>& offsets,
                                                         double rtol, PeriodicStats* stats) {
  check_input(p, speed, omega, n);
  const Track tr(p);
  const Line line(tr, speed, omega, n);
  const int M = line.size(), n_off = static_cast<int>(offsets.size());
  const double d = tr.bay();
  const int zones = n + kExtraZones;
  const double K = 2.0 * kPi * zones / d;
  const std::vector<double> edges = central_edges(d, zones, K, speed, omega);
  PeriodicStats local;
  PeriodicStats& st = stats ? *stats : local;
  st = PeriodicStats();
  const std::vector<Pole> poles = periodic::find_poles(line, edges, st.den_evaluations);
  st.poles = static_cast<int>(poles.size());
  Quadrature q(line, poles, offsets, K);

  std::vector<Panel> panels;
  for (std::size_t e = 0; e + 1 < edges.size(); ++e) panels.push_back({edges[e], edges[e + 1], 0});
  const double tails[5] = {0.0, 0.125, 0.25, 0.5, 1.0};
  for (int kind = 1; kind <= 2; ++kind)
    for (int i = 0; i < 4; ++i) panels.push_back({tails[i], tails[i + 1], kind});

  std::vector<Eigen::MatrixXcd> rank(n_off, Eigen::MatrixXcd::Zero(M, M));
  std::vector<Eigen::VectorXcd> diag(n_off, Eigen::VectorXcd::Zero(M));
  Eigen::VectorXcd fix = Eigen::VectorXcd::Zero(static_cast<int>(poles.size()));
  double scale = 0.0;
  for (int round = 0; round < kMaxRounds; ++round) {
    const std::size_t P = panels.size();
    st.rounds = round + 1;
    st.points += 15 * static_cast<long>(P);
    std::vector<PanelResult> res(P);
    double err_sum = 0.0;
    Eigen::VectorXcd est = Eigen::VectorXcd::Zero(M);  // the diagonal so far, for the scale
    for (int j = 0; j < n_off && j < 1; ++j) est = diag[j];
    for (std::size_t ip = 0; ip < P; ++ip) {
      integrate_panel(q, panels[ip], res[ip]);
      err_sum += res[ip].err;
      est += res[ip].diag[0];
    }
    scale = std::max(scale, est.cwiseAbs().maxCoeff());
    const std::vector<char> accept = accepted(res, err_sum, rtol * scale);
    std::vector<Panel> next;
    for (std::size_t ip = 0; ip < P; ++ip) {
      if (accept[ip]) {
        for (int j = 0; j < n_off; ++j) {
          rank[j] += res[ip].rank[j];
          diag[j] += res[ip].diag[j];
        }
        for (const auto& [c, v] : res[ip].fix) fix(c) += v;
      } else {
        const Panel& pn = panels[ip];
        const double m = 0.5 * (pn.a + pn.b);
        next.push_back({pn.a, m, pn.kind});
        next.push_back({m, pn.b, pn.kind});
      }
    }
    if (next.empty()) return assemble(q, rank, diag, fix);
    if (next.size() > kMaxPanels) break;
    panels.swap(next);
  }
  throw std::runtime_error(
      "the k quadrature of the moving-load receptance did not converge to rtol = " +
      std::to_string(rtol) + " (speed " + std::to_string(speed) + " m/s, frequency " +
      std::to_string(omega / (2.0 * kPi)) +
      " Hz): the tolerance is below the integrand's round-off, or the track is nearly undamped "
      "at a wave the wheel excites (a larger rtol, or more support damping)");
}

}  // namespace trackwheel
