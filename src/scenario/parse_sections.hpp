// Internal: one parsing function per scenario section.
#pragma once

#include "reader.hpp"

namespace towsim::scenario {

/// environment: water_density, gravity, current.
void parse_environment(MapReader& r, EnvironmentSpec& env, Diagnostics& d);
/// cable: geometry, masses and fluid-load coefficients.
void parse_cable(MapReader& r, CableSpec& cable, Diagnostics& d);
/// body: mass properties, load models, attitude (`link_required` false: a
/// network's body, whose link point a line's `to` may give).
void parse_body(MapReader& r, BodySpec& body, Diagnostics& d, bool link_required = true);
/// tow: mode, start, motion pieces, force.
void parse_tow(MapReader& r, TowSpec& tow, const std::string& base_dir, Diagnostics& d);
/// waves: regular or spectrum, water depth (src/io/parse_waves.cpp).
void parse_waves(MapReader& r, WavesSpec& w, Diagnostics& d);
/// vessel: RAOs or a motion record, and the tow point (src/io/parse_waves.cpp).
void parse_vessel(MapReader& r, VesselSpec& v, const std::string& base_dir, Diagnostics& d);
/// simulation: integration and output settings.
void parse_simulation(MapReader& r, SimulationSpec& sim);
/// winch: (src/scenario/parse_winch.cpp).
void parse_winch(MapReader& r, WinchSpec& w, Diagnostics& d);
/// A mapping `key: {NAME: [x, y, z], ...}` of named points (src/scenario/parse_network.cpp).
void parse_points(MapReader& r, const std::string& key, std::vector<NamedPointSpec>& points, bool& given, Where& where,
                  Diagnostics& d);
/// lines:, bodies:, junctions: of a network (s.network set by the caller);
/// in a single chain, bodies: and junctions: are refused.
void parse_network(MapReader& r, const YNode& root, ScenarioSpec& s, Diagnostics& d);
/// vessel.tow_points (a network's named sheaves): `r` reads `vessel`.
void parse_tow_points(MapReader& r, const YNode* vessel, ScenarioSpec& s, Diagnostics& d);

}  // namespace towsim::scenario
