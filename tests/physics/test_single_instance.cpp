// One physics per bus (docs/physics.md, "One physics per bus"): the claim's
// name is the LCM port and the channel prefix; a second claim of one name is
// refused with the line naming the holder's pid and how to run beside it; a
// released claim can be taken again. The names carry this test's pid, so
// parallel tests and a physics running on the same host never meet it.
#include <gtest/gtest.h>
#include <unistd.h>

#include <string>

#include "ubersim/physics/single_instance.hpp"

using ubersim::physics::bus_claim_holder;
using ubersim::physics::bus_claim_name;
using ubersim::physics::BusClaim;
using ubersim::physics::BusTaken;

namespace {

const std::string kUrl = "udpm://239.255.76.67:7667?ttl=0";

std::string own_prefix(const std::string& what) {
  return "test_single_instance_" + std::to_string(::getpid()) + "_" + what + "_";
}

}  // namespace

TEST(BusClaimName, IsThePortAndThePrefixNotTheGroup) {
  EXPECT_EQ(bus_claim_name(kUrl, ""), "ubersim/physics/lcm-port=7667/prefix=");
  EXPECT_EQ(bus_claim_name("udpm://239.255.76.1:7667", "B_"),
            "ubersim/physics/lcm-port=7667/prefix=B_");
  // Another group on the same port shares its traffic: the same bus.
  EXPECT_EQ(bus_claim_name("udpm://239.1.2.3:7667?ttl=0", ""), bus_claim_name(kUrl, ""));
  EXPECT_NE(bus_claim_name("udpm://239.255.76.67:7668?ttl=0", ""), bus_claim_name(kUrl, ""));
  // memq:// stays in its process: no bus to share.
  EXPECT_FALSE(bus_claim_name("memq://", "").has_value());
}

TEST(BusClaimName, ALongPrefixIsNamedByItsHash) {
  const std::string long_prefix(200, 'p');
  const auto name = bus_claim_name(kUrl, long_prefix);
  ASSERT_TRUE(name.has_value());
  EXPECT_LE(name->size(), 107u);  // sun_path without its leading NUL
  EXPECT_EQ(name, bus_claim_name(kUrl, long_prefix));
  EXPECT_NE(name, bus_claim_name(kUrl, std::string(200, 'q')));
}

TEST(BusClaim, ASecondClaimIsRefusedNamingTheHolder) {
  const std::string prefix = own_prefix("second");
  const BusClaim first = BusClaim::claim(kUrl, prefix);
  ASSERT_TRUE(first.held());
  EXPECT_EQ(bus_claim_holder(*bus_claim_name(kUrl, prefix)), ::getpid());
  try {
    BusClaim::claim(kUrl, prefix);
    FAIL() << "a second claim of one bus was not refused";
  } catch (const BusTaken& taken) {
    const std::string line = taken.what();
    EXPECT_NE(line.find("(pid " + std::to_string(::getpid()) + ")"), std::string::npos) << line;
    EXPECT_NE(line.find("LCM port 7667 with channel prefix '" + prefix + "'"), std::string::npos)
        << line;
    EXPECT_NE(line.find("--lcm-url udpm://239.255.76.67:7668?ttl=0"), std::string::npos) << line;
    EXPECT_NE(line.find("--channel-prefix " + prefix + "2_"), std::string::npos) << line;
    EXPECT_EQ(line.find('\n'), std::string::npos) << "not one line: " << line;
  }
  // Beside it: another prefix, another port.
  EXPECT_TRUE(BusClaim::claim(kUrl, prefix + "beside_").held());
  EXPECT_TRUE(BusClaim::claim("udpm://239.255.76.67:7668?ttl=0", prefix).held());
}

TEST(BusClaim, AReleasedClaimCanBeTakenAgain) {
  const std::string prefix = own_prefix("released");
  { const BusClaim first = BusClaim::claim(kUrl, prefix); }
  EXPECT_FALSE(bus_claim_holder(*bus_claim_name(kUrl, prefix)).has_value());
  EXPECT_TRUE(BusClaim::claim(kUrl, prefix).held());
}

TEST(BusClaim, MemqClaimsNothing) {
  const BusClaim a = BusClaim::claim("memq://", "");
  const BusClaim b = BusClaim::claim("memq://", "");
  EXPECT_FALSE(a.held());
  EXPECT_FALSE(b.held());
}
