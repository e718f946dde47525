// The immutable, compiled description of a towing system (docs/theory.md §1-4).
//
// A Model is built once by `compile()` from a parsed scenario and never
// changes during a run. Dynamics are free functions of (model, state, t,
// workspace); they never see YAML. Notation: docs/theory.md.
//
// Frames: global frame R_g with z up, free surface at z = 0. Body axes
// (x forward, y, z) attached to the towed body at its origin O_t.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "towsim/model/depth_control.hpp"
#include "towsim/model/fluid.hpp"
#include "towsim/model/loading_table.hpp"
#include "towsim/model/seabed.hpp"
#include "towsim/model/types.hpp"
#include "towsim/model/winch.hpp"
#include "towsim/tow/tow.hpp"

namespace towsim {

/// Tangential (axial) friction law on a cable element (docs/theory.md §3).
enum class TangentialLaw {
  Pode,  // F_t = -1/2 rho Cd f D L |u|^2 sgn_s(u.e) e   (paper 2.43)
  Skin,  // F_t = -1/2 rho pi D L Ct |u.e| (u.e) e       (lumped-mass codes)
};

/// How the fluid's added mass acts on a cable element (docs/theory.md §3).
enum class AddedMassModel {
  IdealFluid,  // -dP/dt with P = ma (I - ee^T) u, plus the Munk moment (paper 2.42)
  Morison,     // acceleration term only: -ma (I - ee^T) du/dt, -Ia alpha
};

/// One straight cable element i (1 = top): rigid and inextensible (the
/// paper's), or elastic when axial_stiffness > 0 (docs/theory.md §5.4).
struct Element {
  int section = 0;               // index of the cable section it belongs to (0 = top) [-]
  double length;                 // L_i, joint to joint [m] (the paper's 2l)
  double mass;                   // m_i in air [kg] (the paper's 3m)
  double diameter;               // D_i, hydrodynamic and displacement diameter [m]
  double inertia;                // I_i = m_i L_i^2 / 12 about G_i, perpendicular to e_i [kg m^2]
  double added_mass;             // ma_i = Ca rho (pi D^2/4) L_i, normal to e_i [kg]
  double added_inertia;          // Ia_i = ma_i L_i^2 / 12 [kg m^2]
  double weight;                 // apparent weight (m_i - rho A_i L_i) g, along -z [N]
  double drag_factor;            // 1/2 rho Cd D L, normal drag: F = -k |u_n| u_n [kg/m]
  double friction_factor;        // Pode: 1/2 rho Cd f D L; Skin: 1/2 rho pi D L Ct [kg/m]
  double axial_stiffness = 0;    // EA [N]; 0 = inextensible (rigid element, the paper's model)
  double axial_damping = 0;      // c_a [N s]: adds c_a * strain rate to the tension while taut
  double bending_stiffness = 0;  // EI [N m^2]; 0 = no bending stiffness at its joints (the paper's model)
};

/// A point load lumped at a cable joint: clump weight, float, sensor.
/// Its mass moves with the joint; its loads act at the joint.
struct Attachment {
  int joint = 0;          // joint index k (0 = tow point, n = cable end) [-]
  double at = 0;          // arc length asked for, from the tow point [m]
  double mass = 0;        // in air [kg]
  double volume = 0;      // displaced volume [m^3]
  double drag_area = 0;   // Cd A: drag -1/2 rho CdA |u| u [m^2]
  double added_mass = 0;  // isotropic added mass [kg]
};

/// A run of equal elements between two joints of the chain (a section
/// boundary is a joint, or an in-line body).
struct Section {
  std::string name;          // for messages and outputs
  int first_element = 0;     // index of its first element in Cable::elements [-]
  int elements = 0;          // number of elements [-]
  double length = 0;         // [m]
  double breaking_load = 0;  // [N]; 0 = not given
  // Faired cable: loading functions of the flow angle; empty = the default laws.
  LoadingTable normal_loading{};      // f_n(phi), replaces the cross-flow normal drag [-]
  LoadingTable tangential_loading{};  // f_t(phi), replaces the cable's tangential law [-]
};

/// Cable: the chain of elements and its fluid-load options.
struct Cable {
  std::vector<Element> elements;        // ordered from the tow point (1) to the end (n)
  std::vector<Section> sections;        // top to bottom; one for a uniform cable
  std::vector<Attachment> attachments;  // sorted by joint
  TangentialLaw tangential_law = TangentialLaw::Pode;
  AddedMassModel added_mass_model = AddedMassModel::IdealFluid;
  double sign_smoothing_speed = 1e-3;  // v_s in sgn_s(x) = x / sqrt(x^2 + v_s^2) [m/s]

  int n() const { return static_cast<int>(elements.size()); }
  double total_length() const;
};

/// A sphere load model on the body: drag, added mass and buoyancy at its centre.
struct SphereLoad {
  Vec3 center;        // centre, body axes [m]
  double radius;      // [m]
  double drag;        // Cd on the frontal area pi r^2 [-]
  double added_mass;  // Ca, added mass = Ca rho (4/3 pi r^3) [-]
};

/// A slender cylinder load model on the body, loaded like a cable element.
struct CylinderLoad {
  Vec3 center;         // centre, body axes [m]
  Vec3 axis;           // unit axis, body axes [-]
  double length;       // [m]
  double diameter;     // [m]
  double normal_drag;  // Cd on D*L for the normal flow [-]
  double axial_drag;   // Ct skin friction on pi D L for the axial flow [-]
  double added_mass;   // Ca, normal added mass Ca rho pi D^2/4 L [-]
};

/// A lifting surface (fin, depressor wing) on the body.
/// Lift and drag from the local angle of attack in the surface's plane.
struct LiftingSurface {
  Vec3 center;          // centre of pressure, body axes [m]
  Vec3 chord;           // unit chord direction (leading edge forward), body axes [-]
  Vec3 normal;          // unit normal: positive lift side at positive incidence, body axes [-]
  double area;          // planform area [m^2]
  double lift_slope;    // dCL/dalpha below stall [1/rad]
  double stall_angle;   // |alpha| beyond which lift falls off [rad]
  double drag0;         // zero-lift drag coefficient CD0 [-]
  double induced_drag;  // k in CD = CD0 + k CL^2 [-]
  /// Deflection delta(t) [rad] about the span axis (chord x normal), as a table;
  /// one row = constant, empty = 0. Linear interpolation, held at the ends.
  std::vector<double> deflection_time;   // [s]
  std::vector<double> deflection_angle;  // [rad]
  /// A depth-keeping controller sets the deflection instead of the table.
  std::optional<DepthControl> depth_control{};
};

/// A thruster on a body: a force along a fixed body-axes direction, applied
/// at a body-axes point, its magnitude a table over time (docs/contract.md; the
/// paper's "forces from propellers").
struct Thruster {
  Vec3 point = Vec3::Zero();       // where it acts, body axes [m]
  Vec3 direction = Vec3::UnitX();  // unit direction of the thrust, body axes [-]
  std::vector<double> time;        // [s]; one row = constant
  std::vector<double> force;       // thrust at that time [N]; linear interpolation, held at the ends
};

/// A rigid body of the chain (docs/theory.md §4, paper section 4): the towed body at
/// the end, or an in-line body (depressor) between two cable sections.
struct Body {
  std::string name = "body";              // output column prefix ("body" = today's columns)
  int joint = -1;                         // joint k of the chain where its link point Q hangs
                                          // (the bottom of element k); -1 = the cable's end, n [-]
  bool inline_body = false;               // true: the next section hangs from lower_link_point
  Vec3 lower_link_point = Vec3::Zero();   // r_Q2, ball joint with the cable below, body axes [m]
  double mass = 0;                        // m_B [kg]
  Mat3 inertia_cg = Mat3::Zero();         // inertia tensor about the CG, body axes [kg m^2]
  Vec3 cg = Vec3::Zero();                 // r_G, body axes [m]
  Vec3 link_point = Vec3::Zero();         // r_Q, the ball joint with the cable, body axes [m]
  double volume = 0.0;                    // displaced volume not counted by the load models [m^3]
  Vec3 cb = Vec3::Zero();                 // r_B, centre of buoyancy of `volume`, body axes [m]
  Mat6 added_mass = Mat6::Zero();         // user 6x6 added mass about O_t, body axes [SI]
  Mat6 linear_damping = Mat6::Zero();     // D_l: tau = -D_l nu_r, body axes [SI]
  Mat6 quadratic_damping = Mat6::Zero();  // D_q: tau = -D_q (|nu_r| o nu_r) [SI]
  std::vector<SphereLoad> spheres;
  std::vector<CylinderLoad> cylinders;
  std::vector<LiftingSurface> surfaces;
  std::vector<Thruster> thrusters;
  Quat initial_attitude = Quat::Identity();  // body axes -> R_g at t = 0

  // Derived by finalize_body() (compile() calls it); zero until then:
  Mat6 rigid_mass = Mat6::Zero();       // M_RB about O_t, body axes [SI]
  Mat6 fluid_mass = Mat6::Zero();       // M_A: added_mass + sphere and cylinder added masses, about O_t, body axes
  double displaced_volume = 0;          // total: volume + spheres + cylinders [m^3]
  Vec3 buoyancy_center = Vec3::Zero();  // centre of the total displaced volume, body axes [m]
  Mat6 total_mass = Mat6::Zero();       // rigid_mass + fluid_mass, body axes [SI]
  bool damped = false;                  // linear_damping or quadratic_damping not zero (Eigen's isZero)
};

/// How the run starts.
struct Initial {
  enum class Kind { Hanging, Steady, Direction } kind = Kind::Hanging;
  Vec3 direction = -Vec3::UnitZ();  // Direction: unit vector from the tow point [-]
};

enum class Integrator { RK4, DOPRI5, CashKarp54, Rosenbrock };
enum class Formulation { Default, Paper };

/// Name of an integrator as in the scenario key `simulation.integrator`.
inline const char* integrator_key(Integrator i) {
  switch (i) {
    case Integrator::RK4:
      return "rk4";
    case Integrator::DOPRI5:
      return "dopri5";
    case Integrator::CashKarp54:
      return "cash_karp54";
    case Integrator::Rosenbrock:
      return "rosenbrock";
  }
  return "?";
}

/// The integrator a scenario gets when it names none (docs/scenario.md
/// "simulation"): rosenbrock with the default formulation; rk4 with the
/// paper's, whose angles have no O(n) stage solve for rosenbrock.
inline Integrator default_integrator(Formulation f) {
  return f == Formulation::Paper ? Integrator::RK4 : Integrator::Rosenbrock;
}

/// The tolerance a scenario gets when it names none [-]: 1e-4 for
/// rosenbrock, the default accuracy (docs/scenario.md "Accuracy: the time
/// step's share"): every line's tow force within 0.1 % of its peak on the
/// shipped examples and benchmark scenarios (measured 4.8e-5 to 7.8e-4);
/// 1e-6 for dopri5 and cash_karp54 (whose error control sees only the
/// state); rk4 does not use it.
inline double default_tolerance(Integrator i) { return i == Integrator::Rosenbrock ? 1e-4 : 1e-6; }

/// Time integration settings (docs/theory.md §6). A Model built in code
/// keeps these member defaults (rk4); a scenario file's absent keys take
/// default_integrator() and default_tolerance() (src/scenario/parse.cpp).
struct Simulation {
  double duration = 100;         // [s]
  double time_step = 0.01;       // fixed step, or first step if adaptive [s]
  double output_interval = 0.1;  // [s]
  Integrator integrator = Integrator::RK4;
  double tolerance = 1e-6;  // adaptive: relative and absolute error target (rosenbrock: also on forces) [-]
  double max_step = 1.0;    // adaptive: largest step [s]
  Formulation formulation = Formulation::Default;
  bool write_nodes = true;       // write nodes.csv
  double statistics_start = -1;  // sea-state statistics from this time; < 0: half the duration [s]
  int threads = 0;               // >= 1; 0: auto (evaluation_threads, towsim/integrators/system.hpp) [-]
  // The stage solve's W takes the pull of the cable below a body (in-line,
  // or a tree's lines from its points) into its rotational stiffness
  // (body_line_stiffness); the statics' relaxation and Newton-Krylov, which
  // use the stage solve for their path, leave it out (docs/theory.md §6.3).
  // No scenario key.
  bool line_pull_stiffness = true;
};

/// The whole compiled system: a chain of linked parts from the tow point
/// down, cable elements (grouped in sections) and rigid bodies. Body b
/// hangs from joint bodies[b].joint; bodies are sorted by joint, at most one
/// per joint, the end body (at the cable's end, nothing below) last.
struct Model {
  std::string name;  // scenario name (file stem or example name)
  Fluid fluid;
  std::optional<Seabed> seabed;  // environment.seabed; none = no bottom (towsim/model/seabed.hpp)
  Cable cable;
  std::vector<Body> bodies;
  Tow tow;
  Winch winch;  // pay-out and haul-in at the tow point (Mode::None: fixed length)
  Initial initial;
  Simulation sim;
};

/// Fill Element's derived fields from its primary data and the fluid.
/// Cd, f (Pode) or Ct (Skin), and Ca are the cable's coefficients.
Element make_element(double length, double mass_per_length, double diameter, double cd, double tangential_coef,
                     TangentialLaw law, double ca, const Fluid& fluid);

/// Element `el` with its length changed to `length` and every per-length
/// property scaled with it (the winch's top element: the material in it
/// grows or shrinks; mass, weight, drag and added mass ~ length, inertias ~ length^3).
Element scaled_element(const Element& el, double length);

/// Fill Body's derived fields (rigid_mass, fluid_mass, displaced volume).
void finalize_body(Body& body, const Fluid& fluid);

/// Number of the body's surfaces with a depth controller (its ControlState entries).
int control_count(const Body& body);

/// The end body (the one with nothing below it), or nullptr.
const Body* end_body(const Model& model);

/// The joint a body hangs from: body.joint, or n for the end body (-1).
int body_joint(const Model& model, const Body& body);

}  // namespace towsim
