// A project outside certcyl's tree, built against the installed package.
#include <certcyl/certcyl.hpp>

#include <iostream>

int main() {
  using namespace certcyl;
  // Exact input: the point (1/2, 0, 1) lies on the wall of the cylinder of radius 1/2 around
  // the z axis from z = 0 to z = 2.
  const Cylinder<Rational> cyl{{0, 0, 0}, {0, 0, 2}, parse_rational("1/2")};
  const Point3<Rational> x{parse_rational("0.5"), 0, 1};
  const Side side = classify_point(x, cyl);
  std::cout << "consumer: " << to_string(side) << "\n";
  return side == Side::boundary ? 0 : 1;
}
