#pragma once
// What the physics benchmarks share: the machine's load, printed beside
// figures measured on a shared machine, and the baseline they divide by,
// physics alone. (Their work folder is the tests' TempFolder,
// tests/support/temp_folder.hpp.)
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "ubersim/child_process.hpp"

namespace ubersim::physics::bench {

// "1.23 1.10 0.98": the load averages over 1, 5 and 15 minutes.
inline std::string load_average() {
  std::ifstream in("/proc/loadavg");
  std::string one, five, fifteen;
  in >> one >> five >> fifteen;
  return one + " " + five + " " + fifteen;
}

inline std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// The folder this bench was built into (build/bin), and a program beside it.
inline std::filesystem::path bench_dir() {
  return std::filesystem::read_symlink("/proc/self/exe").parent_path();
}
inline std::string bench_program(const std::string& name) {
  return (bench_dir() / name).string();
}

inline double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n == 0 ? 0 : n % 2 == 1 ? values[n / 2] : (values[n / 2 - 1] + values[n / 2]) / 2;
}

// The baseline of the benches: ubersim_physics_bench's server figure (sim s
// per wall s, SIM_STATE every step on the in-process bus) for one scenario
// with `model` ("jointed" or "planar") drive, run in `work`.
inline double physics_alone(const std::string& scenario, const std::string& model, double seconds,
                            const std::filesystem::path& work) {
  const std::filesystem::path out = work / ("alone_" + scenario + "_" + model + ".txt");
  ChildProcess bench(
      {bench_program("ubersim_physics_bench"), "--scenarios", scenario, "--models", model, "--only",
       "server", "--repeat", "1", "--seconds", std::to_string(seconds)},
      out.string());
  if (bench.wait(600) != 0) {
    throw std::runtime_error("ubersim_physics_bench failed: " + bench.log());
  }
  std::smatch match;
  const std::string text = read_file(out);
  if (!std::regex_search(text, match, std::regex(scenario + R"(\s+\S+\s+\S+\s+([0-9.]+))"))) {
    throw std::runtime_error("no figure in: " + text);
  }
  return std::stod(match[1]);
}

}  // namespace ubersim::physics::bench
