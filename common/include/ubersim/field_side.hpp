#pragma once
// The goal a team defends, as command lines and the Python module name it:
// "negative" (the goal at -x) or "positive" (+x). The one parser of it, so
// every program accepts the same words.
#include <stdexcept>
#include <string>
#include <vector>

namespace ubersim {

// The accepted words, for a command-line check: ->check(CLI::IsMember(kDefendedSides)).
inline const std::vector<std::string> kDefendedSides{"negative", "positive"};

// -1 for "negative", +1 for "positive". Throws std::invalid_argument for
// anything else (pybind11 turns it into ValueError).
inline int parse_defended_side(const std::string& text) {
  if (text == kDefendedSides[0]) return -1;
  if (text == kDefendedSides[1]) return 1;
  throw std::invalid_argument("the side a team defends: expected negative or positive, got '" +
                              text + "'");
}

}  // namespace ubersim
