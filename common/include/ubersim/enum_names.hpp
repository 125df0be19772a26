#pragma once
// The words an enumeration is written as in config files and on command lines,
// one table per enumeration: parsing and naming both read it, so a value's
// word is written once.
//
//   inline constexpr EnumNames<Solver, 2> kSolverNames{{{"quickstep", Solver::QuickStep},
//                                                      {"exact", Solver::Exact}}};
//   config.choice("SOLVER", kSolverNames);   // ConfigError: expected 'quickstep' or 'exact'
//   enum_name(Solver::Exact, kSolverNames);  // "exact"
#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace ubersim {

template <class Enum>
struct EnumName {
  const char* name;
  Enum value;
};
template <class Enum, std::size_t N>
using EnumNames = std::array<EnumName<Enum>, N>;

template <class Enum, std::size_t N>
std::optional<Enum> parse_enum(std::string_view text, const EnumNames<Enum, N>& names) {
  for (const auto& entry : names)
    if (text == entry.name) return entry.value;
  return std::nullopt;
}

template <class Enum, std::size_t N>
const char* enum_name(Enum value, const EnumNames<Enum, N>& names) {
  for (const auto& entry : names)
    if (entry.value == value) return entry.name;
  return "?";
}

// "'a', 'b' or 'c'", for an error message.
template <class Enum, std::size_t N>
std::string enum_choices(const EnumNames<Enum, N>& names) {
  std::string out;
  for (std::size_t i = 0; i < N; ++i) {
    if (i > 0) out += i + 1 == N ? " or " : ", ";
    out += "'" + std::string(names[i].name) + "'";
  }
  return out;
}

}  // namespace ubersim
