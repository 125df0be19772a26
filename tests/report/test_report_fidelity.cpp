// The report's experiments, short: each robot type driven through the real
// radio emulator into real physics, read back from the real vision emulator,
// the ball kicked and chipped, and the figure-8 with and without emulated
// latency. Fails when the simulation leaves the tolerances of the physics
// issue: acceleration within 5 % of commanded until the predicted saturation,
// saturation within 10 % of the prediction, ball roll-out and chips within
// 10 % of their models. Physics runs in lockstep: load cannot change a result.
// (run ISOLATED: real LCM multicast)
#include <gtest/gtest.h>
#include <stdlib.h>

#include <filesystem>
#include <memory>

#include "acceleration.hpp"
#include "ball.hpp"
#include "figure8.hpp"
#include "targets.hpp"

namespace {

using namespace ubersim::report;

// The shipped robot types a scenario uses (the full report adds the planar
// variant of the differential drive).
const char* kTypes[] = {"diff_drive_cmdragons02", "omni3_cmdragons02", "omni4_ssl",
                        "omni4_ssl_planar"};

class ReportFidelity : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string pattern = ::testing::TempDir() + "report_fidelity_XXXXXX";
    ASSERT_NE(::mkdtemp(pattern.data()), nullptr);
    dir_ = pattern;
    setup_ = std::make_unique<ExperimentSetup>(
        RigPaths{UBERSIM_BIN_DIR, UBERSIM_SOURCE_CONFIG_DIR, dir_.string()});
  }
  void TearDown() override {
    // Logs of the processes stay when something failed.
    if (!HasFailure())
      std::filesystem::remove_all(dir_);
    else
      std::cerr << "process logs and generated configs: " << dir_ << "\n";
  }

  // Every check must hold; the message names each one that does not.
  static void expect_all_met(const std::vector<Check>& checks) {
    ASSERT_FALSE(checks.empty());
    for (const auto& c : checks) {
      EXPECT_TRUE(c.met()) << c.what << ": measured " << c.measured << ", expected " << c.expected
                           << " +- " << c.tolerance * 100 << " % (error " << c.error() * 100
                           << " %)";
    }
  }

  std::filesystem::path dir_;
  std::unique_ptr<ExperimentSetup> setup_;
};

// 2 m/s^2 forward ramp through the radio, vision noise on: the acceleration
// (ground truth and VISION) within 5 %, the top speed within 10 % of the config's.
TEST_F(ReportFidelity, RampFollowsTwoMetresPerSecondSquaredUntilTopSpeed) {
  for (const char* type : kTypes) {
    SCOPED_TRACE(type);
    RampSettings settings;
    settings.robot_type = type;
    settings.trials = 1;
    settings.first_seed = 3;
    const RampResult ramp = run_ramp(*setup_, settings);
    ASSERT_EQ(ramp.trials.size(), 1u);
    EXPECT_GT(ramp.trials[0].vision.size(), 30u) << "VISION saw the robot too rarely";
    expect_all_met(check_ramp(ramp));
  }
}

// Wheel-speed ramps below and above the predicted torque/traction limit:
// followed within 5 % below it, saturating within 10 % of it above.
TEST_F(ReportFidelity, AccelerationSaturatesWhereTorqueOrTractionPredicts) {
  for (const char* type : kTypes) {
    SCOPED_TRACE(type);
    SweepSettings settings;
    settings.robot_type = type;
    settings.fractions = {0.7, 1.4, 1.8};
    settings.velocity_commands_too = false;
    const SweepResult sweep = run_sweep(*setup_, settings);
    ASSERT_EQ(sweep.points.size(), 3u);
    expect_all_met(check_sweep(sweep));
  }
}

// Flat kicks roll out as the ball config's sliding/rolling model says, chips
// fly as far and as high as ballistics says, within 10 %.
TEST_F(ReportFidelity, BallRollOutAndChipMatchTheirModels) {
  BallSettings settings;
  settings.kick_speeds = {1.0, 3.5, 6.5};
  settings.chip_speeds = {3.0, 5.0};
  const BallResult ball = run_ball(*setup_, settings);
  ASSERT_EQ(ball.kicks.size(), 3u);
  ASSERT_EQ(ball.chips.size(), 2u);
  expect_all_met(check_ball(ball));
}

// The published controller follows the figure-8 in both runs, and the
// emulated latency and noise cost it tracking accuracy (what the report shows).
TEST_F(ReportFidelity, FigureEightShowsWhatLatencyCostsTheController) {
  Figure8Settings emulated;
  emulated.label = "cmdragons02";
  emulated.laps = 2;
  Figure8Settings ideal = emulated;
  ideal.label = "ideal";
  ideal.vision_profile = ideal.radio_profile = "ideal";
  const Figure8Result with_latency = run_figure8(*setup_, emulated);
  const Figure8Result without = run_figure8(*setup_, ideal);
  for (const Figure8Result* r : {&with_latency, &without}) {
    SCOPED_TRACE(r->settings.label);
    // One packet per 30 Hz camera frame (a few frames miss the robot).
    EXPECT_GT(r->packets, 0.9 * 30 * emulated.laps * r->period);
    EXPECT_GT(r->tracking.count, 100u);
    // It really goes round: the mean speed is the path's.
    EXPECT_NEAR(r->mean_speed, emulated.speed, 0.1 * emulated.speed);
  }
  EXPECT_GT(with_latency.tracking.rms, without.tracking.rms);
}

}  // namespace
