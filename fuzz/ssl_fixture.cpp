#include "ssl_fixture.hpp"

#include <ubersim/team_t.hpp>

#include "ubersim/config.hpp"
#include "ubersim/config_paths.hpp"
#include "ubersim/field_config.hpp"
#include "ubersim/robot_config.hpp"

namespace ubersim::fuzz {

SslFixture& SslFixture::instance() {
  static SslFixture fixture = [] {
    SslFixture f;
    const std::string dir = UBERSIM_FUZZ_CONFIG_DIR;
    const RobotTypeConfig robot = load_robot_config(dir, "omni4_ssl");
    f.base = ssl::base_robot_type(ConfigFile::load(resolve_config(dir, "robots", "omni4_ssl")),
                                  robot, 0.0215);
    f.wheels = ssl::wheel_mapping(robot);
    f.field = load_field_config(dir, "division_b").to_message(0.0215);
    for (int i = 0; i < 6; ++i) {
      for (const int8_t team : {int8_t{team_t::YELLOW}, int8_t{team_t::BLUE}}) {
        robot_state_t r{};
        r.team = team;
        r.robot_id = i;
        r.robot_type = "omni4_ssl";
        r.x = (team == team_t::YELLOW ? -1.0 : 1.0) * (0.5 + 0.6 * i);
        r.y = 0.4 * i - 1.0;
        f.state.robots.push_back(r);
      }
    }
    f.state.num_robots = static_cast<int32_t>(f.state.robots.size());
    f.settings.new_robot_type = "omni4_ssl";
    f.settings.robot_radius = robot.radius;
    return f;
  }();
  // Pointers into the fixture, set after it reached its final address.
  fixture.settings.base_robot_type = &fixture.base;
  fixture.settings.current_field = &fixture.field;
  return fixture;
}

}  // namespace ubersim::fuzz
