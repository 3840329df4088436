// Derivative outputs (`#pragma jacobian [OUT...] wrt IN...`, cgagen --jacobian IN,...): for each input
// coefficient x, every kernel value gets a derivative value by the chain rule through the earlier values,
//   d(c)/dx = ∂c/∂x + Σ_s ∂c/∂s · d(s)/dx   (s the earlier values' coefficient symbols c reads),
// so the derivatives reuse the values' own temporaries and the optimizer shares work between the values and
// every derivative. A select differentiates its taken branch (symbolic/select.cpp); sqrt, abs, atan2, exp,
// log and the other functions are GiNaC's exact derivatives. Each derivative output OUT_d_X has OUT's blades.
#include <algorithm>
#include <map>

#include "expand/expander.hpp"

namespace cgagen::expand_detail {

namespace {

using ExMap = std::map<GiNaC::ex, GiNaC::ex, GiNaC::ex_is_less>;

// The symbols of `e` that are keys of `m` (each once).
std::vector<GiNaC::ex> symbols_in(const GiNaC::ex& e, const ExMap& m) {
  std::vector<GiNaC::ex> out;
  for (GiNaC::const_preorder_iterator it = e.preorder_begin(); it != e.preorder_end(); ++it)
    if (GiNaC::is_a<GiNaC::symbol>(*it) && m.count(*it) &&
        std::find_if(out.begin(), out.end(), [&](const GiNaC::ex& s) { return s.is_equal(*it); }) == out.end())
      out.push_back(*it);
  return out;
}

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
    for (const auto& [name, loc] : r.wrt) {
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
          ExMap d;  // value symbol -> its derivative (a derivative value's symbol, or an expression)
          for (size_t i = 0; i < value_count; ++i) {
            const KernelValue& v = kernel_.values[i];
            Multivector dv;
            for (size_t b = 0; b < v.blades.size(); ++b) {
              GiNaC::ex c = v.coeffs[b].diff(in->symbols[k]);
              for (const GiNaC::ex& s : symbols_in(v.coeffs[b], d))
                if (!d.at(s).is_zero()) c += v.coeffs[b].diff(GiNaC::ex_to<GiNaC::symbol>(s)) * d.at(s);
              dv.set(v.blades[b], c);
            }
            KernelValue kv = value_of("d_" + v.name + "_d_" + x, "d_" + v.name + "_" + x, v.loc, dv);
            for (size_t b = 0; b < v.blades.size(); ++b) {
              auto at = std::find(kv.blades.begin(), kv.blades.end(), v.blades[b]);
              d[v.symbols[b]] = at == kv.blades.end() ? GiNaC::ex(0) : GiNaC::ex(kv.symbols[at - kv.blades.begin()]);
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
