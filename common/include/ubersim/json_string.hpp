#pragma once
// A JSON string literal of any text: quotes, backslashes and control characters
// escaped. For the few JSON lines the tools write by hand (event logs, dumps).
#include <cstdio>
#include <string>

namespace ubersim {

inline std::string json_string(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char buffer[8];
      std::snprintf(buffer, sizeof buffer, "\\u%04x", c);
      out += buffer;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

}  // namespace ubersim
