// -O0: every value coefficient of the script that an output reads as a temporary, as written; outputs copy
// the value symbols.
#include "opt/levels.hpp"

namespace cgagen::opt::detail {

using namespace GiNaC;

// -O0: every value coefficient as a temporary, as written.
Program optimize_o0(const Kernel& k) {
  Program p = skeleton(k, Level::O0);
  const ValueNames names(k);
  for (size_t vi = 0; vi < k.values.size(); ++vi) {
    const auto& v = k.values[vi];
    for (size_t i = 0; i < v.blades.size(); ++i) p.temps.push_back({names.of(vi, i), v.symbols[i], v.coeffs[i]});
  }
  for (const auto& o : k.outputs) {
    ProgramOutput po{o.name, {}};
    const auto& v = k.values.at(o.value);
    for (auto b : o.blades) {
      int i = blade_pos(v, b);
      po.slots.push_back({b, i < 0 ? ex(0) : ex(v.symbols[i])});
    }
    p.outputs.push_back(std::move(po));
  }
  drop_unread_temps(p);
  return p;
}
}  // namespace cgagen::opt::detail
