// gabench's models (c3ga, e3ga, h3ga: ga-benchmark's conformal, Euclidean and homogeneous 3D), their
// random blades (ga-benchmark's recipe, seeded) and the reference result of each operation, computed by the
// test suite's independent any-signature oracle (tests/oracle/include/oracle/algebra.hpp) from the
// operations' definitions as ga-benchmark (GATL) gives them.
#pragma once

#include "gabench.hpp"

#include <string>
#include <vector>

#include "oracle/algebra.hpp"

namespace gabench {

namespace og = oracle::ga;

struct Model {
  std::string name;
  int id = 0;                          // ga-benchmark's model id (Conformal 0x01, Euclidean 0x02, Homogeneous 0x03)
  int d = 3;                           // ga-benchmark's D: the base space's dimensions
  std::vector<std::string> cg;         // the vectors in cgagen's order (the algebra's user basis)
  std::vector<std::string> gatl;       // the same vectors in GATL's order (e1 e2 e3 no ni: e0 = no, einf = ni)
  std::vector<int> gatl_to_cg;         // GATL index -> cgagen index
  og::Algebra alg;                     // the oracle's algebra over cgagen's user basis
  int dim() const { return static_cast<int>(cg.size()); }
};

const Model& model(const std::string& name);

// The blades of grade k as bitmasks over cgagen's vectors, in cgagen's order (index tuples lexicographic).
std::vector<og::Bits> grade_blades(int n, int k);

// kSamples random blades of grade k (invertible: |<B ~B>| > 1e-8, as ga-benchmark's Inversion,
// Normalization and InverseGeometricProduct take), from a generator seeded by (model, role, grade).
BladeSet make_blades(const Model& m, int grade, const std::string& role, bool invertible);

// Sample i of a blade set as an oracle multivector (over the diagonal basis).
og::MV oracle_value(const Model& m, const BladeSet& s, std::size_t i);

// The reference result of operation `op` (ga-benchmark's name) on a (and b), by cgagen blade name.
Named reference(const Model& m, const std::string& op, const og::MV& a, const og::MV* b);

// The largest coefficient difference of two results, relative to 1 + the largest coefficient.
double rel_diff(const Named& x, const Named& y);

}  // namespace gabench
