#include "ubersim/process_main.hpp"

#include <cstdio>
#include <exception>

#include "ubersim/cli.hpp"
#include "ubersim/config.hpp"
#include "ubersim/spdlog.hpp"

namespace ubersim {

int run_main(const char* program, const std::function<int()>& body) {
  try {
    return body();
  } catch (const CLI::ParseError& error) {
    // A command line parsed outside parse_command_line: the same one line, exit 2.
    std::fprintf(stderr, "%s\n", command_line_error(program, error).c_str());
    return 2;
  } catch (const ConfigError& error) {
    spdlog::error("configuration: {}", error.what());
    return 2;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "%s: %s\n", program, error.what());
  } catch (...) {
    std::fprintf(stderr, "%s: unknown error\n", program);
  }
  return 1;
}

}  // namespace ubersim
