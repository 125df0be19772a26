#include "ubersim/config.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "ubersim/config_text.hpp"

namespace ubersim {
namespace {

std::string location(const std::string& file, int line) {
  return line > 0 ? file + ":" + std::to_string(line) : file;
}

bool valid_key(const std::string& key) {
  if (key.empty() || !(std::isalpha(static_cast<unsigned char>(key[0])) || key[0] == '_')) {
    return false;
  }
  return std::all_of(key.begin(), key.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
  });
}

// Splits the value part of a line into tokens; "quoted strings" may hold spaces.
// Stops at an unquoted '#'. Throws on an unterminated quote.
std::vector<std::string> tokenize(const std::string& text, const std::string& file, int line) {
  std::vector<std::string> tokens;
  std::size_t i = 0;
  while (i < text.size()) {
    const char c = text[i];
    if (std::isspace(static_cast<unsigned char>(c))) {
      ++i;
    } else if (c == '#') {
      break;
    } else if (c == '"') {
      const std::size_t end = text.find('"', i + 1);
      if (end == std::string::npos) {
        throw ConfigError(file, line, "unterminated string: expected a closing '\"'");
      }
      tokens.push_back(text.substr(i + 1, end - i - 1));
      i = end + 1;
    } else {
      std::size_t end = i;
      while (end < text.size() && !std::isspace(static_cast<unsigned char>(text[end])) &&
             text[end] != '#') {
        ++end;
      }
      tokens.push_back(text.substr(i, end - i));
      i = end;
    }
  }
  return tokens;
}

std::optional<double> parse_real(const std::string& token) {
  if (token.empty()) return std::nullopt;
  errno = 0;
  char* end = nullptr;
  const double value = std::strtod(token.c_str(), &end);
  if (end != token.c_str() + token.size() || errno == ERANGE || !std::isfinite(value)) {
    return std::nullopt;
  }
  return value;
}

std::optional<std::int64_t> parse_integer(const std::string& token) {
  if (token.empty()) return std::nullopt;
  errno = 0;
  char* end = nullptr;
  const long long value = std::strtoll(token.c_str(), &end, 10);
  if (end != token.c_str() + token.size() || errno == ERANGE) return std::nullopt;
  return static_cast<std::int64_t>(value);
}

std::optional<bool> parse_boolean(std::string token) {
  std::transform(token.begin(), token.end(), token.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (token == "true" || token == "yes" || token == "on" || token == "1") return true;
  if (token == "false" || token == "no" || token == "off" || token == "0") return false;
  return std::nullopt;
}

// Config files are a few kB; a file of more than this is not one (and a BASE
// naming /dev/zero or a FIFO must not read forever).
constexpr std::uintmax_t kMaxConfigBytes = std::uintmax_t{1} << 20;

// Letters compared without case: 'gravity' is a misspelling of GRAVITY too.
bool same_letter(char a, char b) {
  return std::toupper(static_cast<unsigned char>(a)) == std::toupper(static_cast<unsigned char>(b));
}

// No key ubersim reads is longer; a longer one is no typo of any, and
// comparing it would cost length squared (a config file is outside input).
constexpr std::size_t kMaxComparedKey = 64;

// Edits (insert, delete, replace, swap two neighbours) that turn a into b.
std::size_t edit_distance(const std::string& a, const std::string& b) {
  const std::size_t width = b.size() + 1;
  std::vector<std::size_t> d((a.size() + 1) * width);
  const auto at = [&](std::size_t i, std::size_t j) -> std::size_t& { return d[i * width + j]; };
  for (std::size_t i = 0; i <= a.size(); ++i) at(i, 0) = i;
  for (std::size_t j = 0; j <= b.size(); ++j) at(0, j) = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t replace = same_letter(a[i - 1], b[j - 1]) ? 0 : 1;
      at(i, j) = std::min({at(i - 1, j) + 1, at(i, j - 1) + 1, at(i - 1, j - 1) + replace});
      if (i > 1 && j > 1 && same_letter(a[i - 1], b[j - 2]) && same_letter(a[i - 2], b[j - 1])) {
        at(i, j) = std::min(at(i, j), at(i - 2, j - 2) + 1);
      }
    }
  }
  return at(a.size(), b.size());
}

// Among `candidates`, the one spelt most nearly like `key`, if any is near
// enough to be a typo of it: one edit in a short key, two (three beyond ten
// letters) in a longer one. Ties go to the first candidate.
std::optional<std::string> nearest_spelling(const std::string& key,
                                            const std::vector<std::string>& candidates) {
  if (key.size() > kMaxComparedKey) return std::nullopt;
  const std::size_t limit = key.size() <= 4 ? 1 : key.size() <= 10 ? 2 : 3;
  std::optional<std::string> best;
  std::size_t best_distance = limit + 1;
  for (const std::string& candidate : candidates) {
    // Keys differ by more than the limit in length cannot be near; skip the table.
    const std::size_t length_gap = candidate.size() > key.size() ? candidate.size() - key.size()
                                                                 : key.size() - candidate.size();
    if (length_gap > limit) continue;
    const std::size_t distance = edit_distance(key, candidate);
    if (distance < best_distance) {
      best = candidate;
      best_distance = distance;
    }
  }
  return best;
}

std::string length_text(std::size_t n) {
  return std::to_string(n) + (n == 1 ? " value" : " values");
}

}  // namespace

std::string read_config_text(const std::filesystem::path& path) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) {
    throw ConfigError(path.string(), 0,
                      std::filesystem::exists(path, error)
                          ? "not a regular file: expected a config file"
                          : "cannot open config file");
  }
  const std::uintmax_t size = std::filesystem::file_size(path, error);
  if (error || size > kMaxConfigBytes) {
    throw ConfigError(path.string(), 0, "larger than 1 MiB: not a config file");
  }
  std::ifstream in(path);
  if (!in) throw ConfigError(path.string(), 0, "cannot open config file");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

ConfigError::ConfigError(std::string file, int line, const std::string& what)
    : std::runtime_error(location(file, line) + ": " + what), file_(std::move(file)), line_(line) {}

ConfigFile ConfigFile::load(const std::filesystem::path& path) {
  ConfigFile config;
  config.path_ = path.string();
  std::vector<std::string> chain;
  config.parse_into(read_config_text(path), path.string(), chain);
  return config;
}

ConfigFile ConfigFile::parse(const std::string& text, const std::string& name) {
  ConfigFile config;
  config.path_ = name;
  std::vector<std::string> chain;
  config.parse_into(text, name, chain);
  return config;
}

void ConfigFile::parse_into(const std::string& text, const std::string& name,
                            std::vector<std::string>& base_chain) {
  if (std::find(base_chain.begin(), base_chain.end(), name) != base_chain.end()) {
    throw ConfigError(name, 0, "BASE chain loops back to this file");
  }
  base_chain.push_back(name);

  std::map<std::string, int> defined_here;  // duplicates within one file are errors
  std::istringstream lines(text);
  std::string raw;
  int line_number = 0;
  bool seen_key = false;
  while (std::getline(lines, raw)) {
    ++line_number;
    if (!raw.empty() && raw.back() == '\r') raw.pop_back();
    const std::size_t first = raw.find_first_not_of(" \t");
    if (first == std::string::npos || raw[first] == '#') continue;

    const std::size_t equals = raw.find('=');
    const std::size_t hash = raw.find('#');
    if (equals == std::string::npos || (hash != std::string::npos && hash < equals)) {
      throw ConfigError(name, line_number, "expected 'NAME = value ...', found no '='");
    }
    std::string key = raw.substr(first, equals - first);
    key.erase(key.find_last_not_of(" \t") + 1);
    if (!valid_key(key)) {
      throw ConfigError(
          name, line_number,
          "expected a key of letters, digits and '_' before '=', found '" + key + "'");
    }
    std::vector<std::string> values = tokenize(raw.substr(equals + 1), name, line_number);
    if (values.empty()) {
      throw ConfigError(name, line_number, "key '" + key + "' has no value: expected at least one");
    }
    if (auto previous = defined_here.find(key); previous != defined_here.end()) {
      throw ConfigError(name, line_number,
                        "duplicate key '" + key + "' (first defined on line " +
                            std::to_string(previous->second) + ")");
    }
    defined_here[key] = line_number;

    if (key == "BASE") {
      if (seen_key) {
        throw ConfigError(name, line_number, "BASE must come before every other key");
      }
      if (values.size() != 1) {
        throw ConfigError(name, line_number, "BASE takes exactly one file name");
      }
      std::filesystem::path base = values[0];
      if (base.is_relative()) base = std::filesystem::path(name).parent_path() / base;
      try {
        parse_into(read_config_text(base), base.string(), base_chain);
      } catch (const ConfigError& error) {
        if (error.line() != 0 || error.file() != base.string()) throw;
        throw ConfigError(name, line_number, "BASE file '" + base.string() + "': " + error.what());
      }
      continue;
    }
    seen_key = true;
    if (entries_.find(key) == entries_.end()) order_.push_back(key);
    entries_[key] = ConfigEntry{std::move(values), name, line_number};
  }
  base_chain.pop_back();
}

bool ConfigFile::has(const std::string& key) const {
  asked_.insert(key);
  return entries_.count(key) != 0;
}

std::vector<std::string> ConfigFile::keys() const {
  return order_;
}

std::string ConfigFile::where(const std::string& key) const {
  const auto found = entries_.find(key);
  return found == entries_.end() ? path_ : location(found->second.file, found->second.line);
}

void ConfigFile::fail(const std::string& key, const std::string& what) const {
  const auto found = entries_.find(key);
  if (found == entries_.end()) throw ConfigError(path_, 0, key + ": " + what);
  throw ConfigError(found->second.file, found->second.line, key + ": " + what);
}

const ConfigEntry& ConfigFile::entry(const std::string& key, const char* expected) const {
  asked_.insert(key);
  const auto found = entries_.find(key);
  if (found == entries_.end()) {
    const std::string missing = "missing required key '" + key + "' (" + expected + ")";
    // Most often the key is there, misspelt: point at that line, which the
    // unknown-key check would only reach once this key were fixed.
    if (const auto typo = unasked_key_like(key)) {
      const ConfigEntry& e = entries_.at(*typo);
      throw ConfigError(e.file, e.line,
                        "unknown key '" + *typo + "': did you mean '" + key +
                            "'? (a required key: " + expected + ")");
    }
    throw ConfigError(path_, 0, missing);
  }
  used_[key] = true;
  return found->second;
}

const ConfigEntry& ConfigFile::entry_of_length(const std::string& key, const char* expected,
                                               std::optional<std::size_t> length) const {
  const ConfigEntry& e = entry(key, expected);
  if (length && e.values.size() != *length) {
    fail(key, "expected " + length_text(*length) + " (" + expected + "), got " +
                  std::to_string(e.values.size()));
  }
  return e;
}

std::vector<double> ConfigFile::reals(const std::string& key,
                                      std::optional<std::size_t> length) const {
  const ConfigEntry& e = entry_of_length(key, "real numbers", length);
  std::vector<double> out;
  out.reserve(e.values.size());
  for (const std::string& token : e.values) {
    const auto value = parse_real(token);
    if (!value) fail(key, "expected a real number, got '" + token + "'");
    out.push_back(*value);
  }
  return out;
}

double ConfigFile::real(const std::string& key) const {
  const ConfigEntry& e = entry_of_length(key, "a real number", 1);
  const auto value = parse_real(e.values[0]);
  if (!value) fail(key, "expected a real number, got '" + e.values[0] + "'");
  return *value;
}

double ConfigFile::real(const std::string& key, double fallback) const {
  return has(key) ? real(key) : fallback;
}

double ConfigFile::real_in(const std::string& key, double min, double max) const {
  const double value = real(key);
  if (value < min || value > max) {
    std::ostringstream what;
    what << "expected a real number in [" << min << ", " << max << "], got " << value;
    fail(key, what.str());
  }
  return value;
}

std::vector<std::int64_t> ConfigFile::integers(const std::string& key,
                                               std::optional<std::size_t> length) const {
  const ConfigEntry& e = entry_of_length(key, "integers", length);
  std::vector<std::int64_t> out;
  out.reserve(e.values.size());
  for (const std::string& token : e.values) {
    const auto value = parse_integer(token);
    if (!value) fail(key, "expected an integer, got '" + token + "'");
    out.push_back(*value);
  }
  return out;
}

std::int64_t ConfigFile::integer(const std::string& key) const {
  const ConfigEntry& e = entry_of_length(key, "an integer", 1);
  const auto value = parse_integer(e.values[0]);
  if (!value) fail(key, "expected an integer, got '" + e.values[0] + "'");
  return *value;
}

std::int64_t ConfigFile::integer(const std::string& key, std::int64_t fallback) const {
  return has(key) ? integer(key) : fallback;
}

std::int64_t ConfigFile::integer_in(const std::string& key, std::int64_t min,
                                    std::int64_t max) const {
  const std::int64_t value = integer(key);
  if (value < min || value > max) {
    fail(key, "expected an integer in [" + std::to_string(min) + ", " + std::to_string(max) +
                  "], got " + std::to_string(value));
  }
  return value;
}

std::vector<std::string> ConfigFile::strings(const std::string& key,
                                             std::optional<std::size_t> length) const {
  return entry_of_length(key, "strings", length).values;
}

std::string ConfigFile::string(const std::string& key) const {
  return entry_of_length(key, "one string", 1).values[0];
}

std::string ConfigFile::string(const std::string& key, const std::string& fallback) const {
  return has(key) ? string(key) : fallback;
}

bool ConfigFile::boolean(const std::string& key) const {
  const ConfigEntry& e = entry_of_length(key, "true or false", 1);
  const auto value = parse_boolean(e.values[0]);
  if (!value) fail(key, "expected true or false, got '" + e.values[0] + "'");
  return *value;
}

bool ConfigFile::boolean(const std::string& key, bool fallback) const {
  return has(key) ? boolean(key) : fallback;
}

void ConfigFile::require_all_used() const {
  for (const std::string& key : order_) {
    if (!used_.count(key)) {
      const ConfigEntry& e = entries_.at(key);
      const auto meant = missing_key_like(key);
      throw ConfigError(e.file, e.line,
                        "unknown key '" + key + "'" +
                            (meant ? ": did you mean '" + *meant + "'?" : std::string()));
    }
  }
}

std::optional<std::string> ConfigFile::unasked_key_like(const std::string& wanted) const {
  std::vector<std::string> unasked;
  for (const std::string& key : order_) {
    if (!used_.count(key) && !asked_.count(key)) unasked.push_back(key);
  }
  return nearest_spelling(wanted, unasked);
}

std::optional<std::string> ConfigFile::missing_key_like(const std::string& unknown) const {
  // Only keys looked for and absent: a key that is defined (CAMERA_0_... when
  // CAMERA_1_... is one camera too many) is not what a typo was meant to be.
  std::vector<std::string> missing;
  for (const std::string& key : asked_) {
    if (!entries_.count(key)) missing.push_back(key);
  }
  return nearest_spelling(unknown, missing);
}

}  // namespace ubersim
