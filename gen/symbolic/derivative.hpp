// The total derivative of an expression as the DAG it is (derivative kernels, expand/jacobian.cpp). GiNaC's
// diff() walks a tree: a coefficient whose values were substituted into each other shares its subexpressions,
// and a tree walk of it costs time exponential in the depth of the sharing. Here every node is differentiated
// once (memoized by identity), by the sum, product, power and chain rules; a function's partial derivatives
// are GiNaC's (its registered derivative, on fresh symbols, then the arguments put back).
#pragma once

#include <ginac/ginac.h>

#include <cstddef>
#include <map>

namespace cgagen::symbolic {

class TotalDerivative {
 public:
  // `leaves`: each symbol's derivative (the variable: 1; a value's coefficient: its derivative's symbol);
  // any other symbol's is 0. `max_nodes`: how many distinct nodes one derivative may visit.
  TotalDerivative(std::map<GiNaC::ex, GiNaC::ex, GiNaC::ex_is_less> leaves, std::size_t max_nodes);
  // d(e); throws std::length_error past max_nodes (the caller names the statement), std::invalid_argument for
  // a node it cannot differentiate.
  GiNaC::ex operator()(const GiNaC::ex& e);

 private:
  GiNaC::ex walk(const GiNaC::ex& e);
  std::map<GiNaC::ex, GiNaC::ex, GiNaC::ex_is_less> leaves_;
  std::map<const GiNaC::basic*, std::pair<GiNaC::ex, GiNaC::ex>> memo_;  // node -> (node kept alive, derivative)
  std::size_t max_nodes_;
};

}  // namespace cgagen::symbolic
