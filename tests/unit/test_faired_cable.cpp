// Faired cable: loading functions f_n(phi), f_t(phi) as tables (LoadingTable,
// element_loads) against the bare-cable laws they sample, and the parsing of
// `normal_drag: {law: table, ...}` / `tangential_drag: {law: table, ...}`
// with exact error texts.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "../support/models.hpp"
#include "../support/scenario_files.hpp"
#include "towsim/hydro/loads.hpp"

using towsim::Element;
using towsim::LoadingTable;
using towsim::Model;
using towsim::TangentialLaw;
using towsim::Vec3;

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kStepDeg = 2.5;  // sampling step of the tables that reproduce a law [deg]

/// f(phi) sampled every kStepDeg over [0, 90] deg.
template <class F>
LoadingTable sampled(F f) {
  LoadingTable t;
  for (double deg = 0; deg <= 90 + 1e-9; deg += kStepDeg) {
    t.phi.push_back(deg * kPi / 180);
    t.f.push_back(f(deg * kPi / 180));
  }
  return t;
}

/// A one-element model with one section (the law's data), in water.
Model one_section(TangentialLaw law, double coef) {
  towsim::testing::CableSpec c;
  c.n = 1;
  c.length = 2;
  c.law = law;
  c.tangential = coef;
  Model m = towsim::testing::cable_model(c);
  m.cable.sections.push_back({"s", 0, 1, 2.0, 0.0, {}, {}});
  return m;
}

/// Loads of the model's only element for axis e and relative velocity u (no rotation, uniform water).
Vec3 force(const Model& m, const Vec3& e, const Vec3& u) {
  Vec3 F, M;
  towsim::element_loads(m, m.cable.elements[0], e, Vec3::Zero(), u, Vec3(0, 0, -10), 0.0, F, M);
  return F;
}

}  // namespace

// Linear interpolation of a smooth f sampled every h has error <= h^2/8 max|f''|;
// sin^2 and cos^2 have |f''| <= 2, so at h = 2.5 deg the tables are within
// (2.5 pi/180)^2 / 8 * 2 = 4.8e-4 of the law: the loads agree to 4.8e-4 R
// (R = 1/2 rho Cd D L |u|^2, times pi Ct/Cd for skin). The smoothed direction of
// the table's normal force adds at most k v_s^2 (1e-6 k at v_s = 1 mm/s).
TEST(FairedCable, TableSamplingCrossFlowAndPodeGivesTheSameLoads) {
  const double f = 0.02;
  const Model bare = one_section(TangentialLaw::Pode, f);
  Model faired = bare;
  faired.cable.sections[0].normal_loading = sampled([](double p) { return std::sin(p) * std::sin(p); });
  faired.cable.sections[0].tangential_loading = sampled([f](double) { return f; });
  const double k = bare.cable.elements[0].drag_factor;  // 1/2 rho Cd D L [kg/m]
  const double interp = std::pow(kStepDeg * kPi / 180, 2) / 8 * 2;
  std::mt19937 rng(11);
  std::normal_distribution<double> g;
  double worst = 0;
  for (int i = 0; i < 2000; ++i) {
    const Vec3 e = Vec3(g(rng), g(rng), g(rng)).normalized();
    const Vec3 u(g(rng), g(rng), g(rng));
    const Vec3 d = force(faired, e, u) - force(bare, e, u);
    const double bound = k * (interp * u.squaredNorm() + 1e-6);
    worst = std::max(worst, d.norm() / bound);
    ASSERT_LE(d.norm(), bound) << "e = " << e.transpose() << ", u = " << u.transpose();
  }
  EXPECT_GT(worst, 0.01);  // the bound is not vacuous: the interpolation error shows
}

TEST(FairedCable, TableSamplingSkinFrictionGivesTheSameLoads) {
  const double ct = 0.01, cd = 1.8;
  const Model bare = one_section(TangentialLaw::Skin, ct);
  Model faired = bare;
  faired.cable.sections[0].tangential_loading = sampled(
      [&](double p) { return kPi * ct / cd * std::cos(p) * std::cos(p); });
  const double k = bare.cable.elements[0].drag_factor;
  const double bound_rel = std::pow(kStepDeg * kPi / 180, 2) / 8 * 2 * kPi * ct / cd;
  std::mt19937 rng(12);
  std::normal_distribution<double> g;
  for (int i = 0; i < 2000; ++i) {
    const Vec3 e = Vec3(g(rng), g(rng), g(rng)).normalized();
    const Vec3 u(g(rng), g(rng), g(rng));
    const Vec3 d = force(faired, e, u) - force(bare, e, u);
    // The table's smoothed sign against skin friction's exact one: (u.e)^2
    // |sgn_s - sgn| <= v_s^2 = 1e-6 m^2/s^2, times k pi Ct / Cd.
    const double bound = k * (bound_rel * u.squaredNorm() + kPi * ct / cd * 1e-6);
    ASSERT_LE(d.norm(), bound) << "e = " << e.transpose() << ", u = " << u.transpose();
  }
}

// The table's loads by hand at one point: phi = 30 deg between axis and flow,
// between rows (20, 0.1) and (40, 0.3): f_n = 0.2; a constant f_t = 0.05.
TEST(FairedCable, TableLoadsByHand) {
  Model m = one_section(TangentialLaw::Pode, 0.0);
  m.cable.sections[0].normal_loading = {{20 * kPi / 180, 40 * kPi / 180}, {0.1, 0.3}};
  m.cable.sections[0].tangential_loading = {{0.0}, {0.05}};
  m.cable.sign_smoothing_speed = 1e-12;  // the exact directions
  const Vec3 e = Vec3::UnitX();
  const Vec3 u = 2.0 * Vec3(std::cos(kPi / 6), std::sin(kPi / 6), 0);
  const double k = m.cable.elements[0].drag_factor;
  const Vec3 F = force(m, e, u) - Vec3(0, 0, -m.cable.elements[0].weight);
  EXPECT_NEAR(F.y(), -k * 4 * 0.2, 1e-12 * k);   // normal: along -u_n = -y
  EXPECT_NEAR(F.x(), -k * 4 * 0.05, 1e-12 * k);  // tangential: u.e > 0, along -e
  EXPECT_NEAR(F.z(), 0.0, 1e-12 * k);
}

// ------------------------------------------------------------ parsing

namespace {
using ScenarioFile = towsim::testing::ScenarioFiles;
using towsim::testing::kCable;
using towsim::testing::kSim;
}  // namespace

TEST_F(ScenarioFile, FairedTablesParseAndSectionsInherit) {
  const auto s = load(
      "cable:\n"
      "  mass_per_length: 1.5\n"
      "  diameter: 0.02\n"
      "  normal_drag: {law: table, cd: 1.2, fn: [[0, 0], [90, 0.6]]}\n"
      "  tangential_drag: {law: table, ft: [[0, 0.05], [90, 0.02]]}\n"
      "  sections:\n"
      "    - {length: 50, elements: 5}\n"
      "    - {length: 50, elements: 5, normal_drag: 1.5, tangential_drag: {law: pode, f: 0.01}}\n"
      "    - {length: 50, elements: 5, normal_drag: {law: table, fn: [[45, 0.3]]}}\n" +
      kSim);
  ASSERT_TRUE(s.ok()) << s.diags.str();
  const auto& c = s.model->cable;
  ASSERT_EQ(c.sections.size(), 3u);
  EXPECT_EQ(c.sections[0].normal_loading.f, (std::vector<double>{0, 0.6}));
  EXPECT_NEAR(c.sections[0].normal_loading.phi[1], kPi / 2, 1e-15);
  EXPECT_EQ(c.sections[0].tangential_loading.f, (std::vector<double>{0.05, 0.02}));
  EXPECT_TRUE(c.sections[1].normal_loading.empty());  // a number: the cross-flow law
  EXPECT_TRUE(c.sections[1].tangential_loading.empty());
  EXPECT_EQ(c.sections[2].normal_loading.f, (std::vector<double>{0.3}));
  EXPECT_EQ(c.sections[2].tangential_loading.f, (std::vector<double>{0.05, 0.02}));  // inherited
  // Cd: the table's scale (1.2), the section's number (1.5), the cable's cd again (1.2).
  const double k12 = 0.5 * 1025 * 1.2 * 0.02 * 10;
  EXPECT_NEAR(c.elements[0].drag_factor, k12, 1e-12 * k12);
  EXPECT_NEAR(c.elements[5].drag_factor, k12 / 1.2 * 1.5, 1e-12 * k12);
  EXPECT_NEAR(c.elements[10].drag_factor, k12, 1e-12 * k12);
  EXPECT_EQ(c.tangential_law, TangentialLaw::Pode);
}

TEST_F(ScenarioFile, FairedTableErrors) {
  const auto s = load(kCable +
                      "  normal_drag: {law: table, fn: [[0, -0.1], [95, 0.3], [45, 0.2]]}\n"
                      "  tangential_drag: {law: table}\n" +
                      kSim);
  EXPECT_EQ(
      s.diags.str(),
      at("6:34: cable.normal_drag.fn.0: fn must be >= 0 (got -0.1)") +
          at("6:45: cable.normal_drag.fn.1: the angle between cable and flow must be within [0, 90] deg (got 95)") +
          at("6:56: cable.normal_drag.fn.2: angles must be strictly increasing (got 45 after 95)") +
          at("7:3: cable.tangential_drag.ft: missing required key"));
}

TEST_F(ScenarioFile, FairedLawChoices) {
  auto s = load(kCable + "  normal_drag: {law: tabel, fn: [[0, 0]]}\n" + kSim);
  // (an unknown law: no second error about its keys)
  EXPECT_EQ(s.diags.str(), at("6:22: cable.normal_drag.law: expected one of cross_flow, table (got 'tabel'; did "
                              "you mean 'table'?)"));
  s = load(kCable + "  tangential_drag: {law: tabel, ft: [[0, 0]]}\n" + kSim);
  EXPECT_EQ(s.diags.str(), at("6:26: cable.tangential_drag.law: expected one of pode, skin, table (got 'tabel'; "
                              "did you mean 'table'?)"));
  s = load(kCable + "  normal_drag: {cd: 1.1, fn: [[0, 0]]}\n" + kSim);
  EXPECT_EQ(s.diags.str(), at("6:26: cable.normal_drag.fn: unknown key (expected one of: law, cd)"));
  s = load(kCable + "  tangential_drag: {law: table, ft: 0.1}\n" + kSim);
  EXPECT_EQ(s.diags.str(), at("6:37: cable.tangential_drag.ft: expected a list of rows of 2 numbers (got '0.1')"));
  s = load(kCable + "  normal_drag: {cd: 1.1}\n" + kSim);
  ASSERT_TRUE(s.ok()) << s.diags.str();
  EXPECT_NEAR(s.model->cable.elements[0].drag_factor, 0.5 * 1025 * 1.1 * 0.019 * 20, 1e-9);
}

// A table law in one section does not count as a different pode/skin law.
TEST_F(ScenarioFile, FairedSectionBesideSkinSections) {
  const auto s = load(
      "cable:\n  mass_per_length: 1.5\n  diameter: 0.02\n  tangential_drag: {law: skin, ct: 0.01}\n"
      "  sections:\n"
      "    - {length: 50, elements: 5, tangential_drag: {law: table, ft: [[0, 0.01]]}}\n"
      "    - {length: 50, elements: 5}\n" +
      kSim);
  ASSERT_TRUE(s.ok()) << s.diags.str();
  EXPECT_EQ(s.model->cable.tangential_law, TangentialLaw::Skin);
  EXPECT_FALSE(s.model->cable.sections[0].tangential_loading.empty());
}
