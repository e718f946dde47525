// Internal: range checks on spec fields, each reporting "must be ... (got ...)".
#pragma once

#include "towsim/scenario/spec.hpp"

namespace towsim::scenario {

/// Report unless value > 0.
void check_positive(const Field<double>& f, Diagnostics& d);
/// Report unless value >= 0.
void check_non_negative(const Field<double>& f, Diagnostics& d);
/// Report unless value >= minimum.
void check_at_least(const Field<long long>& f, long long minimum, Diagnostics& d);
/// Report unless value <= maximum.
void check_at_most(const Field<long long>& f, long long maximum, Diagnostics& d);
/// Report a zero vector ("must be a non-zero vector"), or one too large to
/// normalise (its length overflows).
void check_nonzero(const Field<Vec3>& f, Diagnostics& d);
/// Report a first column (time, depth, ...) that does not strictly increase.
/// `what` names the column in messages ("times", "depths").
void check_increasing(const std::vector<RowSpec>& rows, const std::string& what, Diagnostics& d);
/// Report an inertia tensor that is not symmetric positive definite with its
/// principal moments satisfying the triangle inequality.
void check_inertia(const Field<Mat3>& f, Diagnostics& d);
/// Report a 6x6 matrix that is not symmetric positive semi-definite.
void check_psd6(const Field<Mat6>& f, Diagnostics& d);
/// Report negative diagonal terms of a 6x6 matrix.
void check_diagonal_non_negative(const Field<Mat6>& f, Diagnostics& d);

/// Check the body's values (and its load models).
void check_body(const BodySpec& b, Diagnostics& d);
/// Build the Body from a checked spec (finalize_body included).
Body build_body(const BodySpec& b, const Fluid& fluid);

/// Check the cable (single-section form or sections with in-line bodies,
/// attachments) and the rules that tie it to the end body and simulation.
void check_cable(const CableSpec& c, const BodySpec& end_body, const SimulationSpec& sim, Diagnostics& d);
/// Build the chain: cable elements by section, in-line bodies, the end body,
/// attachments at their joints (model.fluid must be set).
void build_chain(const CableSpec& c, const BodySpec& end_body, Model& model);

/// Check the tow's values; needs no tow errors so far for the turn-speed check.
void check_tow(const TowSpec& t, Diagnostics& d);
/// Build the Tow from a checked spec (without turns and speed changes: the
/// offsets alone, whose velocity starts the course).
Tow build_tow(const TowSpec& t, bool include_manoeuvres = true);

/// Check `environment.seabed` (and its rules with the formulation and waves).
void check_seabed(const ScenarioSpec& s, Diagnostics& d);
/// Build the Seabed into m.seabed from a checked spec (nothing when absent).
void build_seabed(const SeabedSpec& spec, Model& m);
/// Refuse a tow point below the seabed at t = 0, and a hanging or directed
/// start with a cable joint or a body below it (needs the whole model built).
void check_seabed_start(const ScenarioSpec& s, const Model& m, Diagnostics& d);

/// Check `waves:` and `vessel:` (src/io/compile_waves.cpp).
void check_waves(const ScenarioSpec& s, Diagnostics& d);

/// Check winch: against the cable, tow and simulation (src/scenario/compile_winch.cpp).
void check_winch(const ScenarioSpec& s, Diagnostics& d);

/// Build the model's winch (after the chain).
void build_winch(const WinchSpec& w, Model& m);

/// Checks of winch: against the built chain (initial length, limits,
/// attachments); false when one failed.
bool check_winch_model(const WinchSpec& w, const Model& m, Diagnostics& d);

/// With rk4 and a winch on an elastic cable: the fixed step against the
/// axial bound of the top element at its shortest (docs/theory.md §6.5).
void check_winch_rk4(const ScenarioSpec& s, const Model& m, Diagnostics& d);
/// Build the waves (into m.fluid) and the vessel (into m.tow) from a checked
/// spec; needs m.tow and m.fluid built.
void attach_waves(const ScenarioSpec& s, Model& m);

}  // namespace towsim::scenario
