// The oracle's own description of each built-in algebra (tests/oracle/include/oracle/algebra.hpp), written
// from the math independently of gen/algebra; shared by the generator tests that check against it.
#pragma once

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "oracle/algebra.hpp"

namespace og = oracle::ga;

namespace {

// The oracle's own description of each built-in, written from the math independently of gen/algebra.
inline og::Algebra oracle_algebra(const std::string& name) {
  if (name == "2d") return og::Algebra::signature(2, 0, 0, {"e1", "e2"});
  if (name == "3d") return og::Algebra::signature(3, 0, 0, {"e1", "e2", "e3"});
  if (name == "2dpga") return og::Algebra::diagonal({0, 1, 1}, {"e0", "e1", "e2"});
  if (name == "3dpga") return og::Algebra::diagonal({0, 1, 1, 1}, {"e0", "e1", "e2", "e3"});
  if (name == "sta") return og::Algebra::signature(1, 3, 0, {"e0", "e1", "e2", "e3"});
  if (name == "cra") {
    auto a = og::Algebra::diagonal({1, 1, 1, -1}, {"e1", "e2", "einf", "e0"});
    a.null_pair(3, 2, 2, 3);
    return a;
  }
  if (name == "cga") {
    auto a = og::Algebra::diagonal({1, 1, 1, 1, -1}, {"e1", "e2", "e3", "einf", "e0"});
    a.null_pair(4, 3, 3, 4);
    return a;
  }
  if (name == "gac") {
    auto a = og::Algebra::diagonal({1, 1, 1, 1, 1, -1, -1, -1},
                                   {"e1", "e2", "e0p", "e0m", "e0c", "einfp", "einfm", "einfc"});
    for (int k = 0; k < 3; ++k) a.null_pair(2 + k, 5 + k, 2 + k, 5 + k);
    return a;
  }
  if (name == "qga") {
    auto a = og::Algebra::diagonal({1, 1, 1, 1, 1, 1, -1, -1, -1},
                                   {"e1", "e2", "e3", "eo1", "eo2", "eo3", "ei1", "ei2", "ei3"});
    for (int k = 0; k < 3; ++k) a.null_pair(3 + k, 6 + k, 3 + k, 6 + k);
    return a;
  }
  if (name == "dcga") {
    auto a = og::Algebra::diagonal({1, 1, 1, 1, -1, 1, 1, 1, 1, -1},
                                   {"e1", "e2", "e3", "eo1", "ei1", "e6", "e7", "e8", "eo2", "ei2"});
    a.null_pair(3, 4, 3, 4);
    a.null_pair(8, 9, 8, 9);
    return a;
  }
  if (name == "ccga") {
    std::vector<int> metric{1, 1};
    std::vector<std::string> names{"e1", "e2"};
    for (int k = 1; k <= 7; ++k) {
      metric.push_back(1), metric.push_back(-1);
      names.push_back("eo" + std::to_string(k)), names.push_back("ei" + std::to_string(k));
    }
    auto a = og::Algebra::diagonal(metric, names);
    for (int k = 0; k < 7; ++k) a.null_pair(2 + 2 * k, 3 + 2 * k, 2 + 2 * k, 3 + 2 * k);
    return a;
  }
  throw std::invalid_argument(name);
}

using Named = std::map<std::string, double>;  // user blade name -> coefficient

// An oracle multivector by the user's blade names.
inline Named from_oracle(const og::Algebra& alg, const og::MV& diag) {
  Named r;
  for (const auto& [u, c] : og::to_user(alg, diag)) r[og::user_name(alg, u)] = c;
  return r;
}

// The largest coefficient difference of two multivectors by blade name (a missing blade is 0).
inline double max_diff(const Named& a, const Named& b) {
  double d = 0;
  for (const auto& [k, v] : a) d = std::max(d, std::abs(v - (b.count(k) ? b.at(k) : 0.0)));
  for (const auto& [k, v] : b) d = std::max(d, std::abs(v - (a.count(k) ? a.at(k) : 0.0)));
  return d;
}

}  // namespace
