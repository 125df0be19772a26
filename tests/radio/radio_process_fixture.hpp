#pragma once
// Starts a real ubersim_radio with test profiles (yellow: what the test
// studies; blue: a perfect link the driver pings through) and a driver.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <string>

#include "child_process.hpp"  // tests/support
#include "radio_driver.hpp"
#include "radio_test_util.hpp"

namespace radio_test {

using ubersim::test::ChildProcess;

class RadioProcessTest : public ::testing::Test {
 protected:
  // `decorate` shapes the driver's ground truth from the first SIM_STATE on.
  void start(const std::string& yellow_profile, int robots_per_team = 6,
             std::function<void(ubersim::sim_state_t&)> decorate = {}) {
    std::string pattern = ::testing::TempDir() + "radio_test_XXXXXX";
    ASSERT_NE(::mkdtemp(pattern.data()), nullptr);
    dir_ = pattern;
    write(dir_ / "yellow.cfg", yellow_profile);
    write(dir_ / "blue.cfg", profile_text(0, 0, 0, 0, 0));
    std::vector<std::string> argv{UBERSIM_RADIO_EXE, "--yellow-profile",
                                  (dir_ / "yellow.cfg").string(), "--blue-profile",
                                  (dir_ / "blue.cfg").string()};
    driver_ = std::make_unique<RadioDriver>(robots_per_team);
    driver_->decorate = std::move(decorate);
    process_ = std::make_unique<ChildProcess>(argv, (dir_ / "radio.log").string());
    ASSERT_TRUE(driver_->wait_ready()) << process_->log();
  }

  void TearDown() override {
    if (process_) {
      EXPECT_EQ(process_->stop(), 0) << process_->log();
      if (HasFailure()) std::cerr << "--- ubersim_radio log ---\n" << process_->log();
    }
    if (!dir_.empty()) std::filesystem::remove_all(dir_);
  }

  static void write(const std::filesystem::path& path, const std::string& text) {
    std::ofstream(path) << text;
  }

  std::filesystem::path dir_;
  std::unique_ptr<RadioDriver> driver_;
  std::unique_ptr<ChildProcess> process_;
};

}  // namespace radio_test
