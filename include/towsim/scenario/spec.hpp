// The scenario as read from YAML, before validation: plain structs whose
// every value remembers where it was written (file, line, column, key path).
// `parse_scenario()` fills them; `compile()` checks them and builds a Model.
#pragma once

#include <string>
#include <vector>

#include "towsim/model/model.hpp"
#include "towsim/scenario/diagnostics.hpp"

namespace towsim::scenario {

/// Where a value came from: its source location and dotted key path.
struct Where {
  SourceLoc loc;
  std::string path;
};

/// A scenario value with its origin. `given` is false when the key is absent
/// (then `value` is the default) or could not be read (an error was reported).
template <class T>
struct Field {
  T value{};
  Where where;
  bool given = false;

  Field() = default;
  Field(T v) : value(std::move(v)) {}  // NOLINT: implicit, for defaults
};

/// One row of a table: values (e.g. t, Fx, Fy, Fz) and where the row is.
struct RowSpec {
  std::vector<double> values;
  Where where;
};

/// environment.seabed: a flat or tabulated bottom and its contact law.
struct SeabedSpec {
  bool present = false;
  Where where;
  Where depth_where;                       // the `depth` key's value
  std::vector<RowSpec> depth;              // rows {x [m], depth [m]}; a number = one row at x = 0
  Field<double> stiffness{1e5};            // [N/m per m of cable in contact]
  Field<double> damping{1e3};              // [N s/m per m]
  Field<double> friction{0.5};             // Coulomb coefficient [-]
  Field<std::string> contact{"elements"};  // where the cable's contact acts: joints | elements
};

/// environment: water, gravity, current, seabed.
struct EnvironmentSpec {
  Field<double> water_density{1025.0};  // [kg/m^3], 0 = no fluid
  Field<double> gravity{9.81};          // [m/s^2]
  bool current_given = false;
  Where current_where;
  std::vector<RowSpec> current;  // rows {depth [m], ux, uy, uz [m/s]}; uniform = one row at depth 0
  SeabedSpec seabed;
};

/// cable.sections item: a run of equal elements. Unset properties take the
/// cable-level value (or its default).
struct SectionSpec {
  Where where;
  Field<std::string> name;                // for messages [-]
  Field<double> length;                   // [m]
  Field<long long> elements;              // [-]
  Field<double> mass_per_length;          // in air [kg/m]
  Field<double> diameter;                 // [m]
  Field<double> normal_drag;              // Cd [-]
  Field<std::string> normal_law;          // cross_flow | table (faired cable)
  std::vector<RowSpec> normal_table;      // law table: rows {phi [deg], f_n [-]}
  Field<std::string> tangential_law;      // pode | skin | table
  Field<double> tangential_coef;          // f or ct [-]
  std::vector<RowSpec> tangential_table;  // law table: rows {phi [deg], f_t [-]}
  Field<double> added_mass;               // Ca [-]
  Field<double> axial_stiffness;          // EA [N]; absent = inextensible
  Field<double> axial_damping;            // c_a [N s]: tension c_a * strain rate while taut
  Field<double> bending_stiffness;        // EI [N m^2]; absent or 0 = none
  Field<double> breaking_load;            // [N], for utilisation
};

struct BodySpec;

/// cable.attachments item: a point load lumped at the nearest joint.
struct AttachmentSpec {
  Where where;
  Field<double> at;               // arc length from the tow point [m]
  Field<double> mass{0.0};        // [kg]
  Field<double> volume{0.0};      // [m^3]
  Field<double> drag_area{0.0};   // Cd A [m^2]
  Field<double> added_mass{0.0};  // [kg]
};

/// cable: a chain of equal elements.
struct CableSpec {
  Where where;
  Field<double> length;                                // total [m]
  Field<long long> elements;                           // number of elements [-]
  Field<double> mass_per_length;                       // in air [kg/m]
  Field<double> diameter;                              // [m]
  Field<double> normal_drag{1.8};                      // Cd [-]
  Field<std::string> normal_law{"cross_flow"};         // cross_flow | table (faired cable)
  std::vector<RowSpec> normal_table;                   // law table: rows {phi [deg], f_n [-]}
  Field<std::string> tangential_law{"pode"};           // pode | skin | table
  Field<double> tangential_coef{0.0};                  // f (pode, default 0) or ct (skin, default 0.008) [-]
  std::vector<RowSpec> tangential_table;               // law table: rows {phi [deg], f_t [-]}
  Field<double> added_mass{1.0};                       // Ca [-]
  Field<std::string> added_mass_model{"ideal_fluid"};  // ideal_fluid | morison
  Field<double> sign_smoothing_speed{1e-3};            // [m/s]
  Field<double> breaking_load;                         // [N] (single-section form)
  Field<double> axial_stiffness;                       // EA [N]; absent = inextensible (sections inherit it)
  Field<double> axial_damping{0.0};                    // c_a [N s] (sections inherit it)
  Field<double> bending_stiffness{0.0};                // EI [N m^2]; 0 = none (sections inherit it)
  // cable.sections: items in order, each a section or an in-line body
  // (index into `inline_bodies`); empty = the single-section form above.
  Where sections_where;
  std::vector<SectionSpec> sections;
  std::vector<int> item_body;     // per sections item: -1 (a section) or body index
  std::vector<Where> item_where;  // per sections item
  std::vector<BodySpec> inline_bodies;
  std::vector<AttachmentSpec> attachments;
};

/// body.spheres item.
struct SphereSpec {
  Where where;
  Field<Vec3> center;             // body axes [m]
  Field<double> radius;           // [m]
  Field<double> drag{0.5};        // Cd [-]
  Field<double> added_mass{0.5};  // Ca [-]
};

/// body.cylinders item.
struct CylinderSpec {
  Where where;
  Field<Vec3> center;              // body axes [m]
  Field<Vec3> axis;                // body axes, normalised by compile [-]
  Field<double> length;            // [m]
  Field<double> diameter;          // [m]
  Field<double> normal_drag{1.2};  // Cd [-]
  Field<double> axial_drag{0.0};   // Ct [-]
  Field<double> added_mass{1.0};   // Ca [-]
};

/// body.surfaces item depth_control: PID on the body's depth setting the deflection.
struct DepthControlSpec {
  bool present = false;
  Where where;
  Field<double> target_depth;                 // of the body origin, positive down [m] (required)
  Field<double> kp{0.0};                      // [deg/m]
  Field<double> ki{0.0};                      // [deg/(m s)]
  Field<double> kd{0.0};                      // [deg s/m]
  Field<double> max_deflection_deg;           // [deg] (required)
  Field<double> max_rate_deg_s;               // [deg/s] (required)
  Field<double> servo_time_constant{0.1};     // [s]
  Field<double> tracking_time;                // anti-windup [s]; absent = |kp/ki|, or 1 s
  Field<double> initial_deflection_deg{0.0};  // [deg]
  Field<double> settling_band;                // [m]; absent = 1 % of the first depth error
};

/// body.surfaces item.
struct SurfaceSpec {
  Where where;
  Field<Vec3> center;                           // centre of pressure, body axes [m]
  Field<Vec3> chord;                            // body axes [-]
  Field<Vec3> normal;                           // body axes [-]
  Field<double> area;                           // [m^2]
  Field<double> lift_slope{6.283185307179586};  // dCL/dalpha [1/rad]
  Field<double> stall_angle_deg{15.0};          // [deg]
  Field<double> drag0{0.01};                    // CD0 [-]
  Field<double> induced_drag{0.05};             // k [-]
  Where deflection_where;
  std::vector<RowSpec> deflection;  // rows {t [s], delta [deg]}; empty = 0
  DepthControlSpec depth_control;   // absent: the deflection table sets the deflection
};

/// body.thrusters item.
struct ThrusterSpec {
  Where where;
  Field<Vec3> point{Vec3::Zero()};       // body axes [m]
  Field<Vec3> direction{Vec3::UnitX()};  // body axes, normalised by compile [-]
  Where force_where;
  std::vector<RowSpec> force;  // rows {t [s], thrust [N]}; a number = constant
};

/// body: the towed rigid body (optional).
struct BodySpec {
  bool present = false;
  Where where;
  Field<std::string> name;                         // output column prefix (in-line bodies) [-]
  Field<Vec3> lower_link_point;                    // in-line body: where the next section hangs, body axes [m]
  Field<double> mass;                              // [kg]
  Field<Mat3> inertia;                             // about the CG, body axes [kg m^2]
  Field<Vec3> center_of_gravity{Vec3::Zero()};     // [m]
  Field<Vec3> link_point;                          // [m]
  Field<double> volume{0.0};                       // [m^3]
  Field<Vec3> center_of_buoyancy;                  // [m], default = center_of_gravity
  Field<Mat6> added_mass{Mat6::Zero()};            // about O_t, body axes [SI]
  Field<Mat6> linear_damping{Mat6::Zero()};        // [SI]
  Field<Mat6> quadratic_damping{Mat6::Zero()};     // [SI]
  Field<Vec3> initial_attitude_deg{Vec3::Zero()};  // roll, pitch, yaw [deg]
  std::vector<SphereSpec> spheres;
  std::vector<CylinderSpec> cylinders;
  std::vector<SurfaceSpec> surfaces;
  std::vector<ThrusterSpec> thrusters;
};

/// tow.motion item: ramp, heave, turn, speed or track.
struct PieceSpec {
  Where where;
  Field<std::string> type;          // ramp | heave | turn | speed | track
  Field<Vec3> direction;            // ramp [-]
  Field<double> speed;              // ramp, speed [m/s] (`speed_kn` in knots)
  Field<double> ramp_time;          // ramp, speed [s]
  Field<double> amplitude;          // heave [m]
  Field<double> period;             // heave [s]
  Field<double> start_time{0.0};    // heave, turn, speed [s]
  Field<double> radius;             // turn [m]
  Field<std::string> side{"port"};  // turn: port | starboard
  Field<double> angle_deg;          // turn: change of heading at which it ends [deg]; absent = never ends
  Where track_where;                // track: the `file` or `points` key
  std::vector<RowSpec> track;       // track rows {t [s], x, y, z [m]}
  Field<double> speed_scale{1.0};   // track: times are divided by it [-]

  /// A piece that steers the course (turn, speed).
  bool manoeuvre() const { return type.value == "turn" || type.value == "speed"; }
};

/// tow: the tow point's imposed motion or force.
struct TowSpec {
  Where where;
  Field<std::string> mode{"motion"};  // motion | force
  Field<Vec3> start{Vec3::Zero()};    // [m]
  std::vector<PieceSpec> motion;
  bool force_given = false;
  Where force_where;
  std::vector<RowSpec> force;  // rows {t [s], Fx, Fy, Fz [N]}
};

/// initial: hanging | steady | {direction: [x, y, z]}.
struct InitialSpec {
  Field<std::string> kind{"hanging"};
  Field<Vec3> direction;
};

/// The integrator named by a `simulation.integrator` value (one of the
/// parser's choices; anything else: rk4).
inline Integrator integrator_of(const std::string& key) {
  return key == "dopri5"        ? Integrator::DOPRI5
         : key == "cash_karp54" ? Integrator::CashKarp54
         : key == "rosenbrock"  ? Integrator::Rosenbrock
                                : Integrator::RK4;
}

/// simulation: time integration and output settings.
struct SimulationSpec {
  Where where;
  Field<double> duration;         // [s] (required)
  Field<double> time_step{0.01};  // [s]
  Field<std::string> integrator;  // rk4 | dopri5 | cash_karp54 | rosenbrock; absent: default_integrator(formulation)
  Field<double> tolerance;        // [-]; absent: default_tolerance(integrator)
  Field<double> max_step{1.0};    // [s]
  Field<std::string> formulation{"default"};  // default | paper
  Field<double> output_interval{0.1};         // [s]
  Field<bool> write_nodes{true};
  Field<std::string> threads{"auto"};  // an integer >= 1, or auto [-]
};

/// waves: a regular wave or a spectrum, optionally in finite depth.
struct WavesSpec {
  bool present = false;
  Where where;
  bool regular = false;                   // `regular:` given (else `spectrum:`)
  Where kind_where;                       // where `regular:` or `spectrum:` is
  Field<double> height;                   // regular: H [m]
  Field<double> period;                   // regular: T [s]
  Field<double> heading_deg{180.0};       // direction of travel relative to the course [deg]
  Field<std::string> type;                // spectrum: jonswap | pierson_moskowitz
  Field<double> hs;                       // spectrum: significant wave height [m]
  Field<double> tp;                       // spectrum: peak period [s]
  Field<double> gamma{3.3};               // spectrum (jonswap): peak enhancement [-]
  Field<long long> components{200};       // spectrum: number of harmonics [-]
  Field<long long> seed{1};               // spectrum: phase seed [-]
  Field<double> spreading;                // spectrum: cos-2s spreading exponent s [-]; absent = long-crested
  Field<double> water_depth;              // [m]; absent = deep water
  Field<double> statistics_start;         // [s]; absent = half the duration
  Field<double> ramp_time{0.0};           // build-up of the waves and ship motion [s]
  Field<std::string> stretching{"none"};  // kinematics near the surface: none | wheeler
};

/// One RAO row: period [s], heading [deg], dof (0..5), amplitude, phase [deg].
struct RaoRowSpec {
  double period, heading, amplitude, phase;
  int dof;
  Where where;
};

/// A named point: a tow point of the vessel, a hull point of a body.
struct NamedPointSpec {
  Field<std::string> name;  // its key [-]
  Field<Vec3> point;        // vessel or body axes [m]
};

/// vessel: RAOs (file or inline rows) or a measured motion record, and the sheave.
struct VesselSpec {
  bool present = false;
  Where where;
  Field<Vec3> tow_point{Vec3::Zero()};          // sheave in vessel axes from the RAO origin [m]
  Field<std::string> rotations{"small_angle"};  // small_angle | exact
  bool raos_given = false;
  Where raos_where;
  std::vector<RaoRowSpec> raos;
  bool motions_given = false;
  Where motions_where;
  std::vector<RowSpec> motions;  // rows {t [s], surge, sway, heave [m], roll, pitch, yaw [deg]}
  // vessel.tow_points (networks): named sheaves [m, vessel axes from the RAO
  // origin; without a vessel motion, from the tow law's point].
  bool tow_points_given = false;
  Where tow_points_where;
  std::vector<NamedPointSpec> tow_points;
};

/// winch: pay-out and haul-in at the tow point (docs/scenario.md "winch").
struct WinchSpec {
  bool present = false;
  Where where;
  bool rate_given = false;
  Where rate_where;
  std::vector<RowSpec> rate;  // rows {t [s], pay-out speed [m/s]}; a number = one row at t = 0
  bool length_given = false;
  Where length_where;
  std::vector<RowSpec> length;      // rows {t [s], deployed length [m]}
  Field<double> tension;            // constant-tension set point [N]
  Field<double> max_speed;          // [m/s]; absent = no limit
  Field<double> max_acceleration;   // [m/s^2]; absent = no limit
  Field<double> min_length{0.0};    // [m]
  Field<double> max_length;         // drum capacity [m]; absent = no limit
  Field<double> drum_inertia{0.0};  // tension mode: drum inertia as a mass at the rim [kg]
  Field<double> damping{0.0};       // tension mode: drum damping [N s/m]
  Field<double> rating;             // line pull rating [N]
  Field<double> split_at{1.5};      // split above this many element lengths [-]
  Field<double> remove_at{0.1};     // remove below this many element lengths [-]
};

/// bodies item (networks): a body with every key of body: and named hull points.
struct NetworkBodySpec {
  BodySpec body;  // body.name required, body.link_point optional (a line's `to` sets it)
  bool points_given = false;
  Where points_where;
  std::vector<NamedPointSpec> points;  // body axes [m]
};

/// junctions item (networks): a point mass where lines meet.
struct JunctionSpec {
  Where where;
  Field<std::string> name;        // [-]
  Field<double> mass{0.0};        // in air [kg]
  Field<double> volume{0.0};      // displaced volume [m^3]
  Field<double> drag_area{0.0};   // Cd A [m^2]
  Field<double> added_mass{0.0};  // isotropic [kg]
};

/// lines item (networks): a cable from its top end to its bottom end.
struct LineSpec {
  Where where;
  Field<std::string> name;  // [-]
  Field<std::string> from;  // vessel.<tow point> | <junction> | <body>.<point>
  Field<std::string> to;    // <junction> | <body>.<point> | free
  CableSpec cable;          // every key of cable:
  WinchSpec winch;          // lines.<i>.winch (present: a winch at the line's top)
};

/// A whole scenario as written.
struct ScenarioSpec {
  std::string name;         // `name:` key, else the file stem or example name
  std::string description;  // `description:` key (one line), may be empty
  std::string base_dir;     // directory for relative files (track CSV)
  Where root;
  EnvironmentSpec environment;
  CableSpec cable;
  BodySpec body;
  TowSpec tow;
  WinchSpec winch;
  InitialSpec initial;
  SimulationSpec simulation;
  WavesSpec waves;
  VesselSpec vessel;
  // A network (`lines:` given, instead of cable: and body:).
  bool network = false;
  Where lines_where;
  std::vector<LineSpec> lines;
  Where bodies_where;
  std::vector<NetworkBodySpec> bodies;
  Where junctions_where;
  std::vector<JunctionSpec> junctions;

  /// True for a network (`lines:`), compiled by compile_network.
  bool is_network() const { return network; }
};

}  // namespace towsim::scenario
