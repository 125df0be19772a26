#include "ubersim/viewer/request_policy.hpp"

#include <algorithm>
#include <cctype>

namespace ubersim::viewer {
namespace {

bool ends_with(const std::string& text, const std::string& suffix) {
  return text.size() >= suffix.size() &&
         text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

std::string lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

// "localhost:8080", "127.0.0.1", "[::1]:8080" -> true.
bool loopback_host(const std::string& host) {
  std::string name = lower(host);
  if (!name.empty() && name[0] == '[') {
    return name.compare(0, 5, "[::1]") == 0 && (name.size() == 5 || name[5] == ':');
  }
  name = name.substr(0, name.find(':'));
  if (name == "localhost") return true;
  // 127.0.0.0/8, written as a dotted quad of digits.
  if (name.compare(0, 4, "127.") != 0) return false;
  return std::all_of(name.begin(), name.end(), [](char c) {
    return c == '.' || std::isdigit(static_cast<unsigned char>(c));
  });
}

}  // namespace

HandshakeDecision decide_handshake(const std::string& origin, const std::string& host,
                                   bool loopback_bound,
                                   const std::vector<std::string>& allowed_origins,
                                   std::size_t open_pages, std::size_t max_pages) {
  if (open_pages >= max_pages) {
    return {false, 503,
            std::to_string(open_pages) + " pages already open (at most " +
                std::to_string(max_pages) + ")"};
  }
  if (origin.empty()) return {true, 0, ""};
  const std::string wanted = lower(origin);
  for (const std::string& allowed : allowed_origins) {
    if (allowed == "*" || lower(allowed) == wanted) return {true, 0, ""};
  }
  const bool same_origin =
      wanted == "http://" + lower(host) && (!loopback_bound || loopback_host(host));
  if (same_origin) return {true, 0, ""};
  return {false, 403,
          "WebSocket from origin '" + origin + "' (host '" + host +
              "') refused; start the viewer with --allow-origin to let it in"};
}

bool json_depth_within(const std::string& text, int max_depth) {
  int depth = 0;
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\') {
        ++i;  // the escaped character cannot end the string
      } else if (c == '"') {
        in_string = false;
      }
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > max_depth) return false;
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return true;
}

std::string content_type_for(const std::string& file_name) {
  if (ends_with(file_name, ".html")) return "text/html; charset=utf-8";
  if (ends_with(file_name, ".js")) return "text/javascript; charset=utf-8";
  if (ends_with(file_name, ".css")) return "text/css; charset=utf-8";
  if (ends_with(file_name, ".png")) return "image/png";
  if (ends_with(file_name, ".svg")) return "image/svg+xml";
  return "application/octet-stream";
}

std::string served_file_name(const std::string& request_path) {
  std::string path = request_path.substr(0, request_path.find_first_of("?#"));
  if (path.empty() || path[0] != '/') return "";
  path.erase(0, 1);
  if (path.empty()) return "index.html";
  // Plain file names only: nothing outside the web folder can be named.
  if (path[0] == '.') return "";
  for (char c : path) {
    const bool allowed = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') ||
                         (c >= '0' && c <= '9') || c == '_' || c == '-' || c == '.';
    if (!allowed) return "";
  }
  return path;
}

}  // namespace ubersim::viewer
