#include "ubersim/process_main.hpp"

#include <spdlog/spdlog.h>

#include <cstdio>
#include <exception>

#include "ubersim/config.hpp"

namespace ubersim {

int run_main(const char* program, const std::function<int()>& body) {
  try {
    return body();
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
