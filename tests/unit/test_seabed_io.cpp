// environment.seabed and breaking loads as a user meets them: the keys, the
// refusals (exact text), the waves' finite depth, the output columns and the
// utilisation warning and failure flags (INTERFACE.md "Elastic cable and seabed").
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>

#include "../support/cli.hpp"
#include "../support/scenario_files.hpp"
#include "towsim/scenario/scenario.hpp"
#include "towsim/waves/waves.hpp"

namespace fs = std::filesystem;

namespace {

using SeabedIo = towsim::testing::ScenarioFiles;
using towsim::testing::kCable;
using towsim::testing::kSim;
using towsim::testing::read_text_csv;
using towsim::testing::TextCsv;
using towsim::testing::towsim_cli;

nlohmann::json read_json(const fs::path& p) {
  std::ifstream in(p);
  return nlohmann::json::parse(in);
}

}  // namespace

TEST_F(SeabedIo, FlatAndTableRead) {
  const auto flat = load("environment:\n  seabed: {depth: 500, stiffness: 2.0e5, damping: 10, friction: 0.3}\n" +
                         kCable + kSim);
  ASSERT_TRUE(flat.ok()) << flat.diags.str();
  ASSERT_TRUE(flat.model->seabed.has_value());
  const towsim::Seabed& sb = *flat.model->seabed;
  EXPECT_EQ(sb.depth_at(-1e6), 500);
  EXPECT_EQ(sb.stiffness, 2.0e5);
  EXPECT_EQ(sb.damping, 10);
  EXPECT_EQ(sb.friction, 0.3);
  // Defaults: the contract's example values.
  const auto table = load("environment:\n  seabed: {depth: [[0, 200], [1000, 100]]}\n" + kCable + kSim);
  ASSERT_TRUE(table.ok()) << table.diags.str();
  const towsim::Seabed& t = *table.model->seabed;
  EXPECT_EQ(t.depth_at(500), 150);
  EXPECT_EQ(t.depth_at(2000), 100);
  EXPECT_EQ(t.stiffness, 1e5);
  EXPECT_EQ(t.damping, 1e3);
  EXPECT_EQ(t.friction, 0.5);
  EXPECT_TRUE(t.along_elements);  // contact: elements, the default
  const auto none = load(kCable + kSim);
  ASSERT_TRUE(none.ok());
  EXPECT_FALSE(none.model->seabed.has_value());
}

// environment.seabed.contact chooses where the cable feels the law: at its
// joints (the default) or along each element (docs/theory.md §3.2); a value
// that is neither is refused with the choices.
TEST_F(SeabedIo, ContactAtJointsOrAlongElements) {
  const auto along = load("environment:\n  seabed: {depth: 500, contact: elements}\n" + kCable + kSim);
  ASSERT_TRUE(along.ok()) << along.diags.str();
  EXPECT_TRUE(along.model->seabed->along_elements);
  const auto joints = load("environment:\n  seabed: {depth: 500, contact: joints}\n" + kCable + kSim);
  ASSERT_TRUE(joints.ok()) << joints.diags.str();
  EXPECT_FALSE(joints.model->seabed->along_elements);
  const auto bad = load("environment:\n  seabed: {depth: 500, contact: element}\n" + kCable + kSim);
  EXPECT_EQ(bad.diags.str(), at("2:33: environment.seabed.contact: expected one of joints, elements (got "
                                "'element'; did you mean 'elements'?)"));
}

TEST_F(SeabedIo, TowPointBelowTheSeabedIsRefused) {
  const auto s = load("environment:\n  seabed: {depth: 50}\n" + kCable + kSim + "tow:\n  start: [0, 0, -60]\n");
  EXPECT_EQ(s.diags.str(),
            at("11:10: tow.start: the tow point starts below the seabed (z = -60 m; the bottom is at z = -50 m "
               "there)"));
  // `towsim check` exits 2 with the same line.
  const auto [status, out] = towsim_cli("check '" + path_ + "'");
  EXPECT_EQ(status, 2);
  EXPECT_EQ(out, s.diags.str());
}

// A body's start is checked at the points where the seabed touches it
// (hull_points: each sphere's lowest point, each cylinder's end discs, a bare
// body's CG): a sphere reaching 0.5 m below the bottom is refused at its
// lowest point; a CG below the bottom inside a hull that stays above is not.
TEST_F(SeabedIo, BodyStartBelowTheSeabedIsCheckedAtItsContactPoints) {
  const std::string body =  // hangs from the cable's end at z = -100 m (Q at O_t)
      "body:\n  mass: 50\n  inertia: [1, 1, 1]\n  link_point: [0, 0, 0]\n"
      "  center_of_gravity: [0, 0, CGZ]\n  spheres:\n    - {center: [0, 0, -1], radius: 1}\n";
  auto with_cg = [&](const std::string& z) {
    std::string b = body;
    b.replace(b.find("CGZ"), 3, z);
    return b;
  };
  const auto reaching = load("environment:\n  seabed: {depth: 101.5}\n" + kCable + kSim + with_cg("-1"));
  EXPECT_EQ(reaching.diags.str(),
            at("2:19: environment.seabed.depth: body body starts below the seabed (z = -102 m; the bottom is at "
               "z = -101.5 m there): start with initial: steady (the cable settles on the bottom), a direction that "
               "keeps it above, or a shorter cable"));
  const auto cg_low = load("environment:\n  seabed: {depth: 102.5}\n" + kCable + kSim + with_cg("-2.8"));
  EXPECT_TRUE(cg_low.ok()) << cg_low.diags.str();
}

TEST_F(SeabedIo, HangingStartBelowTheSeabedIsRefused) {
  // 100 m hanging in 50 m of water: joint 3 (60 m) is the first below.
  const auto s = load("environment:\n  seabed: {depth: 50}\n" + kCable + kSim);
  EXPECT_EQ(s.diags.str(),
            at("2:19: environment.seabed.depth: cable joint 3 (60 m from the tow point) starts below the seabed "
               "(z = -60 m; the bottom is at z = -50 m there): start with initial: steady (the cable settles on "
               "the bottom), a direction that keeps it above, or a shorter cable"));
  // Laid down by the statics instead: accepted.
  EXPECT_TRUE(load("environment:\n  seabed: {depth: 50}\n" + kCable + kSim + "initial: steady\n").ok());
}

TEST_F(SeabedIo, BadValuesAreRefused) {
  const auto s = load(
      "environment:\n"
      "  seabed:\n"
      "    depth: [[0, 50], [0, -3]]\n"
      "    stiffness: 0\n"
      "    damping: -1\n"
      "    friction: -0.2\n" +
      kCable + kSim + "  formulation: paper\n");
  EXPECT_EQ(s.diags.str(), at("3:22: environment.seabed.depth.1: depth must be > 0 (got -3)") +
                               at("3:22: environment.seabed.depth.1: x values must be strictly increasing (got 0 "
                                  "after 0)") +
                               at("4:16: environment.seabed.stiffness: must be > 0 (got 0)") +
                               at("5:14: environment.seabed.damping: must be >= 0 (got -1)") +
                               at("6:15: environment.seabed.friction: must be >= 0 (got -0.2)") +
                               at("14:16: simulation.formulation: the paper formulation has no seabed contact (use "
                                  "formulation: default)"));
}

TEST_F(SeabedIo, WavesTakeTheSeabedDepth) {
  // Finite-depth dispersion omega^2 = g k tanh(k h), checked against a
  // bisection written here (relative 1e-12: the Newton solve's 1e-14 residual
  // plus the bisection's 2^-60 bracket).
  const auto s = load("environment:\n  seabed: {depth: 30}\n" + kCable + kSim + "initial: steady\n" +
                      "waves:\n  spectrum: {type: jonswap, hs: 2, tp: 10, components: 50}\n");
  ASSERT_TRUE(s.ok()) << s.diags.str();
  const auto& waves = s.model->fluid.waves;
  ASSERT_TRUE(waves);
  EXPECT_EQ(waves->depth, 30);
  const double g = 9.81, h = 30;
  for (const auto& c : waves->components) {
    const double w2 = c.omega * c.omega;
    double lo = w2 / g, hi = w2 / g;  // f(k) = g k tanh(k h) - w2 increases; f(w2/g) <= 0
    while (g * hi * std::tanh(hi * h) < w2) hi *= 2;
    for (int i = 0; i < 200; ++i) {
      const double mid = 0.5 * (lo + hi);
      (g * mid * std::tanh(mid * h) < w2 ? lo : hi) = mid;
    }
    EXPECT_NEAR(c.k, 0.5 * (lo + hi), 1e-12 * c.k) << c.omega;
    EXPECT_GT(c.k, w2 / g);  // shallower than deep water: shorter waves
  }
  // A different water_depth on a flat seabed is refused.
  const auto both = load("environment:\n  seabed: {depth: 30}\n" + kCable + kSim + "initial: steady\n" +
                         "waves:\n  regular: {height: 1, period: 8}\n  water_depth: 40\n");
  EXPECT_EQ(both.diags.str(), at("13:16: waves.water_depth: differs from environment.seabed.depth (30): the waves "
                                 "take the seabed's depth (leave water_depth out)"));
}

TEST_F(SeabedIo, OutputsOfACableOnTheBottom) {
  const fs::path out = dir_ / "out";
  write("environment:\n  seabed: {depth: 80}\n" + kCable + "simulation:\n  duration: 1\n  time_step: 0.002\n" +
        "initial: steady\n");
  const auto [status, text] = towsim_cli("run '" + (dir_ / "scen.yaml").string() + "' --out '" + out.string() + "'");
  ASSERT_EQ(status, 0) << text;
  const TextCsv ts = read_text_csv(out / "timeseries.csv");
  for (const char* c : {"contact_length", "seabed_normal_force", "seabed_friction_force"}) ASSERT_GE(ts.col(c), 0) << c;
  // 100 m of cable in 80 m of water, 20 m elements: the last one lies on the
  // bottom, the one before hangs on to it.
  EXPECT_NEAR(ts.num(ts.rows.size() - 1, "contact_length"), 20, 20);
  EXPECT_GT(ts.num(ts.rows.size() - 1, "seabed_normal_force"), 0);
  // The touchdown point: on the bottom (within 1 cm: the sink w/k and the
  // last row's motion), and the lying length the rest of the 100 m (1e-9:
  // the columns' 12 digits).
  for (const char* c : {"touchdown_arc_length", "touchdown_x", "touchdown_y", "touchdown_z", "lying_length"})
    ASSERT_GE(ts.col(c), 0) << c;
  const std::size_t last = ts.rows.size() - 1;
  EXPECT_NEAR(ts.num(last, "touchdown_z"), -80, 0.01);
  EXPECT_NEAR(ts.num(last, "touchdown_arc_length") + ts.num(last, "lying_length"), ts.num(last, "deployed_length"),
              1e-9);
  EXPECT_GT(ts.num(last, "lying_length"), 0);
  const TextCsv nodes = read_text_csv(out / "nodes.csv");
  EXPECT_GE(nodes.col("seabed_force"), 0);
  EXPECT_LT(nodes.col("utilisation"), 0);  // no breaking load
  const auto sm = read_json(out / "summary.json");
  EXPECT_TRUE(sm["extremes"].contains("max_contact_length"));
  EXPECT_TRUE(sm["extremes"].contains("max_seabed_normal_force"));
  EXPECT_TRUE(sm["extremes"].contains("max_seabed_friction_force"));
  EXPECT_NEAR(sm["final"]["lying_length"].get<double>(), ts.num(last, "lying_length"), 1e-12);
  // No warning: along elements (the default) the lying cable rests on the
  // bottom's level with no shear and no compression, and with the depth a
  // whole number of elements (4 of 20 m) the top tension is w h at 5 and at
  // 10 elements alike, so the element count's estimate is 0 (below 1e-3:
  // the two steady solves' residual).
  EXPECT_TRUE(sm["warnings"].empty()) << sm["warnings"].dump();
  EXPECT_LT(sm["discretisation_error_estimate"].get<double>(), 1e-3);
  // The top tension is w h (1e-6: the steady solve and 10 digits of the column).
  EXPECT_NEAR(ts.num(last, "tow_tension"), 80 * (1.5 - 1025 * M_PI / 4 * 0.019 * 0.019) * 9.81, 1e-6 * 949);
  const auto [cs, described] = towsim_cli("check '" + (dir_ / "scen.yaml").string() + "'");
  EXPECT_EQ(cs, 0);
  EXPECT_NE(described.find("  depth" + std::string(23, ' ') + "80 m (flat)\n"), std::string::npos) << described;
}

// ---------------------------------------------------------------------------
// Utilisation: a cable hanging at rest has the top tension T = w L exactly
// (to round-off, 1e-15 relative); a breaking load set 1e-9 relative on either
// side of 3 T (then of T) decides the warning (then the failure) alone.
// ---------------------------------------------------------------------------
class Utilisation : public SeabedIo {
 protected:
  /// Run the hanging 100 m cable with `breaking_load`; its summary.json and
  /// what the program printed.
  std::pair<nlohmann::json, std::string> run_with(double breaking_load) {
    const fs::path out = dir_ / "out";
    char b[64];
    std::snprintf(b, sizeof b, "%.17g", breaking_load);
    write(kCable + "  breaking_load: " + b + "\n" + "simulation:\n  duration: 1\n  output_interval: 0.5\n");
    const auto [status, text] = towsim_cli("run '" + (dir_ / "scen.yaml").string() + "' --out '" + out.string() + "'");
    EXPECT_EQ(status, 0) << text;
    const TextCsv nodes = read_text_csv(out / "nodes.csv");
    EXPECT_GE(nodes.col("utilisation"), 0);
    EXPECT_NEAR(nodes.num(0, "utilisation"), nodes.num(0, "tension") / breaking_load, 1e-11);
    return {read_json(out / "summary.json"), text};
  }
  double top_tension() const {
    const double w = (1.5 - 1025 * std::numbers::pi / 4 * 0.019 * 0.019) * 9.81;  // apparent weight [N/m]
    return w * 100;
  }
};

TEST_F(Utilisation, WarningExactlyAboveOneThird) {
  const double T = top_tension();
  const auto [below, text_below] = run_with(3 * T * (1 + 1e-9));
  EXPECT_TRUE(below["warnings"].empty()) << below["warnings"].dump();
  EXPECT_TRUE(below["utilisation_warning"].is_null());
  EXPECT_TRUE(below["cable_failure"].is_null());
  EXPECT_EQ(text_below.find("warning"), std::string::npos) << text_below;
  const auto [above, text_above] = run_with(3 * T * (1 - 1e-9));
  ASSERT_EQ(above["warnings"].size(), 1u);
  EXPECT_EQ(above["warnings"][0].get<std::string>().rfind("utilisation above 1/3 (a safety factor below 3 on the "
                                                          "breaking load): first 0.3333333337 at t = 0 s, node 0, 0 m "
                                                          "from the tow point",
                                                          0),
            0u)
      << above["warnings"][0];
  EXPECT_EQ(above["utilisation_warning"]["node"], 0);
  EXPECT_EQ(above["utilisation_warning"]["time"], 0.0);
  EXPECT_TRUE(above["cable_failure"].is_null());
  EXPECT_NE(text_above.find("towsim: warning: utilisation above 1/3"), std::string::npos) << text_above;
}

TEST_F(Utilisation, FailureFlagExactlyAboveOne) {
  const double T = top_tension();
  const auto [below, t1] = run_with(T * (1 + 1e-9));
  EXPECT_TRUE(below["cable_failure"].is_null());
  EXPECT_FALSE(below["utilisation_warning"].is_null());
  const auto [above, t2] = run_with(T * (1 - 1e-9));
  ASSERT_FALSE(above["cable_failure"].is_null());
  EXPECT_EQ(above["cable_failure"]["node"], 0);
  EXPECT_EQ(above["cable_failure"]["arc_length"], 0.0);
  EXPECT_EQ(above["cable_failure"]["time"], 0.0);
  EXPECT_EQ(above["status"], "ok");  // the run goes on
  EXPECT_EQ(above["end_time"], 1.0);
  ASSERT_EQ(above["warnings"].size(), 2u);
  EXPECT_EQ(above["warnings"][1].get<std::string>().rfind("utilisation above 1 (tension above the breaking load", 0),
            0u);
}
