// The optimizer levels' shared internals (levels.cpp and the files it drives: level_o0.cpp, substitute.cpp,
// level_o1.cpp, level_o2.cpp, normalized.cpp): the result of substitution, the output slot plan, the statement
// form and the level entry points. Not part of the opt library's interface (program.hpp is).
#pragma once

#include <map>
#include <string>
#include <vector>

#include "opt/internal.hpp"

namespace cgagen::opt::detail {

// Above this size (printed_size: symbol occurrences as printed) of the -O1 form, -O1 emits and -O2 optimizes
// only the script's statement form.
// The bundled runtime kernels stay below 1300; paper A.1 has 8807 and circle3 208494.
constexpr size_t kMaxExpandedNodes = 4000;
// Past this size of the -O1 form (counted while substituting, over the output coefficients that
// combine_fractions keeps as they are and the values kept as temporaries: a lower bound of the final size)
// substitution stops: the statement form is certain, and substituting the rest would only cost time (a
// 200-line dcga script: 2 million symbol occurrences; 400 squarings M = M*M: seconds). The note then says
// "more than".
constexpr size_t kMaxCountedNodes = kMaxExpandedNodes;

// A script value's name as part of an identifier.
std::string sanitize(const std::string& s);
// The names of the temporaries of the kernel's values in order: v_NAME_BLADE for a name's first assignment,
// vN_NAME_BLADE for its N-th (as -O0 prints them). Numbered rather than told apart by appended '_' (which
// Namer would do): 800 assignments to one name would make names, and the canonical keys built from them,
// as long as the script.
class ValueNames {
 public:
  explicit ValueNames(const Kernel& k);
  const std::string& of(size_t value, size_t blade) const { return names_.at(value).at(blade); }
 private:
  std::vector<std::vector<std::string>> names_;
};
// The position of blade b among v's blades, or -1.
int blade_pos(const KernelValue& v, algebra::BladeIndex b);
// An empty program for the kernel at the level (name, algebra, inputs).
Program skeleton(const Kernel& k, Level level);
// Drops the temporaries no output reads, directly or through other temporaries (a value's blade that an
// `#pragma output` leaves out): every target then compiles -O0 and -O1 code without unused variables.
void drop_unread_temps(Program& p);

// Values substituted into each other, only for the coefficients the outputs need. A value coefficient
// whose expansion would be too large keeps its earlier values as temporaries ("materialized").
struct Substituted {
  ExSet needed;                                      // value symbols the outputs need (transitively)
  std::map<GiNaC::ex, Rat, GiNaC::ex_is_less> full;  // value symbol -> coefficient over inputs and materialized
                                                     // values
  std::vector<GiNaC::ex> materialized;               // value symbols kept as temporaries, in kernel order
  // Substitution stopped early: the -O1 form has more than kMaxCountedNodes symbol occurrences, `full`
  // is incomplete and only the statement form is built.
  bool over_count = false;
};

Substituted substitute(const Kernel& k);

// The materialized values as temporaries (named after the script's values).
std::vector<Temp> materialized_temps(const Kernel& k, const Substituted& s);

// The output slots at -O1: each needed blade's substituted coefficient; identically-zero blades dropped
// unless a pragma asked for them.
struct SlotPlan {
  std::string output;
  algebra::BladeIndex blade;
  Rat value;            // over inputs
  GiNaC::ex value_sym;  // the value coefficient's symbol, or 0 for a blade the value lacks
};

std::vector<std::vector<SlotPlan>> plan_slots(const Kernel& k, const Substituted& s);

// The script's own statements as temporaries (each value expanded over earlier values, only those the
// outputs need), and the outputs as the values' symbols. A coefficient that is one input or one number (a
// point's x, its e0 coefficient 1) is substituted into its users instead: as a temporary it would leave
// products like 1*z that nothing folds later.
struct StatementForm {
  std::vector<Temp> temps;
  std::vector<GiNaC::ex> roots;  // one per output slot, in plan order
};

StatementForm statement_form(const Kernel& k, const Substituted& s, const std::vector<std::vector<SlotPlan>>& plans);

// The size (printed_size) of the expanded (-O1) form: what the CSE passes and the printer would work through.
size_t expanded_size(const std::vector<Temp>& kept, const std::vector<std::vector<SlotPlan>>& plans);

// The note a level leaves when it kept the statement form.
std::string over_budget_note(const char* level, size_t size, bool over_count);

// `#pragma normalized` (normalized.cpp): an identity's rewriting rule, the choices of one rule per identity,
// an expanded polynomial rewritten with a choice, and the check that the pragma names multivector inputs.
struct Rule {
  std::vector<std::pair<GiNaC::ex, int>> lead;  // the monomial's symbols and exponents
  GiNaC::ex rhs;                                // what the monomial equals
};
std::vector<std::vector<Rule>> rule_sets(const Kernel& k);
GiNaC::ex reduce_with(GiNaC::ex p, const std::vector<Rule>& rules);
void check_normalized(const Kernel& k);

// The levels.
Program optimize_o0(const Kernel& k);
Program optimize_o1(const Kernel& k, const Substituted& s, const std::vector<std::vector<SlotPlan>>& plans);
Program optimize_o2(const Kernel& k, const Substituted& s, const std::vector<std::vector<SlotPlan>>& plans);

}  // namespace cgagen::opt::detail
