// The output table: one row per recorded field (name, unit, doc, per wheel, sample or
// support, dtype), and the per-sleeper envelope's table.
//
// This table is the single definition of an output: the recorder fills the fields in table
// order, the binding turns each into a numpy array keyed by its name (per-wheel fields with
// shape (n_samples, n_wheels), per-support fields (n_samples, n_supports)), exports the table as
// _core.OUTPUT_FIELDS (the per-sample and per-wheel rows) and _core.SUPPORT_FIELDS (the
// per-support rows), and Python builds Result's array fields and their documentation from it.
// Adding an output is one row here plus the line that records it (full_path.cpp,
// linear_path.cpp; the supports' rows: SupportRecorder below, which both paths call).
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <limits>
#include <vector>

#include "rail.hpp"
#include "sleepers.hpp"

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
  // per support (recorded on request, SimSettings::record_supports; a fixed rail's supports)
  rail_seat_force,
  ballast_force,
  sleeper_z,
  count
};
constexpr int kFieldCount = static_cast<int>(Field::count);

struct FieldInfo {
  const char* name;          // key in the binding's output dict and Result attribute
  const char* unit;          // SI unit ("-" for dimensionless, "" for integer codes)
  const char* doc;           // one-line meaning, with the equation where there is one
  bool per_wheel;            // one value per wheel and sample (else one per sample)
  bool integer;              // stored as int32 in Python (else float64)
  bool per_support = false;  // one value per support and sample (recorded on request)
};

const std::array<FieldInfo, kFieldCount>& output_fields();

// Samples of every field, sample-major: a per-wheel field holds n_wheels values per sample in
// wheel order. The energy field is filled only when asked for (record_energy); it stays empty
// otherwise.
class Recording {
 public:
  // n_supports: the per-support fields' values per sample (0: those fields stay empty).
  void start(int n_wheels, bool energy, std::size_t expected_samples, int n_supports = 0);
  void push(Field f, double value) { cols_[static_cast<int>(f)].push_back(value); }
  bool wants(Field f) const;
  int n_wheels() const { return n_wheels_; }
  int n_supports() const { return n_supports_; }
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
  int n_supports_ = 0;
  int n_bodies_ = 0;
  std::vector<double> bodies_;
  bool energy_ = false;
};

// Bytes one kept sample takes for n_wheels wheels and n_supports recorded supports
// (output-size estimate before a run).
std::size_t bytes_per_sample(int n_wheels, bool energy, int n_supports = 0);

// The envelope along the track of every physical sleeper (support) a run saw: one entry per
// support in the order the run met them (on a travelling window, as they joined it), with the
// extremes of its forces over the kept samples while it was in the rail. Memory grows with the
// number of supports passed, not with the samples.
enum class EnvelopeField : int {
  x,
  ballast_force_max,
  ballast_force_min,
  rail_seat_force_max,
  rail_seat_force_min,
  sleeper_z_min,
  contact_time,
  observed_time,
  count
};
constexpr int kEnvelopeFieldCount = static_cast<int>(EnvelopeField::count);

struct EnvelopeInfo {
  const char* name;
  const char* unit;
  const char* doc;
};
const std::array<EnvelopeInfo, kEnvelopeFieldCount>& envelope_fields();

class SupportEnvelope {
 public:
  // Support k (0: the first the run met) at X [m], at one kept sample standing for dt_sample
  // [s]: its ballast force Fb and rail-seat force Fp [N] (compression positive) and its
  // sleeper's displacement z [m].
  void observe(long k, double X, double Fb, double Fp, double z, double dt_sample);
  std::size_t size() const { return cols_[0].size(); }
  std::vector<double>& column(int f) { return cols_[f]; }
  const std::vector<double>& column(EnvelopeField f) const { return cols_[static_cast<int>(f)]; }

 private:
  std::array<std::vector<double>, kEnvelopeFieldCount> cols_;
};

// The supports' forces of one kept sample, written once for both paths: for support j at the
// rail's y_j = s_j . u and y_j' (u over map, as sleepers.hpp) and its sleeper's z_j, z_j',
//   rail-seat force Fp_j = -(k_p (y_j - z_j) + c_p (y_j' - z_j'))   (the pad's compression)
//   ballast force  Fb_j = -(k_b z_j + c_b z_j')                     (the bed's compression)
// (single springs: Fp_j = Fb_j = -(k_s y_j + c_s y_j'), z_j = 0: the spring carries the rail
// to the ground). The properties are read from the rail at each call (a travelling window
// streams them). Records the per-support fields if the recording wants them, and the envelope
// of support first + j at X = origin + X_j.
class SupportRecorder {
 public:
  SupportRecorder() = default;
  SupportRecorder(const RailModel& rail, std::vector<int> map);
  int size() const { return static_cast<int>(pt_.size()); }
  void record(const RailModel& rail, const Eigen::VectorXd& u, const Eigen::VectorXd& udot,
              const Eigen::VectorXd& z, const Eigen::VectorXd& zdot, const Sleepers& sleepers,
              long first, double origin, double dt_sample, Recording& rec,
              SupportEnvelope& env) const;

 private:
  std::vector<MeshPoint> pt_;
  std::vector<int> map_;
  double y(int j, const Eigen::VectorXd& u) const;
};

// The vertical acceleration terms A-E of the contact point (docs: Model § Outputs), written once
// for the full and linear paths: with rc = rho cos(phi), A = rc theta' v phi_s, B = rc theta'
// phi_t, C = rc v^2 phi_s^2, D = rc phi_t^2, E = 2 rc phi_t v phi_s [m/s^2].
void record_acc_terms(Recording& rec, double rc, double thetadot, double v, double phi_s,
                      double phi_t);

}  // namespace trackwheel
