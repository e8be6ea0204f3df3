#include "output.hpp"

#include <algorithm>
#include <string_view>
#include <utility>

namespace trackwheel {

const std::array<FieldInfo, kFieldCount>& output_fields() {
  static const std::array<FieldInfo, kFieldCount> table = {{
      {"t", "s", "time", false, false},
      {"x_wheel", "m", "X_A, wheel-centre position (prescribed X_0 + v t)", true, false},
      {"y_wheel", "m", "Y_A, wheel-centre height", true, false},
      {"ydot_wheel", "m/s", "dY_A/dt", true, false},
      {"theta", "rad", "rolling angle", true, false},
      {"thetadot", "rad/s", "rolling rate", true, false},
      {"contact_s", "m", "s*, rail coordinate of the contact point", true, false},
      {"y_contact", "m", "y_B = y(s*), rail displacement under the wheel", true, false},
      {"normal_force", "N", "N, normal contact force (0 without contact)", true, false},
      {"tangential_force", "N", "lambda, tangential contact force on the wheel", true, false},
      {"slip", "m/s", "slip velocity t.(V_A - S edot) - rho thetadot", true, false},
      {"slip_state", "", "0 no contact, 1 stick, 2 slide", true, true},
      {"v_error", "%", "paper's eq. 28, (dX/dt - rho dtheta/dt)/(dX/dt) 100", true, false},
      {"phi", "rad", "rail obliquity at the contact point", true, false},
      {"acc_contact", "m/s^2",
       "vertical acceleration of the contact point d2 y_B/dt2 = S_y e'' + 2 s' S_y,s e' + "
       "s'^2 y_ss (s'' y_s neglected)",
       true, false},
      {"acc_A", "m/s^2", "rho cos(phi) theta' v phi_s (docs: Model § Outputs)", true, false},
      {"acc_B", "m/s^2", "rho cos(phi) theta' phi_t", true, false},
      {"acc_C", "m/s^2", "rho cos(phi) v^2 phi_s^2", true, false},
      {"acc_D", "m/s^2", "rho cos(phi) phi_t^2", true, false},
      {"acc_E", "m/s^2", "2 rho cos(phi) phi_t v phi_s", true, false},
      {"reaction", "N", "horizontal force holding X_A = X_0 + v t", true, false},
      {"penetration", "m", "rho0 - rho (negative: gap)", true, false},
      {"energy", "J", "total mechanical energy (recorded on request only)", false, false},
      {"rail_seat_force", "N",
       "rail-seat force of each support, the pad's compression -(k_p (y - z) + c_p (y' - z')) "
       "(single springs: -(k_s y + c_s y'))",
       false, false, true},
      {"ballast_force", "N",
       "ballast force under each sleeper, the bed's compression -(k_b z + c_b z') (single "
       "springs: the spring's force)",
       false, false, true},
      {"sleeper_z", "m", "each sleeper's displacement z (up positive; 0 for single springs)", false,
       false, true},
  }};
  return table;
}

namespace {
std::size_t per_sample(const FieldInfo& f, int n_wheels, int n_supports) {
  return f.per_wheel ? n_wheels : (f.per_support ? n_supports : 1);
}
}  // namespace

bool Recording::wants(Field f) const {
  if (f == Field::energy) return energy_;
  return !output_fields()[static_cast<int>(f)].per_support || n_supports_ > 0;
}

void Recording::start(int n_wheels, bool energy, std::size_t expected_samples, int n_supports) {
  n_wheels_ = n_wheels;
  energy_ = energy;
  n_supports_ = n_supports;
  const auto& table = output_fields();
  for (int f = 0; f < kFieldCount; ++f) {
    cols_[f].clear();
    if (!wants(static_cast<Field>(f))) continue;
    cols_[f].reserve(expected_samples * per_sample(table[f], n_wheels, n_supports));
  }
}

std::size_t bytes_per_sample(int n_wheels, bool energy, int n_supports) {
  std::size_t b = 0;
  for (const FieldInfo& f : output_fields()) {
    if (!energy && std::string_view(f.name) == "energy") continue;
    b += (f.integer ? 4 : 8) * per_sample(f, n_wheels, n_supports);
  }
  return b;
}

const std::array<EnvelopeInfo, kEnvelopeFieldCount>& envelope_fields() {
  static const std::array<EnvelopeInfo, kEnvelopeFieldCount> table = {{
      {"x", "m", "X_j, the support's track coordinate"},
      {"ballast_force_max", "N", "largest ballast force (compression positive)"},
      {"ballast_force_min", "N", "smallest ballast force (negative: the bed pulls)"},
      {"rail_seat_force_max", "N", "largest rail-seat force (compression positive)"},
      {"rail_seat_force_min", "N", "smallest rail-seat force (negative: the pad pulls)"},
      {"sleeper_z_min", "m", "the sleeper's largest downward displacement, min z"},
      {"contact_time", "s", "time the ballast carried load (ballast force > 0)"},
      {"observed_time", "s", "time the support was in the rail (a travelling window's share)"},
  }};
  return table;
}

void SupportEnvelope::observe(long k, double X, double Fb, double Fp, double z, double dt_sample) {
  const auto i = static_cast<std::size_t>(k);
  if (i >= size()) {
    constexpr double inf = std::numeric_limits<double>::infinity();
    const double fresh[kEnvelopeFieldCount] = {X, -inf, inf, -inf, inf, inf, 0.0, 0.0};
    for (int f = 0; f < kEnvelopeFieldCount; ++f) cols_[f].resize(i + 1, fresh[f]);
  }
  auto col = [&](EnvelopeField f) -> double& { return cols_[static_cast<int>(f)][i]; };
  col(EnvelopeField::ballast_force_max) = std::max(col(EnvelopeField::ballast_force_max), Fb);
  col(EnvelopeField::ballast_force_min) = std::min(col(EnvelopeField::ballast_force_min), Fb);
  col(EnvelopeField::rail_seat_force_max) = std::max(col(EnvelopeField::rail_seat_force_max), Fp);
  col(EnvelopeField::rail_seat_force_min) = std::min(col(EnvelopeField::rail_seat_force_min), Fp);
  col(EnvelopeField::sleeper_z_min) = std::min(col(EnvelopeField::sleeper_z_min), z);
  // the place where a voided sleeper's time on its bed is counted: the ballast carries load
  if (Fb > 0.0) col(EnvelopeField::contact_time) += dt_sample;
  col(EnvelopeField::observed_time) += dt_sample;
}

SupportRecorder::SupportRecorder(const RailModel& rail, std::vector<int> map)
    : map_(std::move(map)) {
  for (double x : rail.supports().position) pt_.push_back(rail.locate(x));
}

double SupportRecorder::y(int j, const Eigen::VectorXd& u) const {
  double v = 0.0;
  for (int a = 0; a < 4; ++a) {
    const int i = map_[pt_[j].dof0() + 2 * a + 1];
    if (i >= 0) v += pt_[j].h.n[a] * u(i);
  }
  return v;
}

void SupportRecorder::record(const RailModel& rail, const Eigen::VectorXd& u,
                             const Eigen::VectorXd& udot, const Eigen::VectorXd& z,
                             const Eigen::VectorXd& zdot, const Sleepers& sleepers, long first,
                             double origin, double dt_sample, Recording& rec,
                             SupportEnvelope& env) const {
  const SupportParams& sp = rail.supports();
  const bool layered = z.size() == size() && !sp.sleeper_mass.empty();
  const bool histories = rec.wants(Field::rail_seat_force);
  for (int j = 0; j < size(); ++j) {
    const double yj = y(j, u), ydj = y(j, udot);
    const double zj = layered ? z(j) : 0.0, zdj = layered ? zdot(j) : 0.0;
    const double Fp = -(sp.stiffness[j] * (yj - zj) + sp.damping[j] * (ydj - zdj));
    // each sleeper's own ballast law in its committed state: a void's or a tensionless bed
    // pushes only once closed (k_b d + c_b d', d = -z - g) and carries nothing open
    const double Fb = layered ? sleepers.ballast(j, zj, zdj) : Fp;
    if (histories) {
      rec.push(Field::rail_seat_force, Fp);
      rec.push(Field::ballast_force, Fb);
      rec.push(Field::sleeper_z, zj);
    }
    env.observe(first + j, origin + sp.position[j], Fb, Fp, zj, dt_sample);
  }
}

void record_acc_terms(Recording& rec, double rc, double thetadot, double v, double phi_s,
                      double phi_t) {
  rec.push(Field::acc_A, rc * thetadot * v * phi_s);
  rec.push(Field::acc_B, rc * thetadot * phi_t);
  rec.push(Field::acc_C, rc * v * v * phi_s * phi_s);
  rec.push(Field::acc_D, rc * phi_t * phi_t);
  rec.push(Field::acc_E, 2.0 * rc * phi_t * v * phi_s);
}

}  // namespace trackwheel
