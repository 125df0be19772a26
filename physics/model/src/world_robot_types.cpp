// Robot types defined at run time (SIM_CONTROL DEFINE_ROBOT_TYPE), e.g. from
// the robot specs a team sends over the SSL simulation protocol.
#include "ubersim/config.hpp"
#include "ubersim/physics/world.hpp"
#include "ubersim/robot_type_definition.hpp"

namespace ubersim::physics {
namespace {

// Enough for one type per robot of both teams, and bounded against a sender
// that defines new names without end.
constexpr std::size_t kMaxDefinedTypes = 64;

}  // namespace

void World::define_robot_type(const std::string& name, const std::string& config_text) {
  auto type =
      std::make_shared<const RobotTypeConfig>(parse_robot_type_definition(name, config_text));
  if (!defined_types_) {
    // First definition: defined names are looked up before the files from now on.
    defined_types_ =
        std::make_shared<std::map<std::string, std::shared_ptr<const RobotTypeConfig>>>();
    RobotTypeSource files = setup_.robot_types;
    setup_.robot_types = [files, defined = defined_types_](const std::string& type_name) {
      const auto found = defined->find(type_name);
      return found != defined->end() ? found->second : files(type_name);
    };
  }
  if (defined_types_->count(name) == 0 && defined_types_->size() >= kMaxDefinedTypes) {
    throw ConfigError(name, 0, "already 64 robot types defined at run time");
  }
  (*defined_types_)[name] = std::move(type);
}

}  // namespace ubersim::physics
