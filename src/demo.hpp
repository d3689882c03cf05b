// The built-in demo: a few queries of each kind, answered in every number type, side by side.
#pragma once

#include <ostream>

namespace certcyl::cli {

// Prints the demo table to `out`; returns 0, or 1 when an exact number type disagreed with
// another exact one (which would be a bug).
int run_demo(std::ostream& out);

}  // namespace certcyl::cli
