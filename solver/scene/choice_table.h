// The machinery of the scene's named choices (choices.h): a table of
// names per enumeration, declared as a specialisation of choices<E>() next
// to the enumeration and defined with SIMSOLS_CHOICES in one .cpp; the
// readers and writers look names up with choice_name(), parse_choice() and
// choice_names().
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace simsols {

template <class E>
struct Named {
  E value;
  const char* name;
};

// One table per enumeration.
template <class E>
std::span<const Named<E>> choices();

// The name of `value` ("?" for a value outside the table).
template <class E>
const char* choice_name(E value) {
  for (const Named<E>& c : choices<E>())
    if (c.value == value) return c.name;
  return "?";
}

// The value named `name`, or nullopt.
template <class E>
std::optional<E> parse_choice(std::string_view name) {
  for (const Named<E>& c : choices<E>())
    if (name == c.name) return c.value;
  return std::nullopt;
}

// Every allowed name, in the table's order.
template <class E>
std::vector<std::string> choice_names() {
  std::vector<std::string> names;
  for (const Named<E>& c : choices<E>()) names.emplace_back(c.name);
  return names;
}

// Every allowed name joined by '|' ("rigid|membrane"), as messages list them.
template <class E>
std::string choice_names_joined() {
  std::string s;
  for (const Named<E>& c : choices<E>()) s += (s.empty() ? "" : "|") + std::string(c.name);
  return s;
}

}  // namespace simsols

// Defines the table of enumeration E, inside namespace simsols:
// SIMSOLS_CHOICES(E, {E::A, "a"}, ...).
#define SIMSOLS_CHOICES(E, ...)                         \
  template <>                                           \
  std::span<const Named<E>> choices() {                 \
    static const Named<E> table[] = {__VA_ARGS__};      \
    return table;                                       \
  }
