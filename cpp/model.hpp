// The immutable model of one run: the rail with its supports, the wheels and the contact law,
// passed to every algorithm as one object (docs: Model § Scene, § Rail, § Wheel, § Contact, §
// Rolling and slip).
//
// Defaults live in Python (trackwheel.Scene): these structs carry no physics defaults, so a
// field the caller forgot is a zero that validation rejects, not a silently different wheel.
#pragma once

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "contact.hpp"
#include "rail.hpp"
#include "state.hpp"
#include "vehicle.hpp"

namespace trackwheel {

// One wheel: a rigid disc (X_A, Y_A, theta) carried at constant forward speed (docs: Model §
// Wheel).
struct WheelParams {
  double mass = 0.0;      // M [kg]
  double inertia = 0.0;   // polar moment of inertia J [kg m^2]
  double radius = 0.0;    // undeformed radius rho0 [m]
  double load = 0.0;      // vertical load F on the centre (car body share) [N]
  double torque = 0.0;    // external torque about the centre, positive in rolling direction [N m]
  double gravity = 0.0;   // g acting on the wheel mass [m/s^2]
  double x_offset = 0.0;  // X_A - (X_0 + v t): the wheel's place along the vehicle [m]
  // Out-of-roundness: the radius change Delta rho(psi) [m] at the wheel angle psi [rad], a
  // piecewise cubic over one revolution [0, 2 pi] (empty: a round wheel). The wheel touches
  // the rail at psi = theta, the rolling angle (the obliquity's shift of the contact point on
  // the wheel, ~1e-3 rad, is neglected), so a defect returns with the rolled, not the
  // travelled, distance (docs: Model § Irregularities).
  Profile out_of_round;
  // T_b of a friction brake on the rotation [N m]: -T_b sign(theta') while the wheel turns; the
  // wheel locks (theta' = 0) while the torque needed to hold it stays <= T_b (docs: Model §
  // Rolling and slip). 0: no brake.
  double brake_torque = 0.0;
  double total_load() const { return load + mass * gravity; }  // P = F + M g [N]
  ProfileValue radius_change(double psi) const {               // Delta rho, d/dpsi, d2/dpsi2 at psi
    if (out_of_round.empty()) return ProfileValue();
    const double two_pi = 6.283185307179586;
    return out_of_round(psi - two_pi * std::floor(psi / two_pi));
  }
};

struct Model {
  const RailModel& rail;            // mesh, section, supports (immutable, shared)
  std::vector<WheelParams> wheels;  // at least one
  ContactParams contact;            // law, stiffness, damping, friction (radius: per wheel)
  VehicleParams vehicle;            // bodies and suspensions above the wheels (none: Part I)

  int n_wheels() const { return static_cast<int>(wheels.size()); }
  int n_bodies() const { return vehicle.n_bodies(); }
  // The contact law of wheel w (its own undeformed radius).
  ContactParams contact_of(int w) const {
    ContactParams c = contact;
    c.radius = wheels[w].radius;
    return c;
  }
};

// Throws std::invalid_argument naming the first wheel or contact field out of range.
void check_model(const Model& model);

// Wheel w's track coordinate X_A at t [m]: X_0 + x_offset + v t (the prescribed forward motion).
inline double wheel_x(const Model& model, const SimSettings& set, int w, double t) {
  return set.x_start + model.wheels[w].x_offset + set.speed * t;
}

// Each wheel's static load [N]: F + M g, plus the vehicle's static force on it (the bodies'
// weight distribution, vehicle.hpp): the scale of its contact forces.
std::vector<double> static_wheel_loads(const Model& model);

// Kinetic energy of the wheels' and the vehicle's bodies' vertical motion,
// sum (1/2) M Y_A'^2 + sum (1/2) m_b z_b'^2 [J] (with the rail's and the sleepers', the runaway
// watchdog's measure).
double vertical_kinetic_energy(const Model& model, const SimState& st);

}  // namespace trackwheel
