// Running maxima and minima for tests that keep a NaN: std::max(worst, NaN) is `worst` (every comparison with
// NaN is false), so a NaN output would pass any "worst <= bound" check. These return NaN once either side is
// NaN, and NaN fails every bound.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

namespace cga::testing {

template <class T>
T nan_max(T a, T b) {
  return std::isnan(a) || std::isnan(b) ? std::numeric_limits<T>::quiet_NaN() : std::max(a, b);
}
template <class T>
T nan_min(T a, T b) {
  return std::isnan(a) || std::isnan(b) ? std::numeric_limits<T>::quiet_NaN() : std::min(a, b);
}

}  // namespace cga::testing
