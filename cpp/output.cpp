#include "output.hpp"

#include <string_view>

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
  }};
  return table;
}

void Recording::start(int n_wheels, bool energy, std::size_t expected_samples) {
  n_wheels_ = n_wheels;
  energy_ = energy;
  const auto& table = output_fields();
  for (int f = 0; f < kFieldCount; ++f) {
    cols_[f].clear();
    if (!wants(static_cast<Field>(f))) continue;
    cols_[f].reserve(expected_samples * (table[f].per_wheel ? n_wheels : 1));
  }
}

std::size_t bytes_per_sample(int n_wheels, bool energy) {
  std::size_t b = 0;
  for (const FieldInfo& f : output_fields()) {
    if (!energy && std::string_view(f.name) == "energy") continue;
    b += (f.integer ? 4 : 8) * (f.per_wheel ? n_wheels : 1);
  }
  return b;
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
