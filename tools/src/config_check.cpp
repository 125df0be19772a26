// ubersim_config_check: loads config files with the schema of their kind and
// prints the first error (file, line, what was expected) or "ok". The same
// loaders the processes use, so a file that passes here loads there.
#include <CLI/CLI.hpp>
#include <iostream>

#include "ubersim/config.hpp"
#include "ubersim/config_paths.hpp"
#include "ubersim/field_config.hpp"
#include "ubersim/robot_config.hpp"
#include "ubersim/scenario_config.hpp"

int main(int argc, char** argv) {
  CLI::App app{"Check ubersim config files against the schema of their kind"};
  std::string kind;
  std::vector<std::string> names;
  std::string config_dir = ubersim::default_config_dir().string();
  app.add_option("kind", kind, "fields | robots | scenarios | any (syntax only)")
      ->required()
      ->check(CLI::IsMember({"fields", "robots", "scenarios", "any"}));
  app.add_option("files", names, "config names or paths")->required();
  app.add_option("--config-dir", config_dir, "config folder")->capture_default_str();
  CLI11_PARSE(app, argc, argv);

  int failures = 0;
  for (const auto& name : names) {
    try {
      const auto path = kind == "any" ? std::filesystem::path(name)
                                      : ubersim::resolve_config(config_dir, kind, name);
      const auto config = ubersim::ConfigFile::load(path);
      const std::string short_name = path.stem().string();
      if (kind == "fields") ubersim::load_field_config(config, short_name);
      if (kind == "robots") ubersim::load_robot_config(config, short_name);
      if (kind == "scenarios") ubersim::load_scenario_config(config, short_name);
      std::cout << path.string() << ": ok\n";
    } catch (const ubersim::ConfigError& error) {
      std::cerr << error.what() << "\n";
      ++failures;
    }
  }
  return failures == 0 ? 0 : 1;
}
