// A project outside certcyl's tree, built against the installed package: one include, and a
// query of each certified kind, each answer known by hand.
#include <certcyl/certcyl.hpp>

#include <iostream>
#include <string>

int main() {
  using namespace certcyl;
  int failures = 0;
  const auto expect = [&failures](const char* what, bool ok) {
    std::cout << "consumer: " << what << (ok ? " ok" : " WRONG") << "\n";
    failures += ok ? 0 : 1;
  };
  // The point (1/2, 0, 1) lies on the wall of the cylinder of radius 1/2 around the z axis from
  // z = 0 to z = 2.
  const Cylinder<Rational> cyl{{0, 0, 0}, {0, 0, 2}, parse_rational("1/2")};
  const Point3<Rational> x{parse_rational("0.5"), 0, 1};
  expect("point on the wall", classify_point(x, cyl) == Side::boundary);
  // The line y = 1/2, z = 1 (direction x) is tangent to that wall at (0, 1/2, 1).
  const Line<Rational> tangent{{0, parse_rational("1/2"), 1}, {1, 0, 0}};
  expect("tangent line", certified_line_cylinder(tangent, cyl).answer == Answer::touching);
  // A cylinder of radius 1/2 along the x axis at height 3: above the first, 1 apart.
  const Cylinder<double> a{{0, 0, 0}, {0, 0, 2}, 0.5}, b{{-1, 0, 3}, {1, 0, 3}, 0.5};
  expect("separated pair", certified_cylinder_cylinder(a, b).answer == Answer::separated);
  // The same cylinder lowered to rest on the first one's top cap (its wall at z = 2).
  const Cylinder<double> c{{-1, 0, 2.5}, {1, 0, 2.5}, 0.5};
  expect("touching pair", certified_cylinder_cylinder(a, c).answer == Answer::touching);
  // A triangle through the axis, in Rational and in double.
  const Triangle<Rational> t{{Point3<Rational>{-1, 0, 1}, Point3<Rational>{1, 0, 1}, Point3<Rational>{0, 1, 1}}};
  expect("triangle through the axis", certified_triangle_cylinder(t, cyl).answer == Answer::overlapping);
  const Triangle<double> td{{Point3<double>{-1, 0, 1}, Point3<double>{1, 0, 1}, Point3<double>{0, 1, 1}}};
  expect("triangle through the axis (double)", certified_triangle_cylinder(td, a).answer == Answer::overlapping);
  // The point on the wall, by the certified point query; then a cylinder of radius -1, rejected.
  expect("certified point on the wall", certified_point_cylinder(x, cyl).answer == Answer::touching);
  std::string error;
  try {
    certified_point_cylinder(Point3<double>{0, 0, 1}, Cylinder<double>{{0, 0, 0}, {0, 0, 2}, -1});
  } catch (const InvalidInput& e) {
    error = e.what();
  }
  expect("negative radius rejected", error == "cylinder.radius: must be positive, got -1");
  return failures == 0 ? 0 : 1;
}
