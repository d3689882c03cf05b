// certcyl/io/json_input.hpp -- reading exact input from JSON (nlohmann-json).
//
// Numbers (design note, section 1):
//   a JSON number      its binary64 value (integers too: 9007199254740993 reads as 2^53);
//                      non-finite values (a literal such as 1e400 overflows) are rejected
//   a JSON string      the exact rational it spells: "p/q", decimal "0.1", hexfloat "0x1.8p-3"
//                      (grammar in certcyl/rational.hpp), of at most kMaxExactBits bits of
//                      numerator and denominator together (larger ones are an error)
// The reader remembers whether every number it read was exactly a binary64 value, so a
// floating-point kernel can report that it saw rounded input.
//
// Operands:
//   point / vector      [x, y, z]
//   cylinder            {"p0": P, "p1": P, "radius": r}
//                    or {"center": P, "axis": V, "radius": r, "height": h}   (seeds' form,
//                       converted exactly as certcyl/primitives.hpp documents)
//   elliptic_cylinder   {"base": P, "a": V, "b": V, "c": V}
//   line, ray           {"origin": P, "direction": V}
//   segment             {"p0": P, "p1": P}
//   triangle            [P, P, P]
// Every error is an InvalidInput whose field is the dotted path given by the caller plus the
// member ("a.radius", "triangle[1][2]"). Unknown members of an operand object are rejected,
// listing the valid names ("l.orgin: unexpected member (expected: origin, direction)"), so a
// misspelt key is not silently ignored.
#pragma once

#include <nlohmann/json.hpp>

#include <cmath>
#include <initializer_list>
#include <string>

#include "certcyl/errors.hpp"
#include "certcyl/primitives.hpp"
#include "certcyl/rational.hpp"

namespace certcyl {

// The largest exact number the reader accepts, in bits of numerator and denominator together:
// the exact stages' cost grows with the operands' size, and this bounds the time of one query.
inline constexpr long kMaxExactBits = 65536;

// Bits of numerator and denominator of q.
inline long exact_bits(const Rational& q) {
  return static_cast<long>(mpz_sizeinbase(q.numerator().mpz(), 2) + mpz_sizeinbase(q.denominator().mpz(), 2));
}

class JsonReader {
 public:
  using json = nlohmann::json;

  // True when every number read so far was exactly a binary64 value.
  bool all_binary64() const { return all_binary64_; }

  ExactValue number(const json& j, const std::string& field) {
    ExactValue v = read_number(j, field);
    all_binary64_ = all_binary64_ && v.is_binary64;
    return v;
  }

  Vec3<Rational> vec3(const json& j, const std::string& field) {
    if (!j.is_array()) throw InvalidInput(field, "expected an array of 3 numbers, got " + kind(j));
    if (j.size() != 3) throw InvalidInput(field, "expected an array of 3 numbers, got " + std::to_string(j.size()) + " elements");
    return {number(j[0], index_field(field, 0)).value, number(j[1], index_field(field, 1)).value,
            number(j[2], index_field(field, 2)).value};
  }

  Cylinder<Rational> cylinder(const json& j, const std::string& field) {
    expect_object(j, field);
    Cylinder<Rational> c;
    if (j.contains("p0") || j.contains("p1")) {
      only_members(j, field, {"p0", "p1", "radius"}, "(endpoint form: p0, p1, radius)");
      c = {vec3(member(j, field, "p0"), join_field(field, "p0")), vec3(member(j, field, "p1"), join_field(field, "p1")),
           number(member(j, field, "radius"), join_field(field, "radius")).value};
    } else if (j.contains("center") || j.contains("axis") || j.contains("height")) {
      only_members(j, field, {"center", "axis", "radius", "height"}, "(center form: center, axis, radius, height)");
      const Vec3<Rational> C = vec3(member(j, field, "center"), join_field(field, "center"));
      const Vec3<Rational> W = vec3(member(j, field, "axis"), join_field(field, "axis"));
      const Rational r = number(member(j, field, "radius"), join_field(field, "radius")).value;
      const Rational h = number(member(j, field, "height"), join_field(field, "height")).value;
      validate_center_axis(W, r, h, field);
      c = Cylinder<Rational>::from_center_axis(C, W, r, h);
    } else {
      throw InvalidInput(field, "expected a cylinder: {\"p0\", \"p1\", \"radius\"} or {\"center\", \"axis\", \"radius\", \"height\"}");
    }
    validate(c, field);
    return c;
  }

  EllipticCylinder<Rational> elliptic_cylinder(const json& j, const std::string& field) {
    expect_object(j, field);
    only_members(j, field, {"base", "a", "b", "c"}, "");
    EllipticCylinder<Rational> e{vec3(member(j, field, "base"), join_field(field, "base")),
                                 vec3(member(j, field, "a"), join_field(field, "a")),
                                 vec3(member(j, field, "b"), join_field(field, "b")),
                                 vec3(member(j, field, "c"), join_field(field, "c"))};
    validate(e, field);
    return e;
  }

  Line<Rational> line(const json& j, const std::string& field) { return origin_direction<Line<Rational>>(j, field); }
  Ray<Rational> ray(const json& j, const std::string& field) { return origin_direction<Ray<Rational>>(j, field); }

  Segment<Rational> segment(const json& j, const std::string& field) {
    expect_object(j, field);
    only_members(j, field, {"p0", "p1"}, "");
    Segment<Rational> s{vec3(member(j, field, "p0"), join_field(field, "p0")), vec3(member(j, field, "p1"), join_field(field, "p1"))};
    validate(s, field);
    return s;
  }

  Triangle<Rational> triangle(const json& j, const std::string& field) {
    if (!j.is_array()) throw InvalidInput(field, "expected an array of 3 points, got " + kind(j));
    if (j.size() != 3) throw InvalidInput(field, "expected an array of 3 points, got " + std::to_string(j.size()) + " elements");
    return {{vec3(j[0], index_field(field, 0)), vec3(j[1], index_field(field, 1)), vec3(j[2], index_field(field, 2))}};
  }

  // The member `name` of object j, or an InvalidInput naming the missing field.
  static const json& member(const json& j, const std::string& field, const char* name) {
    auto it = j.find(name);
    if (it == j.end()) throw InvalidInput(join_field(field, name), "missing");
    return *it;
  }

  // A short description of a JSON value's kind for error messages.
  static std::string kind(const json& j) {
    switch (j.type()) {
      case json::value_t::null: return "null";
      case json::value_t::object: return "an object";
      case json::value_t::array: return "an array";
      case json::value_t::string: return "a string";
      case json::value_t::boolean: return "a boolean";
      case json::value_t::number_integer:
      case json::value_t::number_unsigned:
      case json::value_t::number_float: return "a number";
      case json::value_t::binary: return "binary data";
      case json::value_t::discarded: return "an invalid value";
    }
    return "an unknown value";
  }

  // One number, without touching the binary64 flag.
  static ExactValue read_number(const json& j, const std::string& field) {
    switch (j.type()) {
      case json::value_t::number_float: {
        const double d = j.get<double>();
        if (!std::isfinite(d)) throw InvalidInput(field, "non-finite number");
        return {Rational(d), true};
      }
      case json::value_t::number_integer:
        // The nearest binary64, as for any JSON number (exact up to 2^53).
        return {Rational(static_cast<double>(j.get<std::int64_t>())), true};
      case json::value_t::number_unsigned:
        return {Rational(static_cast<double>(j.get<std::uint64_t>())), true};
      case json::value_t::string: {
        Rational q = parse_rational(j.get_ref<const std::string&>(), field);
        if (const long bits = exact_bits(q); bits > kMaxExactBits)
          throw InvalidInput(field, "exact number of " + std::to_string(bits) + " bits (numerator and denominator); the limit is " +
                                        std::to_string(kMaxExactBits) + " (about 19,700 decimal digits)");
        const bool b64 = is_binary64(q);
        return {std::move(q), b64};
      }
      default:
        throw InvalidInput(field, "expected a number or a string holding an exact number, got " + kind(j));
    }
  }

 private:
  template <class P>
  P origin_direction(const json& j, const std::string& field) {
    expect_object(j, field);
    only_members(j, field, {"origin", "direction"}, "");
    P p{vec3(member(j, field, "origin"), join_field(field, "origin")),
        vec3(member(j, field, "direction"), join_field(field, "direction"))};
    validate(p, field);
    return p;
  }

  static void expect_object(const json& j, const std::string& field) {
    if (!j.is_object()) throw InvalidInput(field, "expected an object, got " + kind(j));
  }

  static void only_members(const json& j, const std::string& field, std::initializer_list<const char*> allowed,
                           const std::string& hint) {
    for (auto it = j.begin(); it != j.end(); ++it) {
      bool known = false;
      for (const char* a : allowed) known = known || it.key() == a;
      if (known) continue;
      // The valid names: the caller's hint when the object has several forms, else the list.
      std::string names;
      for (const char* a : allowed) names += (names.empty() ? "" : ", ") + std::string(a);
      throw InvalidInput(join_field(field, it.key()), "unexpected member " + (hint.empty() ? "(expected: " + names + ")" : hint));
    }
  }

  bool all_binary64_ = true;
};

}  // namespace certcyl
