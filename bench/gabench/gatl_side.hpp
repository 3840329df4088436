// gabench's GATL side: GATL's spelling of each of ga-benchmark's operations (as its source/GATL/*.hpp
// names them: gp, op, lcont, rcont, sp, dot, hip, cp, rp, igp, inv, unit, dual, undual, rnorm_sqr, ...),
// the random blades built from the same factors as cgagen's inputs, and the timed loop of gabench.hpp.
// Included by the per-operation translation units that GabenchScripts.cmake writes, which define
// GABENCH_GATL_MODEL_<model> and expand GABENCH_GATL_UNARY/BINARY(model, op). Compiled only against the
// user's GATL checkout (GATL_DIR, header-only, GPL); nothing of GATL is in this repository.
#pragma once

#include "gabench.hpp"

#include <iomanip>
#include <memory>
#include <sstream>
#include <utility>

#if defined(GABENCH_GATL_MODEL_c3ga)
#include <gatl/ga3c.hpp>
#define GABENCH_GATL_NS ga3c
#define GABENCH_GATL_DIMS 5
#elif defined(GABENCH_GATL_MODEL_e3ga)
#include <gatl/ga3e.hpp>
#define GABENCH_GATL_NS ga3e
#define GABENCH_GATL_DIMS 3
#elif defined(GABENCH_GATL_MODEL_h3ga)
#include <gatl/ga3h.hpp>
#define GABENCH_GATL_NS ga3h
#define GABENCH_GATL_DIMS 4
#else
#error "gatl_side.hpp: define GABENCH_GATL_MODEL_c3ga, _e3ga or _h3ga"
#endif

// Internal linkage: each translation unit's templates are its own model's (the same names in another model's
// unit are other functions).
namespace gabench_gatl {
namespace {

using namespace GABENCH_GATL_NS;
using gabench::BladeSet;
using gabench::Inputs;
using gabench::Side;

// The blade of sample i: its scalar, then the outer product with each factor vector in turn.
template <std::size_t... K>
auto blade(const BladeSet& s, std::size_t i, std::index_sequence<K...>) {
  return (scalar(s.scalars[i]) ^ ... ^ vector(s.factor(i, static_cast<int>(K)), s.factor(i, static_cast<int>(K)) + s.dim));
}
template <int G>
auto blade(const BladeSet& s, std::size_t i) {
  return blade(s, i, std::make_index_sequence<G>{});
}
template <int G>
auto blades(const BladeSet& s) {
  using T = decltype(blade<G>(s, 0));
  auto v = std::make_shared<std::vector<T>>();
  v->reserve(gabench::kSamples);
  for (std::size_t i = 0; i < gabench::kSamples; ++i) v->push_back(blade<G>(s, i));
  return v;
}

template <class R>
gabench::Named read(const std::string& model, const R& r) {
  std::ostringstream os;
  os << std::setprecision(17) << r;
  return gabench::parse_gatl(model, os.str());
}

template <int GA, class Op>
Side unary(const std::string& model, const Inputs& in, Op op) {
  auto va = blades<GA>(*in.a);
  Side s;
  s.run = [va, op](benchmark::State& state) {
    if (!gabench::enough(state)) return;
    const auto* pa = va->data();
    for (auto _ : state) {
      auto r = op(*pa);
      benchmark::DoNotOptimize(r);
      ++pa;
    }
  };
  s.eval = [va, op, model](std::size_t i) { return read(model, op((*va)[i])); };
  return s;
}

template <int GA, int GB, class Op>
Side binary(const std::string& model, const Inputs& in, Op op) {
  auto va = blades<GA>(*in.a);
  auto vb = blades<GB>(*in.b);
  Side s;
  s.run = [va, vb, op](benchmark::State& state) {
    if (!gabench::enough(state)) return;
    const auto* pa = va->data();
    const auto* pb = vb->data();
    for (auto _ : state) {
      auto r = op(*pa, *pb);
      benchmark::DoNotOptimize(r);
      ++pa;
      ++pb;
    }
  };
  s.eval = [va, vb, op, model](std::size_t i) { return read(model, op((*va)[i], (*vb)[i])); };
  return s;
}

template <class Op, std::size_t... G>
bool add_unary(const char* model, const char* name, Op op, std::index_sequence<G...>) {
  (gabench::add({model, name, "GATL", static_cast<int>(G), -1,
                 [m = std::string(model), op](const Inputs& in) { return unary<static_cast<int>(G)>(m, in, op); }}),
   ...);
  return true;
}

template <int GA, class Op, std::size_t... GB>
void add_binary_row(const char* model, const char* name, Op op, std::index_sequence<GB...>) {
  (gabench::add({model, name, "GATL", GA, static_cast<int>(GB),
                 [m = std::string(model), op](const Inputs& in) { return binary<GA, static_cast<int>(GB)>(m, in, op); }}),
   ...);
}
template <class Op, std::size_t... GA>
bool add_binary(const char* model, const char* name, Op op, std::index_sequence<GA...>) {
  (add_binary_row<static_cast<int>(GA)>(model, name, op, std::make_index_sequence<GABENCH_GATL_DIMS + 1>{}), ...);
  return true;
}

}  // namespace
}  // namespace gabench_gatl

// GATL's spelling of each operation.
#define GABENCH_GATL_CliffordConjugation(a) conjugate(a)
#define GABENCH_GATL_Dualization(a) dual(a)
#define GABENCH_GATL_GradeInvolution(a) involute(a)
#define GABENCH_GATL_Inversion(a) inv(a)
#define GABENCH_GATL_Normalization(a) unit(a)
#define GABENCH_GATL_Reversion(a) reverse(a)
#define GABENCH_GATL_SquaredReverseNorm(a) rnorm_sqr(a)
#define GABENCH_GATL_UnaryMinus(a) (-(a))
#define GABENCH_GATL_UnaryPlus(a) (+(a))
#define GABENCH_GATL_Undualization(a) undual(a)
#define GABENCH_GATL_Addition(a, b) ((a) + (b))
#define GABENCH_GATL_CommutatorProduct(a, b) cp(a, b)
#define GABENCH_GATL_DotProduct(a, b) dot(a, b)
#define GABENCH_GATL_GeometricProduct(a, b) gp(a, b)
#define GABENCH_GATL_HestenesInnerProduct(a, b) hip(a, b)
#define GABENCH_GATL_InverseGeometricProduct(a, b) igp(a, b)
#define GABENCH_GATL_LeftContraction(a, b) lcont(a, b)
#define GABENCH_GATL_OuterProduct(a, b) op(a, b)
#define GABENCH_GATL_RegressiveProduct(a, b) rp(a, b)
#define GABENCH_GATL_RightContraction(a, b) rcont(a, b)
#define GABENCH_GATL_ScalarProduct(a, b) sp(a, b)
#define GABENCH_GATL_Subtraction(a, b) ((a) - (b))

#define GABENCH_GATL_UNARY(MODEL, OP)                                                                   \
  namespace gabench_gatl {                                                                              \
  const bool registered_##OP = add_unary(                                                               \
      #MODEL, #OP, [](const auto& a) { return GABENCH_GATL_##OP(a); },                                  \
      std::make_index_sequence<GABENCH_GATL_DIMS + 1>{});                                               \
  }
#define GABENCH_GATL_BINARY(MODEL, OP)                                                                  \
  namespace gabench_gatl {                                                                              \
  const bool registered_##OP = add_binary(                                                              \
      #MODEL, #OP, [](const auto& a, const auto& b) { return GABENCH_GATL_##OP(a, b); },                \
      std::make_index_sequence<GABENCH_GATL_DIMS + 1>{});                                               \
  }
