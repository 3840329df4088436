// The generator's product tables and symbolic multivectors, checked against the independent dense oracle.
#include <catch2/catch.hpp>

#include <random>

#include "algebra/blade.hpp"
#include "algebra/products.hpp"
#include "oracle/multivector.hpp"
#include "symbolic/multivector.hpp"

using namespace cgagen;
using algebra::ProductKind;
using OMV = oracle::MV<double>;

namespace {

// A table row (blade a op blade b) as an oracle multivector.
OMV table_entry(ProductKind kind, int a, int b) {
  OMV r;
  for (const auto& t : algebra::product(kind, a, b))
    r += t.coeff.to_double() * oracle::null_blade<double>(algebra::blade_name(t.blade));
  return r;
}

OMV oracle_blade(int i) { return oracle::null_blade<double>(algebra::blade_name(i)); }

// A symbolic multivector with numeric coefficients, and its oracle twin.
OMV to_oracle(const symbolic::Multivector& m) {
  OMV r;
  for (const auto& [b, c] : m.terms()) {
    GiNaC::ex v = GiNaC::evalf(c);
    REQUIRE(GiNaC::is_a<GiNaC::numeric>(v));
    r += GiNaC::ex_to<GiNaC::numeric>(v).to_double() * oracle_blade(b);
  }
  return r;
}

symbolic::Multivector random_mv(std::mt19937& rng, int blades) {
  std::uniform_int_distribution<int> pick(0, algebra::kBladeCount - 1), num(-9, 9);
  symbolic::Multivector m;
  for (int k = 0; k < blades; ++k) m.set(pick(rng), GiNaC::numeric(num(rng), 4));
  return m;
}

}  // namespace

TEST_CASE("blade names follow the oracle's Gaalop order") {
  for (int i = 0; i < algebra::kBladeCount; ++i) CHECK(algebra::blade_name(i) == oracle::null_blade_names()[i]);
}

TEST_CASE("every geometric, outer and inner table entry equals the oracle's product") {
  for (int a = 0; a < algebra::kBladeCount; ++a) {
    for (int b = 0; b < algebra::kBladeCount; ++b) {
      INFO(algebra::blade_name(a) << " op " << algebra::blade_name(b));
      const OMV A = oracle_blade(a), B = oracle_blade(b);
      CHECK(oracle::max_abs_diff(table_entry(ProductKind::Geometric, a, b), A * B) < 1e-12);
      CHECK(oracle::max_abs_diff(table_entry(ProductKind::Outer, a, b), A ^ B) < 1e-12);
      CHECK(oracle::max_abs_diff(table_entry(ProductKind::Inner, a, b), oracle::inner(A, B)) < 1e-12);
    }
  }
}

TEST_CASE("table entries are exact small rationals in increasing blade order") {
  for (int a = 0; a < algebra::kBladeCount; ++a)
    for (int b = 0; b < algebra::kBladeCount; ++b) {
      int last = -1;
      for (const auto& t : algebra::product(ProductKind::Geometric, a, b)) {
        CHECK(t.blade > last);
        last = t.blade;
        CHECK(!t.coeff.is_zero());
        CHECK((t.coeff.den == 1 || t.coeff.den == 2 || t.coeff.den == 4));
      }
    }
  // einf.e0 = -1 and einf*e0 = -1 + einf^e0.
  const auto& ie = algebra::product(ProductKind::Inner, 4, 5);
  REQUIRE(ie.size() == 1);
  CHECK(ie[0].blade == 0);
  CHECK(ie[0].coeff == algebra::Rational(-1));
  CHECK(algebra::product(ProductKind::Geometric, 4, 4).empty());
  CHECK(algebra::product(ProductKind::Geometric, 5, 5).empty());
}

TEST_CASE("reverse and involution signs match the oracle") {
  for (int i = 0; i < algebra::kBladeCount; ++i) {
    const OMV b = oracle_blade(i);
    CHECK(oracle::max_abs_diff(double(algebra::reverse_sign(i)) * b, oracle::reverse(b)) < 1e-12);
    CHECK(oracle::max_abs_diff(double(algebra::involution_sign(i)) * b, oracle::involute(b)) < 1e-12);
  }
}

TEST_CASE("symbolic multivector operations agree with the oracle on random sparse values") {
  std::mt19937 rng(1234);
  for (int trial = 0; trial < 50; ++trial) {
    const auto a = random_mv(rng, 6), b = random_mv(rng, 6);
    const OMV A = to_oracle(a), B = to_oracle(b);
    CHECK(oracle::max_abs_diff(to_oracle(a * b), A * B) < 1e-9);
    CHECK(oracle::max_abs_diff(to_oracle(a ^ b), A ^ B) < 1e-9);
    CHECK(oracle::max_abs_diff(to_oracle(inner(a, b)), oracle::inner(A, B)) < 1e-9);
    CHECK(oracle::max_abs_diff(to_oracle(a + b), A + B) < 1e-9);
    CHECK(oracle::max_abs_diff(to_oracle(a - b), A - B) < 1e-9);
    CHECK(oracle::max_abs_diff(to_oracle(-a), -A) < 1e-9);
    CHECK(oracle::max_abs_diff(to_oracle(a.reverse()), oracle::reverse(A)) < 1e-9);
    CHECK(oracle::max_abs_diff(to_oracle(a.involute()), oracle::involute(A)) < 1e-9);
    CHECK(oracle::max_abs_diff(to_oracle(a.dual()), oracle::dual(A)) < 1e-9);
    CHECK(oracle::max_abs_diff(to_oracle(a.grade(2)), oracle::grade(A, 2)) < 1e-9);
    CHECK(oracle::max_abs_diff(to_oracle(GiNaC::numeric(3, 2) * a), 1.5 * A) < 1e-9);
  }
}

TEST_CASE("symbolic coefficients are expanded and identically-zero blades dropped") {
  GiNaC::symbol x("x"), y("y");
  using symbolic::Multivector;
  const Multivector p = Multivector::blade(1, x) + Multivector::blade(2, y);
  const Multivector sq = p * p;  // (x e1 + y e2)^2 = x^2 + y^2: the e1^e2 parts cancel
  CHECK(sq.is_scalar());
  CHECK((sq.scalar() - (x * x + y * y)).expand().is_zero());
  CHECK((p ^ p).is_zero());
  // A rational coefficient that only normalizes to zero is dropped too.
  const Multivector r = Multivector::blade(1, x / (x + y)) + Multivector::blade(1, y / (x + y)) - Multivector::e1();
  CHECK(r.is_zero());
  CHECK(Multivector::einf() * Multivector::einf() == Multivector());
  CHECK(Multivector::e1().str() == "e1");
  CHECK(Multivector().str() == "0");
  CHECK(Multivector::blade(9, 2 * x).str() == "(2*x)*e1^e0");
}
