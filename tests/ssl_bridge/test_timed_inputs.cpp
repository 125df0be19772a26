// What the bridge hands timed teams waits for its sim time (timed_inputs.hpp):
// which held messages are due, and up to which time the referee's and the
// radio's messages are all here when a frame is.
#include <gtest/gtest.h>

#include <deque>
#include <string>
#include <utility>
#include <vector>

#include "ubersim/ssl_bridge/timed_inputs.hpp"

using ubersim::ssl::latest_before;
using ubersim::ssl::take_until;

namespace {

using Stamped = std::pair<double, std::string>;
double stamp_of(const Stamped& m) {
  return m.first;
}

std::vector<std::string> names(const std::vector<Stamped>& messages) {
  std::vector<std::string> out;
  for (const Stamped& m : messages) out.push_back(m.second);
  return out;
}

}  // namespace

TEST(TimedInputs, TakeUntilTakesWhatIsDueInArrivalOrderAndKeepsTheRestInOrder) {
  std::vector<Stamped> held = {{0.03, "a"}, {0.01, "b"}, {0.05, "c"}, {0.02, "d"}, {0.06, "e"}};
  EXPECT_EQ(names(take_until(held, 0.03, stamp_of)), (std::vector<std::string>{"a", "b", "d"}));
  EXPECT_EQ(names(held), (std::vector<std::string>{"c", "e"}));
  EXPECT_TRUE(take_until(held, 0.04, stamp_of).empty());
  EXPECT_EQ(names(take_until(held, 1.0, stamp_of)), (std::vector<std::string>{"c", "e"}));
  EXPECT_TRUE(held.empty());
}

TEST(TimedInputs, LatestBeforeIsTheStateBeforeThePublicationNotAtIt) {
  const std::deque<double> states = {0.0, 0.0125, 0.025, 1.0 / 30, 0.05};
  EXPECT_DOUBLE_EQ(latest_before(states, 1.0 / 30), 0.025);
  EXPECT_DOUBLE_EQ(latest_before(states, 0.04), 1.0 / 30);
  EXPECT_DOUBLE_EQ(latest_before(states, 0.0), -1) << "no state before the first";
  EXPECT_DOUBLE_EQ(latest_before({}, 1.0), -1);
}

// The race the rule takes out: the referee judged the state at a frame's
// publication, and its message may come before the frame or after it. Held
// to the state before, it goes out with the next frame on every run.
TEST(TimedInputs, AMessageAboutThePublishedStateWaitsForTheNextFrame) {
  const std::deque<double> states = {0.0125, 0.025, 1.0 / 30};
  std::vector<Stamped> referee = {{0.025, "judged 0.025"}, {1.0 / 30, "judged the frame's state"}};
  const double settled = latest_before(states, 1.0 / 30);
  EXPECT_EQ(names(take_until(referee, settled, stamp_of)),
            (std::vector<std::string>{"judged 0.025"}));
  EXPECT_EQ(names(referee), (std::vector<std::string>{"judged the frame's state"}));
}
