// Derivative outputs (`#pragma jacobian [OUT...] wrt IN...`, cgagen --jacobian IN,...), by the chain rule
// through the kernel's values, in one of two orders chosen per request by its size:
// - forward (n input coefficients, few): for each input coefficient x, every value gets a derivative value,
//     d(c)/dx = ∂c/∂x + Σ_s ∂c/∂s · d(s)/dx   (s the earlier values' coefficient symbols c reads; one
//   memoized walk of c's DAG, symbolic/derivative.hpp); the work is about n times the values'.
// - reverse (m output coefficients, fewer than n): for each output coefficient y, an adjoint per value
//   coefficient, from the last value back to the first,
//     ȳ_s = Σ_c ȳ_c · ∂c/∂s   (c the later coefficients that read s),  dy/dx = Σ_c ȳ_c · ∂c/∂x;
//   the work is about m times the values', whatever n (a joint chain's end point against many angles).
// CGAGEN_JACOBIAN_ORDER=forward|reverse in the environment forces one order (the tests run both).
// Either way the derivatives reuse the values' own temporaries and the optimizer shares work between the
// values and every derivative. A select differentiates its taken branch (symbolic/select.cpp); sqrt, abs,
// atan2, exp, log and the other functions are GiNaC's exact derivatives. Each derivative output OUT_d_X has
// OUT's blades.
#include <algorithm>
#include <map>
#include <cstdlib>
#include <set>
#include <string>

#include "expand/expander.hpp"
#include "symbolic/dag.hpp"
#include "symbolic/derivative.hpp"

namespace cgagen::expand_detail {

namespace {

using ExMap = std::map<GiNaC::ex, GiNaC::ex, GiNaC::ex_is_less>;

// The distinct subexpressions one derivative may visit: the bundled scripts' largest coefficient DAGs have a
// few thousand nodes; a random program's can have far more, and its derivatives stop here with a located
// error rather than run for minutes.
constexpr size_t kMaxDerivativeNodes = 200000;

// A request goes in reverse order when its output coefficients are fewer than its input coefficients. A
// sweep of either order costs about the values' work, a reverse one a little more (measured on the 5-joint
// arm, 5 point coefficients against 5 angles: 4,651 ops reverse, 4,155 forward; a 10-joint chain: 12,710
// against 17,127).
bool reverse_pays(size_t output_coeffs, size_t input_coeffs) {
  if (const char* force = std::getenv("CGAGEN_JACOBIAN_ORDER")) return std::string(force) == "reverse";
  return output_coeffs < input_coeffs;
}

}  // namespace

// The partial derivatives of value i's coefficient b with respect to each symbol it reads, once per
// coefficient for every reverse sweep.
const std::vector<std::pair<GiNaC::ex, GiNaC::ex>>& Expander::partials_of(size_t i, size_t b) {
  auto key = std::make_pair(i, b);
  if (auto it = partials_.find(key); it != partials_.end()) return it->second;
  const KernelValue& v = kernel_.values[i];
  std::set<GiNaC::ex, GiNaC::ex_is_less> symbols;
  symbolic::collect_symbols_into(v.coeffs[b], symbols);
  std::vector<std::pair<GiNaC::ex, GiNaC::ex>> out;
  for (const GiNaC::ex& s : symbols) {
    symbolic::TotalDerivative partial(ExMap{{s, GiNaC::ex(1)}}, kMaxDerivativeNodes);
    GiNaC::ex p;
    try {
      p = partial(v.coeffs[b]);
    } catch (const std::length_error& e) {
      throw CompileError(v.loc, "the derivative of '" + v.name + "' is over cgagen's work budget: " + e.what());
    }
    if (!p.is_zero()) out.emplace_back(s, p);
  }
  return partials_.emplace(key, std::move(out)).first->second;
}

// One reverse sweep per output coefficient of `outputs`: the adjoints of every value coefficient it reads,
// bound as values (one per swept value, over its blades), then for each input coefficient x a value
// d_OUT_d_x over OUT's blades and its output OUT_d_x.
void Expander::reverse_jacobian(const std::vector<size_t>& outputs, const std::vector<std::pair<GiNaC::ex, std::string>>& wrt) {
  std::map<GiNaC::ex, size_t, GiNaC::ex_is_less> value_of_symbol;  // coefficient symbol -> (value index)
  for (size_t i = 0; i < kernel_.values.size(); ++i)
    for (const auto& s : kernel_.values[i].symbols) value_of_symbol[s] = i;
  ExMap is_wrt;
  for (const auto& [x, name] : wrt) is_wrt[x] = x;
  // grads[k][b][x]: d(coefficient b of output k's value)/dx
  std::vector<std::vector<ExMap>> grads;
  for (size_t o : outputs) {
    const KernelOutput& out = kernel_.outputs[o];
    const size_t last = static_cast<size_t>(out.value);
    const KernelValue ov = kernel_.values[last];  // a copy: the sweeps append values
    grads.emplace_back(ov.blades.size());
    for (size_t ob = 0; ob < ov.blades.size(); ++ob) {
      ExMap adjoint{{ov.symbols[ob], GiNaC::ex(1)}};
      for (size_t i = last + 1; i-- > 0;) {
        const KernelValue& v = kernel_.values[i];  // read before `bound` is appended below
        KernelValue bound;  // the adjoints of v's coefficients, as one value
        bound.name = "adj_" + out.name + "_" + algebra::blade_ident(ov.blades[ob]) + "_" + v.name;
        bound.loc = v.loc;
        for (size_t b = 0; b < v.blades.size(); ++b) {
          auto a = adjoint.find(v.symbols[b]);
          if (a == adjoint.end() || a->second.is_zero()) continue;
          GiNaC::ex sym = a->second;
          if (!symbolic::is_symbol_number_or_constant(sym)) {
            bound.blades.push_back(v.blades[b]);
            bound.coeffs.push_back(a->second);
            bound.symbols.push_back(GiNaC::realsymbol(unique_symbol_name(bound.name + "_" + algebra::blade_ident(v.blades[b]))));
            sym = bound.symbols.back();
          }
          for (const auto& [s, p] : partials_of(i, b)) {
            if (is_wrt.count(s)) grads.back()[ob][s] += sym * p;
            else if (value_of_symbol.count(s)) adjoint[s] += sym * p;
          }
          adjoint.erase(a);
        }
        if (!bound.blades.empty()) kernel_.values.push_back(std::move(bound));
      }
    }
  }
  // The outputs in forward order's order: for each input coefficient, each output's derivative.
  for (const auto& [x, name] : wrt)
    for (size_t k = 0; k < outputs.size(); ++k) {
      KernelOutput d = kernel_.outputs[outputs[k]];
      const KernelValue& ov = kernel_.values[static_cast<size_t>(d.value)];
      d.name += "_d_" + name;
      if (std::any_of(kernel_.outputs.begin(), kernel_.outputs.end(), [&](const KernelOutput& e) { return e.name == d.name; }))
        continue;  // asked for twice
      KernelValue kv;
      kv.name = "d_" + ov.name + "_d_" + name;
      kv.loc = ov.loc;
      for (size_t ob = 0; ob < ov.blades.size(); ++ob) {
        auto g = grads[k][ob].find(x);
        if (g == grads[k][ob].end() || g->second.is_zero()) continue;
        kv.blades.push_back(ov.blades[ob]);
        kv.coeffs.push_back(g->second);
        kv.symbols.push_back(GiNaC::realsymbol(unique_symbol_name("d_" + ov.name + "_" + name + "_" + algebra::blade_ident(ov.blades[ob]))));
      }
      d.value = static_cast<int>(kernel_.values.size());
      d.from_pragma = true;  // the output's own blades, zeros included: a fixed layout
      kernel_.values.push_back(std::move(kv));
      kernel_.outputs.push_back(std::move(d));
    }
}

void Expander::apply_jacobians() {
  struct Request {
    std::vector<size_t> outputs;  // indices into kernel_.outputs
    std::vector<std::pair<std::string, front::SourceLoc>> wrt;
  };
  std::vector<Request> requests;
  auto all_outputs = [&] {
    std::vector<size_t> all(kernel_.outputs.size());
    for (size_t i = 0; i < all.size(); ++i) all[i] = i;
    return all;
  };
  for (const auto& j : pragmas_.jacobians()) {
    Request r;
    for (const auto& o : j.outputs) {
      auto it = std::find_if(kernel_.outputs.begin(), kernel_.outputs.end(), [&](const KernelOutput& k) { return k.name == o.name; });
      if (it == kernel_.outputs.end()) throw CompileError(o.loc, "'#pragma jacobian' names '" + o.name + "', which is not an output");
      r.outputs.push_back(static_cast<size_t>(it - kernel_.outputs.begin()));
    }
    if (r.outputs.empty()) r.outputs = all_outputs();
    for (const auto& w : j.wrt) r.wrt.push_back({w.name, w.loc});
    requests.push_back(std::move(r));
  }
  if (!jacobian_wrt_.empty()) {
    Request r{all_outputs(), {}};
    for (const auto& w : jacobian_wrt_) r.wrt.push_back({w, {1, 1}});
    requests.push_back(std::move(r));
  }
  if (requests.empty()) return;

  const size_t value_count = kernel_.values.size();
  std::map<std::string, size_t> derivative_of;  // input coefficient name -> first derivative value index
  for (const Request& r : requests) {
    // The request's size in coefficients, and its order.
    std::vector<std::pair<GiNaC::ex, std::string>> coefficients;  // symbol, name (a, or M_e1 for M's e1)
    for (const auto& w : r.wrt) {
      auto in = std::find_if(kernel_.inputs.begin(), kernel_.inputs.end(), [&](const KernelInput& k) { return k.name == w.first; });
      if (in == kernel_.inputs.end())
        throw CompileError(w.second, "'jacobian' with respect to '" + w.first + "', which is not an input of the script");
      for (size_t k = 0; k < in->symbols.size(); ++k)
        coefficients.emplace_back(in->symbols[k], in->is_multivector ? w.first + "_" + algebra::blade_ident(in->blades[k]) : w.first);
    }
    size_t output_coeffs = 0;
    for (size_t o : r.outputs) output_coeffs += kernel_.values[static_cast<size_t>(kernel_.outputs[o].value)].blades.size();
    if (reverse_pays(output_coeffs, coefficients.size())) {
      reverse_jacobian(r.outputs, coefficients);
      continue;
    }
    for (const auto& w : r.wrt) {
      const std::string& name = w.first;  // not a structured binding: lambdas below capture it (clang 15)
      const front::SourceLoc loc = w.second;
      auto in = std::find_if(kernel_.inputs.begin(), kernel_.inputs.end(), [&](const KernelInput& k) { return k.name == name; });
      if (in == kernel_.inputs.end())
        throw CompileError(loc, "'jacobian' with respect to '" + name + "', which is not an input of the script");
      for (size_t k = 0; k < in->symbols.size(); ++k) {
        const std::string x = in->is_multivector ? name + "_" + algebra::blade_ident(in->blades[k]) : name;
        // The derivative values of x, once for all requests: value i's derivative is value first + i.
        size_t first = 0;
        if (auto it = derivative_of.find(x); it != derivative_of.end()) {
          first = it->second;
        } else {
          first = kernel_.values.size();
          derivative_of[x] = first;
          // Each symbol's derivative: x's is 1, a value coefficient's is its derivative value's symbol (filled
          // in value order, so a coefficient's leaves are known when it is differentiated).
          ExMap leaves{{in->symbols[k], GiNaC::ex(1)}};
          for (size_t i = 0; i < value_count; ++i) {
            const KernelValue& v = kernel_.values[i];
            Multivector dv;
            symbolic::TotalDerivative total(leaves, kMaxDerivativeNodes);  // shared by the value's blades
            for (size_t b = 0; b < v.blades.size(); ++b) {
              try {
                dv.set(v.blades[b], total(v.coeffs[b]));
              } catch (const std::length_error& e) {
                throw CompileError(v.loc, "the derivative of '" + v.name + "' with respect to '" + x +
                                              "' is over cgagen's work budget: " + e.what());
              }
            }
            // Every coefficient that is not literally 0 is kept: an exact zero test (value_of's) of a derivative
            // of a large coefficient can take minutes, and a kept zero only computes a 0.
            KernelValue kv;
            kv.name = "d_" + v.name + "_d_" + x;
            kv.loc = v.loc;
            for (const auto& [blade, c] : dv.terms()) {
              if (c.is_zero()) continue;
              kv.blades.push_back(blade);
              kv.coeffs.push_back(c);
              kv.symbols.push_back(GiNaC::realsymbol(unique_symbol_name("d_" + v.name + "_" + x + "_" + algebra::blade_ident(blade))));
            }
            for (size_t b = 0; b < v.blades.size(); ++b) {
              auto at = std::find(kv.blades.begin(), kv.blades.end(), v.blades[b]);
              if (at != kv.blades.end()) leaves[v.symbols[b]] = kv.symbols[at - kv.blades.begin()];
            }
            kernel_.values.push_back(std::move(kv));
          }
        }
        for (size_t o : r.outputs) {
          KernelOutput out = kernel_.outputs[o];
          out.name += "_d_" + x;
          if (std::any_of(kernel_.outputs.begin(), kernel_.outputs.end(), [&](const KernelOutput& e) { return e.name == out.name; }))
            continue;  // asked for twice
          out.value = static_cast<int>(first + static_cast<size_t>(kernel_.outputs[o].value));
          out.from_pragma = true;  // the output's own blades, zeros included: a fixed layout
          kernel_.outputs.push_back(std::move(out));
        }
      }
    }
  }
}

}  // namespace cgagen::expand_detail
