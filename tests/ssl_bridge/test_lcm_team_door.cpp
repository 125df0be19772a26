// The LCM door's command line side (lcm_team_door.hpp): which bus an LCM team
// gets, how its command is given it, and what is refused.
#include <gtest/gtest.h>

#include "ubersim/ssl_bridge/lcm_team_door.hpp"

using ubersim::Team;
using ubersim::ssl::apply_team_protocols;
using ubersim::ssl::grsim_teams;
using ubersim::ssl::LcmDoorOptions;
using ubersim::ssl::private_lcm_url;
using ubersim::ssl::TeamGroupOptions;
using ubersim::ssl::TeamProtocol;

TEST(LcmTeamDoor, PrivateBusIsTheNextPortOnTheSameGroupWithTtlZero) {
  EXPECT_EQ(private_lcm_url("udpm://239.255.76.67:7667?ttl=0"), "udpm://239.255.76.67:7668?ttl=0");
  EXPECT_EQ(private_lcm_url("udpm://239.255.76.67:7667?ttl=1&recv_buf_size=100"),
            "udpm://239.255.76.67:7668?ttl=0");
  EXPECT_EQ(private_lcm_url("memq://"), std::nullopt);
  EXPECT_EQ(private_lcm_url("udpm://239.255.76.67:65535"), std::nullopt);
}

TEST(LcmTeamDoor, AnLcmTeamsCommandRunsOnThePrivateBus) {
  TeamGroupOptions teams;
  teams.commands = {{Team::Yellow, false, "yellow_ai"}, {Team::Blue, false, "blue_ai"}};
  LcmDoorOptions door;
  EXPECT_EQ(apply_team_protocols({{"yellow", "lcm"}, {"blue", "ssl"}},
                                 "udpm://239.255.76.67:7667?ttl=0", teams, door),
            "");
  ASSERT_EQ(door.teams.size(), 1u);
  EXPECT_EQ(door.teams[0], Team::Yellow);
  EXPECT_EQ(door.url, "udpm://239.255.76.67:7668?ttl=0");
  EXPECT_EQ(teams.commands[0].command,
            "LCM_DEFAULT_URL='udpm://239.255.76.67:7668?ttl=0'; export LCM_DEFAULT_URL; yellow_ai");
  EXPECT_EQ(teams.commands[1].command, "blue_ai");
}

TEST(LcmTeamDoor, BadProtocolsAreRefusedWithAReason) {
  const std::string url = "udpm://239.255.76.67:7667?ttl=0";
  TeamGroupOptions teams;
  teams.commands = {{Team::Yellow, false, "yellow_ai"}};
  LcmDoorOptions door;
  EXPECT_NE(
      apply_team_protocols({{"yellow", "dds"}}, url, teams, door).find("not ssl, lcm or grsim"),
      std::string::npos);
  EXPECT_NE(apply_team_protocols({{"blue", "lcm"}}, url, teams, door).find("no --team-command"),
            std::string::npos);
  EXPECT_NE(apply_team_protocols({{"yellow", "lcm"}}, "memq://", teams, door).find("udpm://"),
            std::string::npos);
  door.url = url;
  EXPECT_NE(apply_team_protocols({{"yellow", "lcm"}}, url, teams, door).find("main bus"),
            std::string::npos);
}

TEST(LcmTeamDoor, GrsimTeamsKeepTheirCommandAndMayPlayBothColours) {
  const std::string url = "udpm://239.255.76.67:7667?ttl=0";
  TeamGroupOptions teams;
  teams.commands = {{Team::Yellow, false, "yellow_ai"}, {Team::Blue, false, "blue_ai"}};
  LcmDoorOptions door;
  EXPECT_EQ(apply_team_protocols({{"blue", "grsim"}}, url, teams, door), "");
  EXPECT_TRUE(door.teams.empty());
  EXPECT_EQ(teams.commands[1].command, "blue_ai");
  EXPECT_EQ(teams.commands[1].protocol, TeamProtocol::Grsim);
  EXPECT_EQ(teams.commands[0].protocol, TeamProtocol::Ssl);
  EXPECT_EQ(grsim_teams(teams), std::vector<Team>{Team::Blue});

  TeamGroupOptions both;
  both.commands = {{Team::Yellow, true, "one_ai"}};
  EXPECT_EQ(apply_team_protocols({{"both", "grsim"}}, url, both, door), "");
  EXPECT_EQ(grsim_teams(both), (std::vector<Team>{Team::Yellow, Team::Blue}));
  EXPECT_NE(apply_team_protocols({{"both", "lcm"}}, url, both, door).find("one colour"),
            std::string::npos);
  EXPECT_NE(apply_team_protocols({{"yellow", "grsim"}, {"yellow", "ssl"}}, url, teams, door)
                .find("given twice"),
            std::string::npos);
}
