#pragma once
// Names of enumerated options: one table per enum serves reading a name (with its aliases) and
// printing it, so that the two cannot disagree.
#include <initializer_list>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "dresskit/mesh/errors.h"

namespace dresskit {

/// "1 vertex", "2 vertices": a count and the noun it counts, singular for one.
inline std::string counted(long long n, const char* one, const char* many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

/// (name, value) pairs; a value's first name is the one printed, later ones are aliases.
template <typename E>
using NameTable = std::initializer_list<std::pair<const char*, E>>;

/// The value named `text`. Throws InputError "<what>: '<text>' is not a, b or c" (each value's
/// first name) otherwise.
template <typename E>
E parse_name(const std::string& text, NameTable<E> names, const std::string& what) {
  for (const auto& [name, value] : names)
    if (text == name) return value;
  std::vector<std::string> first;
  std::vector<E> seen;
  for (const auto& [name, value] : names) {
    bool known = false;
    for (const E& s : seen) known = known || s == value;
    if (known) continue;
    seen.push_back(value);
    first.emplace_back(name);
  }
  std::string list;
  for (std::size_t k = 0; k < first.size(); ++k)
    list += (k == 0 ? "" : k + 1 == first.size() ? " or " : ", ") + first[k];
  throw InputError(what + ": '" + text + "' is not " + list);
}

/// The number `text` spells out in full (std::stod on the whole text: no trailing characters), or
/// nothing for an empty text, a text that is not a number or one out of range.
inline std::optional<double> parse_number(const std::string& text) {
  std::size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    return std::nullopt;
  }
  if (used != text.size()) return std::nullopt;
  return value;
}

/// The value's first name in the table ("?" for a value it lacks).
template <typename E>
std::string name_of(E value, NameTable<E> names) {
  for (const auto& [name, v] : names)
    if (v == value) return name;
  return "?";
}

}  // namespace dresskit
