// certcyl/errors.hpp -- the typed errors raised at the input boundary.
//
// Every input is validated once, where it enters the library (the JSON reader or the
// primitives' `validate`), and rejected with an `InvalidInput` whose message starts with the
// dotted path of the offending field ("a.radius", "triangle[2][1]", ...). Algorithms behind
// the boundary assume valid input and never re-check it.
#pragma once

#include <stdexcept>
#include <string>
#include <utility>

namespace certcyl {

class InvalidInput : public std::invalid_argument {
 public:
  InvalidInput(std::string field, const std::string& what)
      : std::invalid_argument(field.empty() ? what : field + ": " + what), field_(std::move(field)) {}

  // The dotted path of the offending field; empty when the whole input is at fault.
  const std::string& field() const noexcept { return field_; }

 private:
  std::string field_;
};

// Joins a field path and a member name: join_field("a", "radius") == "a.radius".
inline std::string join_field(const std::string& parent, const std::string& member) {
  return parent.empty() ? member : parent + "." + member;
}

// Joins a field path and an index: index_field("triangle", 2) == "triangle[2]".
inline std::string index_field(const std::string& parent, std::size_t i) {
  return parent + "[" + std::to_string(i) + "]";
}

}  // namespace certcyl
