// Scene check: seed 000 eq. 25-26 and 36, Wen-Yu U_mf, terminal velocity, findings.
#include <gtest/gtest.h>

#include <cmath>

#include "tfdem/scene_check.h"

namespace {

using namespace tfdem;

// Seed 000 Table 1, uniform-inflow bed (SI): d = 2.5 mm, rho = 2526, k_n = 800 N/m,
// eta_n = 0.00177 N s/m, inflow 1.5 U_mf = 1.5 * 1.28 m/s, cells 1 cm.
Scene uniform_bed() {
  Scene s;
  s.particle_diameter = 0.0025;
  s.particle_density = 2526.0;
  s.gas = {1.2, 1.8e-5};
  s.gas_velocity = 1.5 * 1.28;
  s.cell_size = 0.01;
  s.normal_stiffness = 800.0;
  s.normal_damping = 0.00177;
  s.dem_time_step = 5e-6;
  s.coupling_interval = 20;
  return s;
}

bool has_finding(const SceneReport &r, Finding::Level level, const std::string &topic) {
  for (const auto &f : r.findings)
    if (f.level == level && f.topic == topic) return true;
  return false;
}

// Seed 000 after eq. 36 quotes St ~ 37,422 for the uniform-inflow case.
TEST(SceneCheck, StokesNumberOfUniformBedMatchesPaper) {
  const SceneReport r = check_scene(uniform_bed());
  const double tau_p = 2526.0 * 0.0025 * 0.0025 / (18.0 * 1.8e-5);
  EXPECT_NEAR(r.numbers.relaxation_time, tau_p, 1e-12 * tau_p);
  EXPECT_NEAR(r.numbers.stokes, 37422.0, 1.0);
}

// Wen-Yu U_mf against seed 000 Table 1 (1.28 and 1.80 m/s): within 3 %, the spread of the
// correlation against the paper's values (which come from the experiments).
TEST(SceneCheck, MinimumFluidizationNearPaperTable) {
  const drag::Gas air{1.2, 1.8e-5};
  const double ar = 1.2 * (2526.0 - 1.2) * 9.81 * std::pow(0.0025, 3) / (1.8e-5 * 1.8e-5);
  const double expected = (std::sqrt(33.7 * 33.7 + 0.0408 * ar) - 33.7) * 1.8e-5 / (1.2 * 0.0025);
  EXPECT_NEAR(minimum_fluidization_velocity(0.0025, 2526.0, air, 9.81), expected, 1e-12);
  EXPECT_NEAR(minimum_fluidization_velocity(0.0025, 2526.0, air, 9.81) / 1.28, 1.0, 0.03);
  EXPECT_NEAR(minimum_fluidization_velocity(0.004, 2700.0, air, 9.81) / 1.80, 1.0, 0.03);
}

// Terminal velocity: the force balance holds to 1e-10, and a 20 um sphere (Re ~ 0.01) falls at
// the Stokes velocity (rho_p - rho_g) g d^2 / (18 mu) within the Schiller-Naumann correction.
TEST(SceneCheck, TerminalVelocityBalancesWeightAndDrag) {
  const drag::Gas air{1.2, 1.8e-5};
  const double d = 0.0025, rho = 2526.0;
  const double u = terminal_velocity(d, rho, air, 9.81);
  const double re = 1.2 * u * d / 1.8e-5;
  const double cd = re < 1000 ? 24.0 / re * (1.0 + 0.15 * std::pow(re, 0.687)) : 0.44;
  const double weight = (rho - 1.2) * 9.81 * 3.14159265358979323846 * d * d * d / 6.0;
  const double drag = 0.5 * cd * 1.2 * 3.14159265358979323846 * d * d / 4.0 * u * u;
  EXPECT_NEAR(drag / weight, 1.0, 1e-10);
  const double small = 20e-6;
  const double stokes = (rho - 1.2) * 9.81 * small * small / (18.0 * 1.8e-5);
  const double u_small = terminal_velocity(small, rho, air, 9.81);
  const double re_small = 1.2 * u_small * small / 1.8e-5;
  EXPECT_NEAR(u_small * (1.0 + 0.15 * std::pow(re_small, 0.687)) / stokes, 1.0, 1e-9);
}

TEST(SceneCheck, ContactNumbersOfUniformBed) {
  const SceneReport r = check_scene(uniform_bed());
  EXPECT_NEAR(r.numbers.restitution, 0.97, 0.005);
  const double steps = 37.0 + (r.numbers.restitution - 0.86) / (0.97 - 0.86) * (57.0 - 37.0);  // ~57 at e_n ~0.97
  EXPECT_NEAR(r.numbers.recommended_time_step, r.numbers.contact_time / steps, 1e-18);
  EXPECT_NEAR(r.numbers.cell_to_particle, 4.0, 1e-12);
  EXPECT_TRUE(has_finding(r, Finding::Level::Ok, "DEM time step"));
  EXPECT_TRUE(has_finding(r, Finding::Level::Ok, "void fraction"));
  EXPECT_FALSE(r.has_errors());
}

TEST(SceneCheck, FlagsTooLargeTimeStepAndSmallCells) {
  Scene s = uniform_bed();
  s.dem_time_step = 1e-4;  // t_c ~ 3.6e-4 s: under 10 steps per contact
  s.cell_size = 0.002;
  const SceneReport r = check_scene(s);
  EXPECT_TRUE(r.has_errors());
  EXPECT_TRUE(has_finding(r, Finding::Level::Error, "DEM time step"));
  EXPECT_TRUE(has_finding(r, Finding::Level::Advice, "void fraction"));
  EXPECT_NE(format_report(r).find("[ERROR ] DEM time step"), std::string::npos);
}

TEST(SceneCheck, FlagsCouplingIntervalLongerThanDragResponse) {
  Scene s = uniform_bed();
  s.coupling_interval = 100000;
  EXPECT_TRUE(has_finding(check_scene(s), Finding::Level::Advice, "drag coupling"));
}

// Jet bed of seed 000 with eta_n = 20 N s/m: critical damping for two 4 mm, 2700 kg/m^3
// spheres is 2 sqrt(k m_eff) = 2 sqrt(800 * 4.524e-5 kg) = 0.38 N s/m, so the contact is
// overdamped: an error, not t_c = inf passing the step check.
TEST(SceneCheck, OverdampedContactIsAnError) {
  Scene s = uniform_bed();
  s.particle_diameter = 0.004;
  s.particle_density = 2700.0;
  s.normal_damping = 20.0;
  const SceneReport r = check_scene(s);
  EXPECT_TRUE(has_finding(r, Finding::Level::Error, "DEM time step"));
  EXPECT_TRUE(r.has_errors());
  EXPECT_NE(dem_step_problem(r.numbers.contact_time, 1e-5).find("overdamped"), std::string::npos);
}

// The step rule: t_c = 1e-3 s allows dt up to 1e-4 s (10 steps), the next step up is refused
// and the message gives the recommended step: t_c/37 = 2.703e-5 s at the jet bed's e_n 0.86,
// t_c/57 = 1.754e-5 s when e_n is not known.
TEST(SceneCheck, DemStepRuleAtItsLimit) {
  EXPECT_EQ(dem_step_problem(1e-3, 1e-4, 0.86), "");
  EXPECT_NE(dem_step_problem(1e-3, 1.01e-4, 0.86).find("above t_c/10 = 0.0001 s"), std::string::npos);
  EXPECT_NE(dem_step_problem(1e-3, 1.01e-4, 0.86).find("t_c/37 = 2.703e-05 s"), std::string::npos);
  EXPECT_NE(dem_step_problem(1e-3, 1.01e-4).find("t_c/57 = 1.754e-05 s"), std::string::npos);
}

// The rule's anchors are the two measured beds (jet e_n 0.86: 37 steps; bubbling e_n 0.97:
// 57); halfway between them (e_n 0.915) it asks for 47; outside them the nearer bed's value.
TEST(SceneCheck, RecommendedStepsPerContactFollowTheMeasuredBeds) {
  EXPECT_DOUBLE_EQ(recommended_steps_per_contact(0.86), 37.0);
  EXPECT_DOUBLE_EQ(recommended_steps_per_contact(0.97), 57.0);
  EXPECT_NEAR(recommended_steps_per_contact(0.915), 47.0, 1e-12);
  EXPECT_DOUBLE_EQ(recommended_steps_per_contact(0.5), 37.0);
  EXPECT_DOUBLE_EQ(recommended_steps_per_contact(0.99), 57.0);
  EXPECT_DOUBLE_EQ(recommended_steps_per_contact(kUnknownRestitution), 57.0);
}

// 40 steps per contact: enough for the jet bed's restitution, advice for the bubbling bed's.
TEST(SceneCheck, DemStepAdviceDependsOnRestitution) {
  EXPECT_EQ(dem_step_advice(1e-3, 1e-3 / 40.0, 0.86), "");
  const std::string advice = dem_step_advice(1e-3, 1e-3 / 40.0, 0.97);
  EXPECT_NE(advice.find("recommend >= 57 for e_n = 0.97"), std::string::npos);
  EXPECT_NE(advice.find("dt <= 1.754e-05 s"), std::string::npos);
  EXPECT_EQ(dem_step_advice(1e-3, 1e-3 / 60.0, 0.97), "");
}

// The measured bound 3.2: within it nothing; at Courant 4 with a 1 ms step the largest step
// the rule allows is 1 ms x 3.2 / 4 = 0.8 ms.
TEST(SceneCheck, GasStepProblemAboveTheMeasuredCourantNumber) {
  EXPECT_EQ(gas_step_problem(0.5, 1e-3), "");
  EXPECT_EQ(gas_step_problem(3.2, 1e-3), "");
  const std::string problem = gas_step_problem(4.0, 1e-3);
  EXPECT_NE(problem.find("the gas Courant number reached 4 (> 3.2"), std::string::npos);
  EXPECT_NE(problem.find("use <= 0.0008 s"), std::string::npos);
}

// The engine advice follows U / U_mf: seed 000's uniform bed at 1.5 U_mf (Wen-Yu U_mf 1.263
// m/s for 2.5 mm glass in air, by hand: Ar = 1.433e6, Re_mf = 210.5) is bubbling throughout,
// where the hard spheres measured faster; Goldschmidt's 1.30 m/s is 1.029 U_mf of its large
// spheres.
TEST(SceneCheck, AdvisesHardSpheresForABedBubblingThroughout) {
  Scene s = uniform_bed();
  s.gas_velocity = 1.52 * 1.263;
  EXPECT_TRUE(has_finding(check_scene(s), Finding::Level::Advice, "particle engine"));
  s.gas_velocity = 1.30;
  const SceneReport near = check_scene(s);
  EXPECT_TRUE(has_finding(near, Finding::Level::Ok, "particle engine"));
  EXPECT_NE(format_report(near).find("U = 1.029 U_mf"), std::string::npos) << format_report(near);
}

TEST(SceneCheck, RejectsNonPositiveInput) {
  Scene s = uniform_bed();
  s.particle_diameter = -1.0;
  EXPECT_THROW(check_scene(s), std::invalid_argument);
}

}  // namespace
