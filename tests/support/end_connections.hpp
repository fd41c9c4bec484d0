#pragma once
// The element end connections the contact element's tests try (a member's "release" or
// "end_springs"), as flexibilities: 0 rigid, ∞ a hinge, else 1/k of a rotational spring. Shared
// by the force law's tests (connected_law) and the element's (its tangent with such ends).

#include <cmath>

namespace tsm::test {

struct Ends {
  double i, j;  // flexibilities: 0 rigid, ∞ hinge, else 1/k
};
inline constexpr Ends connections[] = {{INFINITY, 0.0}, {0.0, INFINITY}, {INFINITY, INFINITY},
                                       {0.4, 0.0},      {0.3, 0.7},      {INFINITY, 0.5}};

}  // namespace tsm::test
