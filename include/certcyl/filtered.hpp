// certcyl/filtered.hpp -- the one place where interval filters fall back to exact arithmetic.
//
// A filtered predicate is a generic callable `p.template operator()<NT>()` returning a value
// that does not depend on NT (a sign, an enum, a small struct of them). `filtered_call` runs it
// in CGAL::Interval_nt<false> under upward FPU rounding; if any comparison is undecided
// (CGAL::Uncertain_conversion_exception), it runs it again in the exact type `Exact`
// (CGAL::Gmpq by default) and counts the fall-back. Decided interval comparisons are always
// right, so the answer is the exact one either way.
#pragma once

#include <CGAL/FPU.h>
#include <CGAL/Gmpq.h>
#include <CGAL/Interval_nt.h>
#include <CGAL/Uncertain.h>

#include <cstdint>

namespace certcyl {

// How often a filtered predicate ran, and how often it needed exact arithmetic.
struct FilterCounter {
  std::uint64_t calls = 0;
  std::uint64_t exact = 0;

  FilterCounter& operator+=(const FilterCounter& o) {
    calls += o.calls;
    exact += o.exact;
    return *this;
  }
};

template <class Exact = CGAL::Gmpq, class Predicate>
auto filtered_call(Predicate&& p, FilterCounter& counter) {
  ++counter.calls;
  {
    CGAL::Protect_FPU_rounding<true> upward;
    try {
      return p.template operator()<CGAL::Interval_nt<false>>();
    } catch (const CGAL::Uncertain_conversion_exception&) {
      // else: the intervals could not decide; fall through to exact arithmetic.
    }
  }
  ++counter.exact;
  return p.template operator()<Exact>();
}

}  // namespace certcyl
