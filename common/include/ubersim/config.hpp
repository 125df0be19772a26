#pragma once
// Reader for ubersim's ASCII configuration format (after the ÜberSim paper):
//
//   # comment
//   NAME = v1 v2 ...   # values: reals, integers or strings (a vector of any non-zero length)
//   BASE = other.cfg   # optional first key: start from another file, then override its keys
//
// A file is parsed once into a ConfigFile; consumers read typed values out of it
// into plain structs and then call require_all_used(), which turns every key
// nobody asked for into an error that names its file and line. So a typo in a
// key is an error, never silently ignored; and where a key the reader looked
// for is missing and a key nobody asked for is spelt nearly like it, the error
// names that key's line and suggests the right name.
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "ubersim/enum_names.hpp"

namespace ubersim {

// Every config problem: message already carries "file:line: ".
class ConfigError : public std::runtime_error {
 public:
  ConfigError(std::string file, int line, const std::string& what);
  const std::string& file() const { return file_; }
  int line() const { return line_; }  // 0 when the problem is the file as a whole

 private:
  std::string file_;
  int line_;
};

struct ConfigEntry {
  std::vector<std::string> values;  // raw tokens, quotes removed
  std::string file;                 // where it was defined (the overriding file wins)
  int line = 0;
};

class ConfigFile {
 public:
  // Parses `path` (and its BASE chain). Throws ConfigError.
  static ConfigFile load(const std::filesystem::path& path);
  // Parses text as if it were the file `name` (for tests and embedded defaults).
  static ConfigFile parse(const std::string& text, const std::string& name);

  const std::string& path() const { return path_; }
  bool has(const std::string& key) const;
  std::vector<std::string> keys() const;

  double real(const std::string& key) const;
  double real(const std::string& key, double fallback) const;
  // A real that must lie in [min, max].
  double real_in(const std::string& key, double min, double max) const;
  std::vector<double> reals(const std::string& key, std::optional<std::size_t> length = {}) const;

  std::int64_t integer(const std::string& key) const;
  std::int64_t integer(const std::string& key, std::int64_t fallback) const;
  // An integer that must lie in [min, max].
  std::int64_t integer_in(const std::string& key, std::int64_t min, std::int64_t max) const;
  std::vector<std::int64_t> integers(const std::string& key,
                                     std::optional<std::size_t> length = {}) const;

  std::string string(const std::string& key) const;
  std::string string(const std::string& key, const std::string& fallback) const;
  std::vector<std::string> strings(const std::string& key,
                                   std::optional<std::size_t> length = {}) const;

  // true/false, yes/no, on/off, 1/0.
  bool boolean(const std::string& key) const;
  bool boolean(const std::string& key, bool fallback) const;

  // Where a key was defined, for error messages of consumers ("file:line").
  std::string where(const std::string& key) const;
  // A ConfigError located at `key`'s definition.
  [[noreturn]] void fail(const std::string& key, const std::string& what) const;

  // One word of an enumeration's table (enum_names.hpp); another word fails
  // with the words it accepts.
  template <class Enum, std::size_t N>
  Enum choice(const std::string& key, const EnumNames<Enum, N>& names) const {
    const std::string text = string(key);
    if (const std::optional<Enum> value = parse_enum(text, names)) return *value;
    fail(key, "expected " + enum_choices(names) + ", got '" + text + "'");
  }

  // Throws ConfigError naming the first key (in file order) no accessor has read.
  void require_all_used() const;

 private:
  const ConfigEntry& entry(const std::string& key, const char* expected) const;
  const ConfigEntry& entry_of_length(const std::string& key, const char* expected,
                                     std::optional<std::size_t> length) const;
  void parse_into(const std::string& text, const std::string& name,
                  std::vector<std::string>& base_chain);
  // The defined key, nobody has asked for, spelt most nearly like `wanted`.
  std::optional<std::string> unasked_key_like(const std::string& wanted) const;
  // The key looked for but not defined, spelt most nearly like `unknown`.
  std::optional<std::string> missing_key_like(const std::string& unknown) const;

  std::string path_;
  std::map<std::string, ConfigEntry> entries_;
  std::vector<std::string> order_;  // keys in definition order, for stable errors
  mutable std::map<std::string, bool> used_;
  mutable std::set<std::string> asked_;  // every key looked for, found or not
};

}  // namespace ubersim
