#pragma once
// ubersim_demo_team's shell (docs/design.md, "One shape for every program"):
// the DemoTeam core (demo_team.hpp) on the process host. The command line
// (main.cpp) fills the options.
#include "demo_team.hpp"

namespace demo {

// Plays as `own` until SIGINT/SIGTERM (0). Throws std::runtime_error when LCM
// fails.
int run_demo_team(const DemoTeamOptions& options, ubersim::Team own);

}  // namespace demo
