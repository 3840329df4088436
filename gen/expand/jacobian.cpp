// Derivative outputs (`#pragma jacobian [OUT...] wrt IN...`, cgagen --jacobian IN,...): for each input
// coefficient x, every kernel value gets a derivative value by the chain rule through the earlier values,
//   d(c)/dx = ∂c/∂x + Σ_s ∂c/∂s · d(s)/dx   (s the earlier values' coefficient symbols c reads; one
// memoized walk of c's DAG, symbolic/derivative.hpp),
// so the derivatives reuse the values' own temporaries and the optimizer shares work between the values and
// every derivative. A select differentiates its taken branch (symbolic/select.cpp); sqrt, abs, atan2, exp,
// log and the other functions are GiNaC's exact derivatives. Each derivative output OUT_d_X has OUT's blades.
#include <algorithm>
#include <map>

#include "expand/expander.hpp"
#include "symbolic/derivative.hpp"

namespace cgagen::expand_detail {

namespace {

using ExMap = std::map<GiNaC::ex, GiNaC::ex, GiNaC::ex_is_less>;

// The distinct subexpressions one derivative may visit: the bundled scripts' largest coefficient DAGs have a
// few thousand nodes; a random program's can have far more, and its derivatives stop here with a located
// error rather than run for minutes.
constexpr size_t kMaxDerivativeNodes = 200000;

}  // namespace

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
  for (const Request& r : requests)
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

}  // namespace cgagen::expand_detail
