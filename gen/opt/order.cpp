// The print order of a Program's assignments (order.hpp).
#include "opt/order.hpp"

#include <algorithm>
#include <map>

#include "opt/internal.hpp"

namespace cgagen::opt {

using namespace GiNaC;
using detail::ExSet;

std::vector<Assignment> print_order(const Program& program) {
  std::map<ex, size_t, ex_is_less> temp_index;
  for (size_t i = 0; i < program.temps.size(); ++i) temp_index[program.temps[i].sym] = i;
  ExSet array_inputs;
  for (const auto& in : program.inputs)
    if (in.is_multivector) array_inputs.insert(in.symbols.begin(), in.symbols.end());

  // For an expression: 1 + the last temporary it reads (0: none), and whether it reads a multivector input.
  struct Reads {
    size_t after = 0;
    bool array_input = false;
  };
  auto reads = [&](const ex& e) {
    ExSet syms;
    detail::collect_symbols(e, syms);
    Reads r;
    for (const auto& s : syms) {
      if (auto it = temp_index.find(s); it != temp_index.end()) r.after = std::max(r.after, it->second + 1);
      r.array_input |= array_inputs.count(s) > 0;
    }
    return r;
  };

  size_t first_store = 0;  // no output element before this many temporaries
  for (size_t i = 0; i < program.temps.size(); ++i)
    if (!array_inputs.empty() && reads(program.temps[i].value).array_input) first_store = i + 1;
  // bucket[p]: the output elements printed right after the first p temporaries.
  std::vector<std::vector<Assignment>> bucket(program.temps.size() + 1);
  bool pinned = false;  // an output element reads a multivector input: all outputs after the temporaries
  for (size_t o = 0; o < program.outputs.size() && !pinned; ++o)
    for (size_t k = 0; k < program.outputs[o].slots.size(); ++k) {
      const Reads r = reads(program.outputs[o].slots[k].value);
      if (r.array_input) {
        pinned = true;
        break;
      }
      bucket[std::max(r.after, first_store)].push_back({Assignment::Kind::Output, o, k});
    }

  std::vector<Assignment> order;
  if (pinned) {
    for (size_t i = 0; i < program.temps.size(); ++i) order.push_back({Assignment::Kind::Temp, i, 0});
    for (size_t o = 0; o < program.outputs.size(); ++o)
      for (size_t k = 0; k < program.outputs[o].slots.size(); ++k) order.push_back({Assignment::Kind::Output, o, k});
    return order;
  }
  order.insert(order.end(), bucket[0].begin(), bucket[0].end());
  for (size_t i = 0; i < program.temps.size(); ++i) {
    order.push_back({Assignment::Kind::Temp, i, 0});
    order.insert(order.end(), bucket[i + 1].begin(), bucket[i + 1].end());
  }
  return order;
}

}  // namespace cgagen::opt
