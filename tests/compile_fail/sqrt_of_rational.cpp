// Must NOT compile: Gmpq has no square root, and nt::sqrt says so at compile time.
#include "certcyl/number_traits.hpp"

int main() {
  const CGAL::Gmpq two(2);
  return certcyl::nt::sign(certcyl::nt::sqrt(two)) == CGAL::POSITIVE ? 0 : 1;
}
