#include "linear_track.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "banded.hpp"

namespace trackwheel {

namespace {

std::string fmt(double x) { return format3(x); }

// The linear vertical track in generalised coordinates q (y coordinates, or modal).
struct LinearTrack {
  int ny = 0, nq = 0, bw = 3;
  bool modal = false;
  std::vector<int> full_of_y;        // y coordinate -> full ANCF index
  std::vector<int> y_of_full;        // full -> y coordinate (-1)
  BandMatrix M, C, K;                // over q
  Eigen::VectorXd Qg;                // over q
  Eigen::MatrixXd Phi;               // ny x nq (modal only)
  const RailModel* rail = nullptr;

  explicit LinearTrack(const RailModel& r, int n_modes) : rail(&r) {
    const auto& f2f = r.full_to_free();
    y_of_full.assign(r.n_dof(), -1);
    for (int i = 0; i < r.n_dof(); ++i)
      if (f2f[i] >= 0 && i % 2 == 1) {
        y_of_full[i] = static_cast<int>(full_of_y.size());
        full_of_y.push_back(i);
      }
    ny = static_cast<int>(full_of_y.size());
    // y blocks of the free-coordinate band matrices at the straight reference
    BandMatrix Kf(r.n_free(), kHalfBandwidth);
    r.add_tangent(r.reference(), 1.0, Kf);
    BandMatrix My(ny, 3), Cy(ny, 3), Ky(ny, 3);
    for (int a = 0; a < ny; ++a)
      for (int b = std::max(0, a - 3); b <= std::min(ny - 1, a + 3); ++b) {
        const int i = f2f[full_of_y[a]], j = f2f[full_of_y[b]];
        if (!r.mass().in_band(i, j)) continue;
        My.at(a, b) = r.mass().at(i, j);
        Cy.at(a, b) = r.support_damping().at(i, j);
        Ky.at(a, b) = Kf.at(i, j);
      }
    Eigen::VectorXd Qgy(ny);
    for (int a = 0; a < ny; ++a) Qgy(a) = r.gravity_force()(full_of_y[a]);
    if (n_modes <= 0) {
      nq = ny;
      M = My;
      C = Cy;
      K = Ky;
      Qg = Qgy;
      return;
    }
    if (n_modes > ny)
      throw std::invalid_argument("n_modes must be in [1, " + std::to_string(ny) + "]");
    modal = true;
    nq = n_modes;
    bw = nq - 1;
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(Ky.dense(), My.dense());
    if (es.info() != Eigen::Success) throw std::runtime_error("modal reduction failed");
    Phi = es.eigenvectors().leftCols(nq);  // mass-normalised
    const Eigen::MatrixXd Cm = Phi.transpose() * Cy.dense() * Phi;
    M.resize(nq, bw);
    C.resize(nq, bw);
    K.resize(nq, bw);
    for (int a = 0; a < nq; ++a) {
      M.at(a, a) = 1.0;
      K.at(a, a) = es.eigenvalues()(a);
      for (int b = 0; b < nq; ++b) C.at(a, b) = Cm(a, b);
    }
    Qg = Phi.transpose() * Qgy;
  }

  // The generalised-coordinate vector of the y coordinate with full ANCF index i (zero if fixed):
  // a unit vector, or a row of Phi.
  Eigen::VectorXd basis(int i) const {
    const int k = y_of_full[i];
    if (k < 0) return Eigen::VectorXd::Zero(nq);
    if (modal) return Phi.row(k).transpose();
    Eigen::VectorXd e = Eigen::VectorXd::Zero(nq);
    e(k) = 1.0;
    return e;
  }

  // s(X), s_s(X), s_ss(X) over q: y(X) = s . q etc.
  void coupling(double X, Eigen::VectorXd& s, Eigen::VectorXd& ss, Eigen::VectorXd& sss) const {
    const MeshPoint mp = rail->locate(X);
    Eigen::VectorXd y = Eigen::VectorXd::Zero(ny), ys = y, yss = y;
    for (int a = 0; a < 4; ++a) {
      const int k = y_of_full[mp.dof0() + 2 * a + 1];
      if (k < 0) continue;
      y(k) = mp.h.n[a];
      ys(k) = mp.h.ns[a];
      yss(k) = mp.h.nss[a];
    }
    if (modal) {
      s = Phi.transpose() * y;
      ss = Phi.transpose() * ys;
      sss = Phi.transpose() * yss;
    } else {
      s = y;
      ss = ys;
      sss = yss;
    }
  }
};

}  // namespace

SimOutput simulate_linear(const RailModel& rail, const WheelParams& wheel,
                          const ContactParams& contact, const SimSettings& set,
                          const LinearOptions& opt, const ProgressFn& progress) {
  check_settings(set);
  const LinearTrack tr(rail, opt.n_modes);
  const int nq = tr.nq;
  const WheelModel wm = opt.wheel_model;
  const double P = wheel.total_load(), r0 = wheel.radius, v = set.speed, h = set.dt;
  const double Mw = wheel.mass;
  auto law = [&](double delta, double& dN) {  // contact force and stiffness
    if (wm == WheelModel::Sprung) {
      dN = contact.stiffness;
      return contact.stiffness * delta;
    }
    if (delta <= 0.0) {
      dN = 0.0;
      return 0.0;
    }
    const double sq = std::sqrt(delta);
    dN = 1.5 * contact.stiffness * sq;
    return contact.stiffness * delta * sq;
  };
  auto static_compression = [&]() {
    if (wm == WheelModel::Sprung) return P / contact.stiffness;
    if (wm == WheelModel::Hertz) return std::pow(P / contact.stiffness, 2.0 / 3.0);
    return 0.0;
  };

  // initial state
  Eigen::VectorXd s, ss, sss;
  tr.coupling(set.x_start, s, ss, sss);
  BandMatrix Kf = tr.K;
  if (!Kf.factorize()) throw std::runtime_error("rail stiffness is singular");
  Eigen::VectorXd q = tr.Qg;
  if (!opt.sudden) q -= P * s;
  Kf.solve_in_place(q);
  Eigen::VectorXd qd = Eigen::VectorXd::Zero(nq), qdd = Eigen::VectorXd::Zero(nq);
  double Y = s.dot(q) + r0 + opt.drop_height - (opt.sudden ? 0.0 : static_compression());
  double Yd = 0.0, Ydd = 0.0, N = 0.0, dN = 0.0;
  if (wm == WheelModel::MovingForce) N = P;
  else if (wm == WheelModel::MovingMass) N = opt.sudden ? 0.0 : P;
  else N = law(r0 - Y + s.dot(q), dN);
  {  // initial accelerations with the initial contact force
    Eigen::VectorXd rhs = tr.Qg - N * s, Kq, Cq;
    tr.K.multiply(q, Kq);
    rhs -= Kq;
    BandMatrix Mf = tr.M;
    if (!Mf.factorize()) throw std::runtime_error("rail mass matrix is singular");
    Mf.solve_in_place(rhs);
    qdd = rhs;
    Ydd = wm == WheelModel::MovingForce || wm == WheelModel::MovingMass ? s.dot(qdd)
                                                                         : (N - P) / Mw;
  }

  // generalized-alpha (Chung-Hulbert parameters, Arnold-Bruls form)
  const double ri = set.rho_inf;
  const double am = (2.0 * ri - 1.0) / (ri + 1.0), af = ri / (ri + 1.0);
  const double gam = 0.5 - am + af, bet = 0.25 * (1.0 - am + af) * (1.0 - am + af);
  const double bp = bet * (1.0 - af) / (1.0 - am), gp = gam * (1.0 - af) / (1.0 - am);
  const double cq = bp * h * h, cv = gp * h;
  BandMatrix A(nq, tr.bw);
  A.set_linear_combination(1.0, tr.M, cv, tr.C);
  A.add_scaled(cq, tr.K);
  if (!A.factorize()) throw std::runtime_error("iteration matrix is singular");

  SimOutput out;
  const long n_steps = static_cast<long>(std::llround(set.t_end / h));
  auto record = [&](double t) {
    tr.coupling(set.x_start + v * t, s, ss, sss);
    const double yc = s.dot(q), ys = ss.dot(q), yss = sss.dot(q), yst = ss.dot(qd);
    out.t.push_back(t);
    out.x_wheel.push_back(set.x_start + v * t);
    out.y_wheel.push_back(Y);
    out.ydot_wheel.push_back(Yd);
    out.theta.push_back(v * t / r0);
    out.thetadot.push_back(v / r0);
    out.contact_s.push_back(set.x_start + v * t);
    out.y_contact.push_back(yc);
    out.normal_force.push_back(N);
    out.tangential_force.push_back(0.0);
    out.slip.push_back(0.0);
    out.v_error.push_back(0.0);
    const double phi = std::atan(ys), g = 1.0 + ys * ys;
    const double phi_s = yss / g, phi_t = yst / g;
    const double delta = wm == WheelModel::MovingForce || wm == WheelModel::MovingMass
                             ? 0.0
                             : r0 - Y + yc;
    const double rc = (r0 - delta) * std::cos(phi), thd = v / r0;
    out.phi.push_back(phi);
    out.acc_A.push_back(rc * thd * v * phi_s);
    out.acc_B.push_back(rc * thd * phi_t);
    out.acc_C.push_back(rc * v * v * phi_s * phi_s);
    out.acc_D.push_back(rc * phi_t * phi_t);
    out.acc_E.push_back(2.0 * rc * phi_t * v * phi_s);
    out.acc_contact.push_back(s.dot(qdd) + 2.0 * v * ss.dot(qd) + v * v * yss);
    out.reaction.push_back(0.0);
    out.penetration.push_back(delta);
    out.state.push_back(N > 0.0 ? 1 : 0);
    if (set.record_energy) {
      Eigen::VectorXd Mqd, Kq;
      tr.M.multiply(qd, Mqd);
      tr.K.multiply(q, Kq);
      double Vc = 0.0;
      if (wm == WheelModel::Sprung) Vc = 0.5 * contact.stiffness * delta * delta;
      if (wm == WheelModel::Hertz && delta > 0)
        Vc = 0.4 * contact.stiffness * delta * delta * std::sqrt(delta);
      out.energy.push_back(0.5 * qd.dot(Mqd) + 0.5 * q.dot(Kq) - tr.Qg.dot(q) +
                           0.5 * Mw * Yd * Yd + P * Y + Vc);
    }
  };
  record(0.0);

  Eigen::VectorXd a = qdd, Kq, Cq, r1, x1, x2, g;
  const bool damped = tr.C.dense().cwiseAbs().maxCoeff() > 0.0;
  double aY = Ydd;
  Eigen::Matrix2d D;
  Eigen::MatrixXd W(nq, 4);
  Eigen::VectorXd Z(nq);
  int cache_el = -1;
  Eigen::VectorXd r2(2);
  for (long n = 1; n <= n_steps; ++n) {
    const double t1 = n * h;
    const double X1 = set.x_start + v * t1;
    tr.coupling(X1, s, ss, sss);
    {  // Z = A^-1 s(X) = sum_a N_a A^-1 s_a, columns cached per element
      const MeshPoint mp = rail.locate(X1);
      if (mp.element != cache_el) {
        for (int k = 0; k < 4; ++k) {
          W.col(k) = tr.basis(mp.dof0() + 2 * k + 1);
          if (!W.col(k).isZero(0.0)) A.solve_in_place(W.col(k));
        }
        cache_el = mp.element;
      }
      Z = mp.h.n[0] * W.col(0) + mp.h.n[1] * W.col(1) + mp.h.n[2] * W.col(2) +
          mp.h.n[3] * W.col(3);
    }
    // predictors: q_{n+1} = qh + cq qdd_{n+1}, qd_{n+1} = qdh + cv qdd_{n+1}
    const Eigen::VectorXd q0 = q, qd0 = qd, qdd0 = qdd, a0 = a;
    const double Y0 = Y, Yd0 = Yd, Ydd0 = Ydd, aY0 = aY;
    const Eigen::VectorXd ah = (af * qdd0 - am * a0) / (1.0 - am);  // a_{n+1} minus qdd part
    const Eigen::VectorXd qh = q0 + h * qd0 + h * h * ((0.5 - bet) * a0 + bet * ah);
    const Eigen::VectorXd qdh = qd0 + h * ((1.0 - gam) * a0 + gam * ah);
    const double aYh = (af * Ydd0 - am * aY0) / (1.0 - am);
    const double Yh = Y0 + h * Yd0 + h * h * ((0.5 - bet) * aY0 + bet * aYh);
    const double Ydh = Yd0 + h * ((1.0 - gam) * aY0 + gam * aYh);
    // g = C qdh + K qh - Q_g: r_q(qdd) = (M + cv C + cq K) qdd + g + s N
    tr.K.multiply(qh, g);
    if (damped) {
      tr.C.multiply(qdh, Cq);
      g += Cq;
    }
    g -= tr.Qg;
    // Newton from qdd_{n+1} = 0: exact in one iteration for the linear wheel models
    Eigen::VectorXd qdd1 = Eigen::VectorXd::Zero(nq);
    double Ydd1 = 0.0, N1 = N;
    bool conv = false;
    for (int it = 0; it < std::max(set.max_newton, 1); ++it) {
      q = qh + cq * qdd1;
      qd = qdh + cv * qdd1;
      Y = Yh + cq * Ydd1;
      Yd = Ydh + cv * Ydd1;
      // residuals r = inertia + internal - external (solve J dx = -r)
      if (it == 0) {
        r1 = -(g + N1 * s);
      } else {
        tr.M.multiply(qdd1, r1);
        tr.K.multiply(qdd1, Kq);
        r1 += cq * Kq + g + N1 * s;
        if (damped) {
          tr.C.multiply(qdd1, Cq);
          r1 += cv * Cq;
        }
        r1 = -r1;
      }
      // border [Y'', N]: A x1 + s dN = r1,  D [dY''; dN] + c s^T x1 e_1 = r2
      D.setZero();
      double c = 0.0;
      switch (wm) {
        case WheelModel::MovingForce:
          r2(0) = -Ydd1;  // dummy: the 'wheel' follows nothing
          r2(1) = -(N1 - P);
          D(0, 0) = 1.0;
          D(1, 1) = 1.0;
          break;
        case WheelModel::MovingMass:
          r2(0) = -(Mw * Ydd1 - N1 + P);
          r2(1) = -(Y - s.dot(q) - r0) / cq;
          D(0, 0) = Mw;
          D(0, 1) = -1.0;
          D(1, 0) = 1.0;
          c = -1.0;
          break;
        default: {
          const double delta = r0 - Y + s.dot(q);
          const double Nd = law(delta, dN);
          r2(0) = -(Mw * Ydd1 - N1 + P);
          r2(1) = -(N1 - Nd);
          D(0, 0) = Mw;
          D(0, 1) = -1.0;
          D(1, 1) = 1.0;
          D(1, 0) = dN * cq;
          c = -dN * cq;
        }
      }
      // Schur complement on the 2-wide border with Z = A^-1 s from the element cache
      x1 = r1;
      A.solve_in_place(x1);
      Eigen::Matrix2d S = D;
      S(1, 1) -= c * s.dot(Z);
      const Eigen::Vector2d rhs(r2(0), r2(1) - c * s.dot(x1));
      const double det = S.determinant();
      if (!std::isfinite(det) || det == 0.0) {
        std::ostringstream msg;
        msg << "simulation diverged at t = " << fmt(t1) << " s (step " << n
            << "): singular iteration matrix";
        throw DivergenceError(msg.str(), t1, n, "singular iteration matrix");
      }
      const Eigen::Vector2d xb = S.partialPivLu().solve(rhs);
      x2 = xb;
      x1 -= xb(1) * Z;
      ++out.newton_iterations;
      qdd1 += x1;
      Ydd1 += x2(0);
      N1 += x2(1);
      const double dq = cq * std::max(x1.lpNorm<Eigen::Infinity>(), std::abs(x2(0)));
      const bool linear = wm != WheelModel::Hertz;
      if (linear || (dq <= set.newton_tol && std::abs(x2(1)) <= 1e-6 * std::max(1.0, P))) {
        conv = true;
        q = qh + cq * qdd1;  // the state at the final accelerations
        qd = qdh + cv * qdd1;
        Y = Yh + cq * Ydd1;
        Yd = Ydh + cv * Ydd1;
        a = ah + ((1.0 - af) / (1.0 - am)) * qdd1;
        aY = aYh + ((1.0 - af) / (1.0 - am)) * Ydd1;
        break;
      }
    }
    if (!conv || !q.allFinite() || !std::isfinite(Y)) {
      std::ostringstream msg;
      msg << "simulation diverged at t = " << fmt(t1) << " s (step " << n << "): "
          << (conv ? "non-finite state" : "Newton did not converge");
      throw DivergenceError(msg.str(), t1, n,
                            "the time step " + fmt(h) + " s is too large for the contact");
    }
    qdd = qdd1;
    Ydd = Ydd1;
    N = N1;
    if (wm == WheelModel::MovingForce) {
      Y = s.dot(q) + r0;
      Yd = 0.0;
    }
    out.steps = n;
    if (n % set.output_every == 0) record(t1);
    if (progress && set.progress_every > 0 && n % set.progress_every == 0) progress(n, n_steps);
  }
  return out;
}

}  // namespace trackwheel
