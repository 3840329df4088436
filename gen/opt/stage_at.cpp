// Staging at named values (--stage-at A,B): a Kernel split where the caller says, into
//   NAME_prepare(every input the body does not read) -> prepared = the named values' coefficients
//   NAME(prepared, the inputs the rest reads)          -> the kernel's outputs
// Automatic staging (stage.cpp) splits by rate and puts everything the uniform inputs decide into the prepare,
// which is right when the prepare runs once per batch. A two-pass batch loop runs the prepare once per element
// instead: a skinning blend's first pass mixes a vertex's four palette entries (sums of products that a
// compiler vectorizes across the blades of one vertex), its second pass does the rest (square roots,
// exponentials, the sandwich) lane-wise across vertices. There the cut belongs where the script names it:
// after the blend, before the transcendental part. The two halves are the script's own statements, each
// optimized as an ordinary kernel, so every target prints them as it prints any staged kernel.
#include <algorithm>
#include <map>
#include <set>
#include <stdexcept>

#include "opt/internal.hpp"
#include "opt/stage.hpp"

namespace cgagen::opt {

using namespace GiNaC;
using detail::collect_symbols;
using detail::ExSet;

namespace {

std::string join(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

// The values of k that `roots` need (directly or through other values), as a mask over k.values.
std::vector<bool> needed_values(const Kernel& k, ExSet wanted) {
  std::vector<bool> need(k.values.size(), false);
  // Values refer only to earlier values: one backward sweep closes the set.
  for (size_t v = k.values.size(); v-- > 0;) {
    bool used = false;
    for (const auto& s : k.values[v].symbols) used = used || wanted.count(s) > 0;
    if (!used) continue;
    need[v] = true;
    for (const auto& c : k.values[v].coeffs) collect_symbols(c, wanted);
  }
  return need;
}

// The inputs of k whose symbols occur in `used`, in input order.
std::vector<KernelInput> inputs_used(const Kernel& k, const ExSet& used) {
  std::vector<KernelInput> out;
  for (const auto& in : k.inputs)
    if (std::any_of(in.symbols.begin(), in.symbols.end(), [&](const realsymbol& s) { return used.count(s) > 0; }))
      out.push_back(in);
  return out;
}

}  // namespace

StagedProgram stage_at(const Kernel& kernel, const std::vector<std::string>& names, Level level) {
  algebra::Using in(kernel.algebra);
  if (names.empty()) throw std::invalid_argument("--stage-at names no value");
  // The cut: each name's last assignment.
  std::vector<size_t> cut;
  for (const auto& n : names) {
    size_t found = kernel.values.size();
    for (size_t v = 0; v < kernel.values.size(); ++v)
      if (kernel.values[v].name == n) found = v;
    if (found == kernel.values.size()) {
      std::vector<std::string> assigned;
      for (const auto& v : kernel.values)
        if (std::find(assigned.begin(), assigned.end(), v.name) == assigned.end()) assigned.push_back(v.name);
      throw std::invalid_argument("--stage-at names '" + n + "', which the script does not assign (it assigns: " +
                                  join(assigned) + ")");
    }
    if (std::any_of(kernel.outputs.begin(), kernel.outputs.end(), [&](const KernelOutput& o) { return o.value == static_cast<int>(found); }))
      throw std::invalid_argument("--stage-at names '" + n + "', which is an output; name a value the outputs are computed from");
    if (kernel.values[found].blades.empty())
      throw std::invalid_argument("--stage-at names '" + n + "', which is identically 0");
    if (std::find(cut.begin(), cut.end(), found) != cut.end())
      throw std::invalid_argument("--stage-at names '" + n + "' twice");
    cut.push_back(found);
  }

  // The prepared array's name and its symbols (fresh: the values' own symbols may print like other names).
  std::string prepared_name = "prepared";
  auto taken = [&](const std::string& p) {
    return std::any_of(kernel.inputs.begin(), kernel.inputs.end(), [&](const KernelInput& i) {
      return i.name == p || std::any_of(i.symbols.begin(), i.symbols.end(),
                                        [&](const realsymbol& s) { return s.get_name().rfind(p, 0) == 0; });
    });
  };
  while (taken(prepared_name)) prepared_name += "_";
  KernelInput prepared;
  prepared.name = prepared_name;
  prepared.is_multivector = true;
  std::vector<std::string> labels;
  exmap to_prepared;
  for (size_t c : cut) {
    const KernelValue& v = kernel.values[c];
    for (size_t b = 0; b < v.blades.size(); ++b) {
      realsymbol s(prepared_name + "_" + std::to_string(prepared.symbols.size()));
      to_prepared[v.symbols[b]] = s;
      prepared.symbols.push_back(s);
      prepared.blades.push_back(0);
      labels.push_back(v.name + "." + algebra::blade_name(v.blades[b]));
    }
  }

  // The body: every later value with the cut values read from `prepared`, and what the outputs still need.
  Kernel second = kernel;
  second.uniforms.clear();
  {
    std::vector<KernelValue> values = kernel.values;
    for (auto& v : values)
      for (auto& c : v.coeffs) c = c.subs(to_prepared, subs_options::no_pattern);
    Kernel probe = kernel;
    probe.values = values;
    ExSet wanted;
    for (const auto& o : kernel.outputs)
      wanted.insert(kernel.values[o.value].symbols.begin(), kernel.values[o.value].symbols.end());
    std::vector<bool> need = needed_values(probe, wanted);
    for (size_t c : cut) need[c] = false;
    ExSet used;
    std::map<size_t, int> index;
    second.values.clear();
    for (size_t v = 0; v < values.size(); ++v) {
      if (!need[v]) continue;
      index[v] = static_cast<int>(second.values.size());
      second.values.push_back(values[v]);
      for (const auto& c : values[v].coeffs) collect_symbols(c, used);
    }
    for (auto& o : second.outputs) o.value = index.at(static_cast<size_t>(o.value));
    second.inputs = {prepared};
    for (const auto& i : inputs_used(kernel, used)) second.inputs.push_back(i);
  }

  // The prepare: the cut values and what they read.
  Kernel first = kernel;
  first.uniforms.clear();
  first.outputs.clear();
  {
    ExSet wanted;
    for (size_t c : cut) wanted.insert(kernel.values[c].symbols.begin(), kernel.values[c].symbols.end());
    const std::vector<bool> need = needed_values(kernel, wanted);
    ExSet used;
    std::vector<KernelValue> values;
    std::map<size_t, int> index;
    for (size_t v = 0; v < kernel.values.size(); ++v) {
      if (!need[v]) continue;
      index[v] = static_cast<int>(values.size());
      values.push_back(kernel.values[v]);
      for (const auto& c : kernel.values[v].coeffs) collect_symbols(c, used);
    }
    first.values = values;
    // Every input the body does not read, in input order (unread ones too): the prepare's parameters are then
    // the same whichever outputs the body keeps, so one prepare serves a kernel and its --outputs variants.
    first.inputs.clear();
    for (const auto& i : kernel.inputs)
      if (std::none_of(second.inputs.begin(), second.inputs.end(), [&](const KernelInput& b) { return b.name == i.name; }))
        first.inputs.push_back(i);
    for (const auto& i : inputs_used(kernel, used))
      if (std::none_of(first.inputs.begin(), first.inputs.end(), [&](const KernelInput& a) { return a.name == i.name; }))
        throw std::invalid_argument("--stage-at " + join(names) + ": input '" + i.name +
                                    "' is read both before the cut (by the named values) and after it");
    for (size_t c : cut)
      first.outputs.push_back({kernel.values[c].name, kernel.values[c].loc, index.at(c), kernel.values[c].blades, false});
  }

  std::erase_if(first.normalized, [&](const UniformName& n) {
    return std::none_of(first.inputs.begin(), first.inputs.end(), [&](const KernelInput& i) { return i.name == n.name; });
  });
  std::erase_if(second.normalized, [&](const UniformName& n) {
    return std::none_of(second.inputs.begin(), second.inputs.end(), [&](const KernelInput& i) { return i.name == n.name; });
  });

  StagedProgram sp;
  first.name = kernel.name + "_prepare";
  Program pre = optimize(first, level);
  // The named values' coefficients as one output, in the order of the names.
  ProgramOutput out{prepared_name, {}};
  for (const auto& o : pre.outputs)
    for (const auto& s : o.slots) out.slots.push_back({0, s.value});
  pre.outputs = {out};
  pre.labels[prepared_name] = labels;
  sp.prepare = std::move(pre);
  sp.body = optimize(second, level);
  sp.body.labels[prepared_name] = labels;
  for (const auto& i : first.inputs) sp.uniforms.push_back(i.name);
  sp.at = names;
  return sp;
}

}  // namespace cgagen::opt
