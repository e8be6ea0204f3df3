// The output table: one row per recorded field (name, unit, doc, per wheel or not, dtype).
//
// This table is the single definition of an output: the recorder fills the fields in table
// order, the binding turns each into a numpy array keyed by its name (per-wheel fields with
// shape (n_samples, n_wheels)), exports the table as _core.OUTPUT_FIELDS, and Python builds
// Result's array fields and their documentation from it. Adding an output is one row here plus
// the line that records it (time_loop recorders: dynamics.cpp, linear_track.cpp).
#pragma once

#include <array>
#include <cstddef>
#include <vector>

namespace trackwheel {

enum class Field : int {
  t,
  x_wheel,
  y_wheel,
  ydot_wheel,
  theta,
  thetadot,
  contact_s,
  y_contact,
  normal_force,
  tangential_force,
  slip,
  slip_state,
  v_error,
  phi,
  acc_contact,
  acc_A,
  acc_B,
  acc_C,
  acc_D,
  acc_E,
  reaction,
  penetration,
  energy,
  count
};
constexpr int kFieldCount = static_cast<int>(Field::count);

struct FieldInfo {
  const char* name;  // key in the binding's output dict and Result attribute
  const char* unit;  // SI unit ("-" for dimensionless, "" for integer codes)
  const char* doc;   // one-line meaning, with the equation where there is one
  bool per_wheel;    // one value per wheel and sample (else one per sample)
  bool integer;      // stored as int32 in Python (else float64)
};

const std::array<FieldInfo, kFieldCount>& output_fields();

// Samples of every field, sample-major: a per-wheel field holds n_wheels values per sample in
// wheel order. The energy field is filled only when asked for (record_energy); it stays empty
// otherwise.
class Recording {
 public:
  void start(int n_wheels, bool energy, std::size_t expected_samples);
  void push(Field f, double value) { cols_[static_cast<int>(f)].push_back(value); }
  bool wants(Field f) const { return f != Field::energy || energy_; }
  int n_wheels() const { return n_wheels_; }
  std::size_t n_samples() const { return cols_[0].size(); }
  std::vector<double>& column(int f) { return cols_[f]; }
  // The vehicle's bodies (outside the field table: one (z, phi) pair per body and sample,
  // sample-major; none without bodies).
  void start_bodies(int n_bodies) {
    n_bodies_ = n_bodies;
    bodies_.clear();
  }
  void push_body(double z, double phi) {
    bodies_.push_back(z);
    bodies_.push_back(phi);
  }
  int n_bodies() const { return n_bodies_; }
  std::vector<double>& bodies() { return bodies_; }

 private:
  std::array<std::vector<double>, kFieldCount> cols_;
  int n_wheels_ = 1;
  int n_bodies_ = 0;
  std::vector<double> bodies_;
  bool energy_ = false;
};

// Bytes one kept sample takes for n_wheels wheels (output-size estimate before a run).
std::size_t bytes_per_sample(int n_wheels, bool energy);

// The vertical acceleration terms A-E of the contact point (docs: Model § Outputs), written once
// for the full and linear paths: with rc = rho cos(phi), A = rc theta' v phi_s, B = rc theta'
// phi_t, C = rc v^2 phi_s^2, D = rc phi_t^2, E = 2 rc phi_t v phi_s [m/s^2].
void record_acc_terms(Recording& rec, double rc, double thetadot, double v, double phi_s,
                      double phi_t);

}  // namespace trackwheel
