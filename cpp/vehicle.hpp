// The planar vehicle above the wheels (docs: Model § The vehicle): rigid bodies (bogie frames,
// car body) with a vertical displacement z and a small pitch phi each, joined to the wheel
// centres and to each other by linear spring-damper suspensions.
//
// Vehicle coordinates u = [Y_A,0 .. Y_A,n_w-1, z_0, phi_0, z_1, phi_1, ...]: the wheel centre
// heights (owned by the wheels' borders) and the bodies' (z, phi). A point at arm a (along +X,
// the direction of travel) on body b is at height z_b + a phi_b (phi small, positive nose up).
// Suspension s joins a lower point (a wheel centre, or a point of a body) to a point of an
// upper body; its extension is d_s = g_s . u with constant g_s, and it pulls the two points
// together with f_s = k_s d_s + c_s d_s' (tension positive). z is measured from the height at
// which every spring is unstretched, so the weights set the static deflections. Everything is
// linear: generalised forces f_u = -K_v u - C_v u' - G with constant K_v = sum k g g^T,
// C_v = sum c g g^T and the bodies' weights G, whatever the track does.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "state.hpp"

namespace trackwheel {

// One rigid body of the vehicle (a bogie frame or the car body, on one rail: half the body).
struct BodyParams {
  double mass = 0.0;     // [kg]
  double inertia = 0.0;  // pitch moment of inertia about the centre of mass [kg m^2]
  double gravity = 0.0;  // g on the body [m/s^2]
  double load = 0.0;     // constant downward force on its centre (e.g. a car body's share) [N]
};

// One suspension: a linear spring and viscous damper in parallel, vertical.
struct SuspensionParams {
  double stiffness = 0.0;  // k [N/m]
  double damping = 0.0;    // c [N s/m]
  int lower_wheel = -1;    // the lower end is this wheel's centre, or -1 ...
  int lower_body = -1;     // ... a point of this body
  double lower_arm = 0.0;  // arm of that point from the lower body's centre [m]
  int upper_body = 0;      // the upper end is a point of this body
  double upper_arm = 0.0;  // arm of that point from the upper body's centre [m]
};

struct VehicleParams {
  std::vector<BodyParams> bodies;  // none: the wheels carry constant loads (Part I)
  std::vector<SuspensionParams> suspensions;
  int n_bodies() const { return static_cast<int>(bodies.size()); }
  bool empty() const { return bodies.empty(); }
};

// Throws std::invalid_argument naming the first body or suspension out of range.
void check_vehicle(const VehicleParams& vehicle, int n_wheels);

// Total weight and load of the bodies, sum (m_b g + load_b) [N].
double vehicle_weight(const VehicleParams& vehicle);

// The vehicle's constant matrices over u (n_u = n_wheels + 2 n_bodies).
struct VehicleMatrices {
  Eigen::MatrixXd K, C;  // suspension stiffness and damping, sum k g g^T, sum c g g^T
  Eigen::VectorXd mass;  // diagonal of the mass matrix over u (the wheels' entries zero:
                         // their inertia is the wheels' own)
  Eigen::VectorXd G;     // weights of the bodies over u [N] (z rows: m g; others 0)
  int n_wheels = 0;
};
VehicleMatrices vehicle_matrices(const VehicleParams& vehicle, int n_wheels);

// The suspensions' and the bodies' weights as generalised forces over u:
// f = -K u - C u' - G [N, N m].
Eigen::VectorXd vehicle_forces(const VehicleMatrices& vm, const Eigen::VectorXd& u,
                               const Eigen::VectorXd& udot);
// Energy of the bodies: kinetic (over the body entries of u), suspension springs and the
// bodies' gravity [J].
double vehicle_energy(const VehicleMatrices& vm, const Eigen::VectorXd& u,
                      const Eigen::VectorXd& udot);

// u and u' of a state: the wheels' heights Y_A and rates, then the bodies' [z, phi] and rates.
void vehicle_coordinates(const SimState& st, Eigen::VectorXd& u, Eigen::VectorXd& udot);

// The vehicle's rows in a path's border system (System, LinearSystem), written once for both
// paths: the suspensions' forces f_u on the wheels' force rows (vertical) and on the bodies'
// rows M_b [z_b'', phi_b''] = f_u, and their Jacobian with respect to the accelerations,
// cq K_v + cv C_v (u = u_pred + cq u'', u' = u'_pred + cv u''). The layout places wheel
// heights and bodies in the border (state.hpp).
class VehicleRows {
 public:
  VehicleRows() = default;
  VehicleRows(const VehicleParams& vehicle, const BorderLayout& layout);
  bool empty() const { return layout_.n_bodies == 0; }
  const VehicleMatrices& matrices() const { return vm_; }
  // fb(vehicle(i)) += f_u(i), f_u = -K_v u - C_v u' - G_v at the state's u, u'.
  void add_forces(const SimState& st, Eigen::VectorXd& fb) const;
  // The bodies' rows of the negated residual, r = fb - M_b x (fb holding f_u), at the iterate x.
  void body_residual(const Eigen::VectorXd& x, const Eigen::VectorXd& fb, Eigen::VectorXd& r) const;
  // D += M_b on the bodies' diagonal; unless inertia_only also cq K_v + cv C_v over u.
  void add_block(Eigen::MatrixXd& D, bool inertia_only, double cq, double cv) const;
  // vehicle_energy at the state [J].
  double energy(const SimState& st) const;

 private:
  VehicleMatrices vm_;
  BorderLayout layout_;
  mutable Eigen::VectorXd u_, udot_, fu_;  // buffers
};

// The bodies' static coordinates [z, phi per body] above wheel centres at heights Y: the
// bodies' rows of K_v u = -G_v solved with Y held (minimum-norm, so a body free to pitch, e.g.
// on one wheel, stays level).
Eigen::VectorXd static_bodies(const VehicleMatrices& vm, const Eigen::VectorXd& Y);
// The vehicle's static force on each wheel centre [N] (negative: pressing it down). For a
// statically determinate vehicle it does not depend on Y.
Eigen::VectorXd static_wheel_forces(const VehicleMatrices& vm, const Eigen::VectorXd& Y);

}  // namespace trackwheel
