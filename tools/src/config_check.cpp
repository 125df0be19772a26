// ubersim_config_check: loads config files with the schema of their kind and
// prints the first error (file, line, what was expected) or "ok". The same
// loaders the processes use, so a file that passes here loads there. Exit 0
// when every file loads, 2 when one has an error (as every program on a config error).
#include <CLI/CLI.hpp>
#include <cstdio>
#include <iostream>

#include "ubersim/cli.hpp"
#include "ubersim/config.hpp"
#include "ubersim/config_paths.hpp"
#include "ubersim/field_config.hpp"
#include "ubersim/json_string.hpp"
#include "ubersim/process_main.hpp"
#include "ubersim/robot_config.hpp"
#include "ubersim/scenario_config.hpp"

namespace {

using ubersim::json_string;

// --dump: every key with where it is defined and its values, as one JSON
// object, so that tools in other languages (the batch runner) read our format
// through this one parser and report errors with the same file and line.
void dump(const ubersim::ConfigFile& config) {
  std::cout << "{";
  const char* separator = "";
  for (const auto& key : config.keys()) {
    std::cout << separator << json_string(key) << ": {\"where\": " << json_string(config.where(key))
              << ", \"values\": [";
    const char* comma = "";
    for (const auto& value : config.strings(key)) {
      std::cout << comma << json_string(value);
      comma = ", ";
    }
    std::cout << "]}";
    separator = ", ";
  }
  std::cout << "}\n";
}

int parse_and_run(int argc, char** argv) {
  CLI::App app{"Check ubersim config files against the schema of their kind"};
  std::string kind;
  std::vector<std::string> names;
  std::string config_dir = ubersim::default_config_dir().string();
  app.add_option("kind", kind, "fields | robots | scenarios | any (syntax only)")
      ->required()
      ->check(CLI::IsMember({"fields", "robots", "scenarios", "any"}));
  app.add_option("files", names, "config names or paths")->required();
  app.add_option("--config-dir", config_dir, "config folder")->capture_default_str();
  bool dump_keys = false;
  app.add_flag("--dump", dump_keys, "print every key, where it is defined and its values (JSON)");
  if (const auto stop = ubersim::parse_command_line(app, argc, argv)) return *stop;

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
      if (dump_keys) {
        dump(config);
      } else {
        std::cout << path.string() << ": ok\n";
      }
    } catch (const ubersim::ConfigError& error) {
      std::cerr << error.what() << "\n";
      ++failures;
    }
  }
  return failures == 0 ? 0 : 2;  // a config error, as in every program
}

}  // namespace

int main(int argc, char** argv) {
  return ubersim::run_main("ubersim_config_check", [&] { return parse_and_run(argc, argv); });
}
