// Memoized total derivatives over the expression DAG (derivative.hpp).
#include "symbolic/derivative.hpp"

#include <stdexcept>

#include "symbolic/dag.hpp"

namespace cgagen::symbolic {

TotalDerivative::TotalDerivative(std::map<GiNaC::ex, GiNaC::ex, GiNaC::ex_is_less> leaves, std::size_t max_nodes)
    : leaves_(std::move(leaves)), max_nodes_(max_nodes) {}

GiNaC::ex TotalDerivative::operator()(const GiNaC::ex& e) { return walk(e); }

GiNaC::ex TotalDerivative::walk(const GiNaC::ex& e) {
  using GiNaC::ex;
  if (auto it = memo_.find(node_of(e)); it != memo_.end()) return it->second.second;
  if (memo_.size() >= max_nodes_)
    throw std::length_error("the derivative visits more than " + std::to_string(max_nodes_) + " distinct subexpressions");
  ex d = 0;
  switch (kind_of(e)) {
    case Kind::Numeric:
    case Kind::Constant:
      break;
    case Kind::Symbol: {
      auto it = leaves_.find(e);
      if (it != leaves_.end()) d = it->second;
      break;
    }
    case Kind::Add: {
      GiNaC::exvector terms;
      for (size_t i = 0; i < e.nops(); ++i)
        if (ex t = walk(e.op(i)); !t.is_zero()) terms.push_back(t);
      d = GiNaC::add(terms);
      break;
    }
    case Kind::Mul: {  // Σ_i d(f_i) Π_{j≠i} f_j
      GiNaC::exvector terms;
      for (size_t i = 0; i < e.nops(); ++i) {
        ex di = walk(e.op(i));
        if (di.is_zero()) continue;
        GiNaC::exvector factors{di};
        for (size_t j = 0; j < e.nops(); ++j)
          if (j != i) factors.push_back(e.op(j));
        terms.push_back(GiNaC::mul(factors));
      }
      d = GiNaC::add(terms);
      break;
    }
    case Kind::Power: {
      const ex b = e.op(0), p = e.op(1);
      const ex db = walk(b), dp = walk(p);
      if (!db.is_zero()) d += p * GiNaC::pow(b, p - 1) * db;
      if (!dp.is_zero()) d += e * GiNaC::log(b) * dp;
      break;
    }
    case Kind::Function: {  // Σ_i ∂f/∂a_i (a) d(a_i), ∂f/∂a_i from GiNaC on fresh symbols
      const GiNaC::function& f = GiNaC::ex_to<GiNaC::function>(e);
      GiNaC::exvector fresh;
      GiNaC::exmap back;
      for (size_t i = 0; i < e.nops(); ++i) {
        GiNaC::symbol s;
        fresh.push_back(s);
        back[s] = e.op(i);
      }
      const ex on_fresh = GiNaC::function(f.get_serial(), fresh);
      for (size_t i = 0; i < e.nops(); ++i) {
        ex di = walk(e.op(i));
        if (di.is_zero()) continue;
        d += on_fresh.diff(GiNaC::ex_to<GiNaC::symbol>(fresh[i])).subs(back) * di;
      }
      break;
    }
    case Kind::Other:
      throw std::invalid_argument("cannot differentiate " + std::string(typeid(*node_of(e)).name()));
  }
  memo_.emplace(node_of(e), std::make_pair(e, d));
  return d;
}

}  // namespace cgagen::symbolic
