#pragma once
// The one place that decides what an ubersim program's exit code says and how
// an error that escapes it is reported.
#include <functional>

namespace ubersim {

// Runs a program's body (parse the command line, set up logging, run) and
// returns its exit code: what the body returns (0 = a clean stop), 2 for a
// bad command line (one line on stderr, see parse_command_line in cli.hpp) or
// a configuration error (logged: the message names file, line and what was
// expected), 1 for anything else (written to stderr after the program's name,
// since the error may come before logging is set up). Nothing escapes it.
int run_main(const char* program, const std::function<int()>& body);

}  // namespace ubersim
