// certcyl/vec3.hpp -- a small 3-vector over any certcyl number type.
//
// Why not Eigen::Matrix<NT,3,1>: Eigen's expression templates keep references to temporaries
// (fatal with `auto` and CORE::Expr or Lazy_exact_nt), need a NumTraits specialisation per
// type, and bring nothing to 3-vectors. Geometry uses this type; Eigen is used where there is
// real linear algebra (the double-precision solvers), on double.
#pragma once

#include <array>
#include <cstddef>

namespace certcyl {

template <class NT>
struct Vec3 {
  NT x, y, z;

  const NT& operator[](std::size_t i) const { return i == 0 ? x : (i == 1 ? y : z); }
  NT& operator[](std::size_t i) { return i == 0 ? x : (i == 1 ? y : z); }

  // Applies f to each coordinate: the way vectors change number type.
  template <class F>
  auto map(F&& f) const -> Vec3<decltype(f(x))> {
    return {f(x), f(y), f(z)};
  }

  friend Vec3 operator+(const Vec3& a, const Vec3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
  friend Vec3 operator-(const Vec3& a, const Vec3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
  friend Vec3 operator-(const Vec3& a) { return {-a.x, -a.y, -a.z}; }
  friend Vec3 operator*(const NT& s, const Vec3& a) { return {s * a.x, s * a.y, s * a.z}; }
  friend Vec3 operator*(const Vec3& a, const NT& s) { return {a.x * s, a.y * s, a.z * s}; }
  friend Vec3 operator/(const Vec3& a, const NT& s) { return {a.x / s, a.y / s, a.z / s}; }
  Vec3& operator+=(const Vec3& b) { return *this = *this + b; }
  Vec3& operator-=(const Vec3& b) { return *this = *this - b; }

  // Coordinate-wise identity; meaningful for exact types (tests, exact checks).
  friend bool operator==(const Vec3& a, const Vec3& b) { return a.x == b.x && a.y == b.y && a.z == b.z; }
};

template <class NT>
NT dot(const Vec3<NT>& a, const Vec3<NT>& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}

template <class NT>
Vec3<NT> cross(const Vec3<NT>& a, const Vec3<NT>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

template <class NT>
NT squared_length(const Vec3<NT>& a) {
  return dot(a, a);
}

// Determinant of the matrix with columns a, b, c: dot(a, cross(b, c)).
template <class NT>
NT determinant(const Vec3<NT>& a, const Vec3<NT>& b, const Vec3<NT>& c) {
  return dot(a, cross(b, c));
}

}  // namespace certcyl
