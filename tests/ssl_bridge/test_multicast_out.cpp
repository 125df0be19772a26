// Where the bridge's multicast streams go: the interface list, and the table
// of group memberships that decides whether the lo copy is sent.
#include <gtest/gtest.h>

#include <stdexcept>

#include "ubersim/ssl_bridge/multicast_out.hpp"

namespace ubersim::ssl {
namespace {

// /proc/net/igmp as Linux writes it: lo joined 224.5.23.2 and 224.0.0.1,
// eth0 joined 224.5.23.1 and 224.0.0.1.
constexpr const char* kIgmp =
    "Idx\tDevice    : Count Querier\tGroup    Users Timer\tReporter\n"
    "1\tlo        :     2      V3\n"
    "\t\t\t\t021705E0     1 0:00000000\t\t0\n"
    "\t\t\t\t010000E0     1 0:00000000\t\t0\n"
    "2\teth0      :     2      V3\n"
    "\t\t\t\t011705E0     1 0:00000000\t\t0\n"
    "\t\t\t\t010000E0     1 0:00000000\t\t0\n";

TEST(SslMulticastOut, MembershipsAreReadPerInterface) {
  GroupMemberships memberships;
  memberships.parse(kIgmp);
  EXPECT_TRUE(memberships.joined("lo", "224.5.23.2"));
  EXPECT_FALSE(memberships.joined("eth0", "224.5.23.2"));
  EXPECT_TRUE(memberships.joined("eth0", "224.5.23.1"));
  EXPECT_FALSE(memberships.joined("lo", "224.5.23.1"));
  EXPECT_TRUE(memberships.joined("eth0", "224.0.0.1"));
  EXPECT_FALSE(memberships.joined("wlan0", "224.0.0.1"));
  EXPECT_FALSE(memberships.joined("lo", "not an address"));
}

TEST(SslMulticastOut, AnUnreadableTableMeansNoMemberships) {
  GroupMemberships memberships("/nonexistent/igmp");
  memberships.refresh();
  EXPECT_FALSE(memberships.joined("lo", "224.5.23.2"));
  memberships.parse("garbage\n\t\t\tZZZZZZZZ 1\n\t\t\t12 1\n");
  EXPECT_FALSE(memberships.joined("garbage", "224.5.23.2"));
}

// /proc/net/route of a desktop with a multicast route to lo as well.
constexpr const char* kRoutes =
    "Iface\tDestination\tGateway \tFlags\tRefCnt\tUse\tMetric\tMask\t\tMTU\tWindow\tIRTT\n"
    "eth0\t00000000\t010200C0\t0003\t0\t0\t100\t00000000\t0\t0\t0\n"
    "eth0\t000200C0\t00000000\t0001\t0\t0\t0\t00FFFFFF\t0\t0\t0\n"
    "lo\t000000E0\t00000000\t0001\t0\t0\t0\t000000F0\t0\t0\t0\n";

TEST(SslMulticastOut, TheLongestPrefixRouteNamesTheDevice) {
  EXPECT_EQ(route_device("224.5.23.2", kRoutes), "lo");   // 224.0.0.0/4 beats the default
  EXPECT_EQ(route_device("192.0.2.7", kRoutes), "eth0");  // 192.0.2.0/24
  EXPECT_EQ(route_device("8.8.8.8", kRoutes), "eth0");    // the default route
  EXPECT_EQ(route_device("224.5.23.2", "Iface\tDestination\n"), "");  // no route
  EXPECT_EQ(route_device("not an address", kRoutes), "");
  EXPECT_EQ(interface_address("no-such-device0"), "");
}

TEST(SslMulticastOut, InterfaceListsAreAddressesWithoutRepeats) {
  std::vector<std::string> warnings;
  const auto interfaces = resolve_interfaces(" 127.0.0.1 ,127.0.0.1,,", "224.5.23.2", warnings);
  ASSERT_EQ(interfaces.size(), 1u);
  EXPECT_EQ(interfaces[0].address, "127.0.0.1");
  EXPECT_TRUE(interfaces[0].loopback());
  EXPECT_TRUE(warnings.empty());
  EXPECT_THROW(resolve_interfaces("eth0", "224.5.23.2", warnings), std::invalid_argument);
}

TEST(SslMulticastOut, ALoopbackOnlyStreamSaysItStaysOnLo) {
  StreamSettings settings;
  settings.name = "vision";
  settings.group = "224.5.23.2";
  settings.port = 10020;
  settings.ttl = 0;
  settings.interfaces = "127.0.0.1";
  const MulticastStream stream(settings);
  const std::string text = stream.describe();
  EXPECT_NE(text.find("vision to 224.5.23.2:10020 (ttl 0: this host only) on "), std::string::npos)
      << text;
  EXPECT_NE(text.find("127.0.0.1"), std::string::npos) << text;
}

TEST(SslMulticastOut, NoInterfaceIsAnError) {
  StreamSettings settings;
  settings.name = "vision";
  settings.group = "224.5.23.2";
  settings.port = 10020;
  settings.interfaces = " , ";
  EXPECT_THROW(MulticastStream{settings}, std::invalid_argument);
}

}  // namespace
}  // namespace ubersim::ssl
