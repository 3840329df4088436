// The expander's class (internal to the expand stage): one Expander walks one script. Its jobs live in one
// file each:
//   statements.cpp  the run, statements, macros and calls (and expand(), the stage's entry, expand.hpp);
//   branches.cpp    if/else as per-blade selects, and conditions;
//   values.cpp      the kernel's values: recording, binding (cost model, products stage), outputs, inputs;
//   eval.cpp        expressions: names and inputs, operators, product chains as words, division.
// See expand.hpp, kernel.hpp and the "Semantics" section of docs/language.md.
#pragma once

#include <algorithm>
#include <cstddef>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "algebra/algebra.hpp"
#include "expand/algebra_builtins.hpp"
#include "expand/builtins.hpp"
#include "expand/cost.hpp"
#include "expand/hints.hpp"
#include "expand/inverse.hpp"
#include "expand/kernel.hpp"
#include "expand/pragmas.hpp"
#include "expand/words.hpp"
#include "front/parser.hpp"
#include "symbolic/budget.hpp"
#include "symbolic/dag.hpp"
#include "symbolic/multivector.hpp"
#include "symbolic/node_cache.hpp"
#include "symbolic/probes.hpp"
#include "symbolic/select.hpp"
#include "symbolic/zero_test.hpp"

namespace cgagen::expand_detail {

using front::CompileError;
using front::Expr;
using front::SourceLoc;
using front::Stmt;
using expand_builtins::blade_list;
using expand_builtins::describe;
using expand_builtins::magnitude;
using symbolic::Multivector;
using GiNaC::ex;

// "0.5" -> 1/2, "1e-3" -> 1/1000, "12" -> 12, exactly; nullopt for a malformed number.
std::optional<ex> parse_number(const std::string& text);
// A basis vector of the current algebra (CGA: e1 e2 e3 einf e0 ep em), and its value.
bool is_basis_name(const std::string& n);
Multivector basis(const std::string& n);

class Expander : private expand_pragmas::PragmaHost,
                 private expand_builtins::Context,
                 private expand_words::Host {
 public:
  explicit Expander(std::string name, std::vector<std::string> jacobian_wrt = {})
      : jacobian_wrt_(std::move(jacobian_wrt)) {
    kernel_.name = std::move(name);
  }

  Kernel run(const front::Script& script);

 private:
  struct Frame {
    std::string macro;
    const Stmt* def;  // which definition (macros overload by arity)
    std::vector<Multivector> args;
    std::map<std::string, Multivector> locals;
    std::map<std::string, std::string> inlined;  // each local's name in the inlined script (macro_M_k)
  };
  struct Mark {
    std::string name;
    SourceLoc loc;
  };
  Kernel kernel_;
  std::string statement_name_;           // the top-level statement being expanded (names its bound parts)
  std::map<std::string, int> parts_;     // bound parts per statement name
  std::map<std::string, Multivector> globals_;     // current value of every assigned or input name
  // Macros by name, then by arity (the highest _P(n) they use): Gaalop overloads macros by argument count.
  std::map<std::string, std::map<size_t, const Stmt*>> macros_;
  std::map<std::string, int> assignments_;         // times each name was assigned (symbol naming)
  std::map<std::string, int> last_value_;          // index of the last assignment that may be an output
  std::set<std::string> symbol_names_;
  std::vector<Frame> frames_;                      // active macro calls, innermost last
  // Every input's and value's symbol: zero tests of a coefficient through the chain of earlier values.
  symbolic::ZeroTests zeros_;
  std::vector<Mark> marks_;                        // in order of first marking
  std::set<std::string> script_names_;             // every name the script assigns or defines as a macro
  // The names Gaalop's inliner checks a new macro_M_k against: every name a statement of the script (not a
  // macro body) assigns or reads, and every name a call has given a local so far.
  std::set<std::string> inlined_taken_;
  std::map<std::string, int> inlined_suffix_;     // per macro_M_k: the next number to try after it
  std::map<std::string, const Stmt*> latest_macro_;  // the last definition of each macro name
  expand_pragmas::Pragmas pragmas_;
  std::vector<int> evaluated_values_;   // values of '!x = e;' (kept though no output needs them)
  expand_words::Products words_;        // the script's products as words (expand/words.hpp)
  const Expr* statement_value_ = nullptr;  // the right-hand side of the top-level assignment being expanded
  // Set when that right-hand side is itself a product chain: the word it was evaluated as.
  std::optional<std::pair<algebra::ProductKind, expand_words::Word>> statement_word_;

  // The current algebra's built-in macros (algebra_builtins.cpp; none for CGA), defined before the script
  // so that a script's own definition of the same name replaces them.
  std::unique_ptr<front::SourceFile> prelude_file_;
  std::unique_ptr<front::Script> prelude_;
  void define_algebra_builtins();

  bool is_algebra_builtin(const Stmt* def) const;

  // ---- statements --------------------------------------------------------------------------------

  // Every name the script assigns or defines as a macro, inside if/else branches too; and into
  // inlined_taken_, every name its statements assign or read.
  void collect_script_names(const std::vector<front::StmtPtr>& statements);

  // The name a local k of macro M takes in one call, as Gaalop's inliner names it: macro_M_k, or where
  // that name is taken, macro_M_k1, macro_M_k2, ... (the first free one). Each call renames every local.
  std::string inlined_name(const std::string& macro, const std::string& local);

  void exec_top(const Stmt& s);

  // ---- if / else ----------------------------------------------------------------------------------
  // Both branches are expanded, each from the state before the 'if'. Afterwards every name that either
  // branch assigns holds, per blade, select(condition, its value at the end of the then-branch, its value at
  // the end of the else-branch); a branch that leaves the name alone contributes the value from before the
  // 'if', or 0 where the name had none. No branch is taken at run time: the kernel stays straight-line code.
  std::vector<std::vector<std::string>*> assigned_in_branch_;  // names assigned, per active branch

  void exec_if(const Stmt& s);

  // An if condition over scalars.
  symbolic::Condition condition(const Expr& e);

  ex condition_operand(const Expr& e);

  void exec_local(const Stmt& s);

  // An output marked inside a macro: named as the call renamed the local (inlined_name), so each call of
  // the macro gives an output of its own (macro_M_k, then macro_M_k1, ...), as in Gaalop.
  void macro_output(const Stmt& s, const Multivector& v);

  void check_assignable(const Stmt& s);

  void define_macro(const Stmt& s);

  std::string unique_symbol_name(const std::string& wanted);

  // One KernelValue per assignment; later statements see the name through the value's own symbols.
  void record_value(const Stmt& s, const Multivector& v, bool bind = true);

  // A part of the current statement bound to temporaries by the cost model (expand/cost.hpp): a value of
  // the kernel that no name refers to; later products see its blades' symbols.
  Multivector bind_part(const Multivector& v, SourceLoc loc);

  Multivector bind_if_long(const Multivector& m, SourceLoc loc) override;

  // A product of a and b, with the operands the cost model picks bound to temporaries first.
  Multivector product(algebra::ProductKind kind, Multivector a, Multivector b, SourceLoc loc);

  // ---- the products stage (expand/words.hpp) -------------------------------------------------------

  Multivector multiply(algebra::ProductKind kind, const Multivector& a, const Multivector& b, SourceLoc loc) override;

  Multivector bind_word(std::string& name, const Multivector& v, SourceLoc loc) override;

  // The product kind of a chain expression: a geometric or outer product, or the reverse of one.
  static std::optional<algebra::ProductKind> chain_kind(const Expr& e);

  // The factors of a chain of products of `kind`, in order, each evaluated once, left to right as written.
  void flatten(const Expr& e, algebra::ProductKind kind, expand_words::Word& out, ex& coeff);

  Multivector eval_chain(const Expr& e, algebra::ProductKind kind);

  static Multivector reference(const KernelValue& kv);

  // v as a kernel value: one symbol per blade whose coefficient is not identically zero.
  KernelValue value_of(const std::string& name, const std::string& symbol_base, SourceLoc loc, const Multivector& v);

  // Values that no output needs (directly or through other values) are not part of the kernel: -O0 would
  // emit them as dead temporaries (e.g. the inputs of a rotated point's square that cancels to 0).
  void drop_unused_values();

  void mark(const std::string& name, SourceLoc loc);

  void finish_outputs();

  // `#pragma jacobian` and --jacobian (expand/jacobian.cpp): the derivative outputs, OUT_d_IN (a multivector
  // input's coefficient: OUT_d_IN_BLADE), each over OUT's blades, from derivative values built by the chain
  // rule through the kernel's values.
  void apply_jacobians();
  void reverse_jacobian(const std::vector<size_t>& outputs, const std::vector<std::pair<GiNaC::ex, std::string>>& wrt);
  const std::vector<std::pair<GiNaC::ex, GiNaC::ex>>& partials_of(size_t value, size_t blade);
  std::map<std::pair<size_t, size_t>, std::vector<std::pair<GiNaC::ex, GiNaC::ex>>> partials_;
  std::vector<std::string> jacobian_wrt_;  // --jacobian: every output with respect to these inputs

  // ---- what pragmas ask of the expander (expand/pragmas.hpp) -----------------------------------------

  bool is_basis_name(const std::string& name) const override { return expand_detail::is_basis_name(name); }
  bool is_assigned(const std::string& name) const override { return script_names_.count(name) > 0; }
  bool is_defined(const std::string& name) const override { return globals_.count(name) > 0; }
  void declare_input(const std::string& name, const std::vector<algebra::BladeIndex>& blades) override;

  // ---- zero tests through the value chain (symbolic/zero_test.hpp) --------------------------------

  bool vanishes(const ex& c) override { return zeros_.vanishes(c); }

  // Statements see earlier values only through their symbols, so an identity that holds for the values
  // (c*einf*c is a vector when c is a 2-blade) is invisible here. Where it matters (a divisor, a function
  // argument, the argument of exp) the blades that must vanish are checked with the values inlined.
  template <class MustVanish>
  Multivector drop_vanishing(const Multivector& m, MustVanish must_vanish) {
    return m.without([&](algebra::BladeIndex b, const ex& c) { return must_vanish(b) && vanishes(c); });
  }

  Multivector scalar_part_if_scalar(const Multivector& m) override {
    return m.is_scalar() ? m : drop_vanishing(m, [](algebra::BladeIndex b) { return b != 0; });
  }

  Multivector bivector_part_if_bivector(const Multivector& m) override {
    return drop_vanishing(m, [](algebra::BladeIndex b) { return algebra::blade_grade(b) != 2; });
  }

  // ---- expressions -------------------------------------------------------------------------------

  Multivector lookup(const Expr& e);

  // A free name becomes an input; when it is one edit from a name the script or the language knows, that
  // is more likely a typo (eiof for einf) than a new input, and silently wrong code: warn.
  // Variables first (short ones too: Tt for T), then functions (expand/hints.hpp).
  void warn_if_typo(const std::string& n, SourceLoc loc);

  Multivector eval(const Expr& e);

  Multivector divide(const Multivector& a, const Multivector& b_in, const Expr& be) override;

  // Is b the value of a name the script declares a versor (`#pragma versor`, or a `normalized` input)?
  bool declared_versor(const Multivector& b) const;

  // Runs f, turning GiNaC's arithmetic faults (division by zero, ...) into diagnostics at loc.
  template <class F>
  Multivector guarded(SourceLoc loc, F&& f) {
    try {
      return f();
    } catch (const CompileError&) {
      throw;
    } catch (const symbolic::BudgetExceeded&) {
      throw;  // reported for the whole statement
    } catch (const std::exception& ex) {
      throw CompileError(loc, std::string("cannot evaluate: ") + ex.what());
    }
  }

  static void check_arity(const Expr& e, const std::vector<size_t>& arities);

  Multivector call(const Expr& e);

  // The highest _P(n) a macro's body and result use.
  static size_t macro_arity(const Stmt& def);

  Multivector call_macro(const Stmt& def, std::vector<Multivector> args, const Expr& e);
};

}  // namespace cgagen::expand_detail
