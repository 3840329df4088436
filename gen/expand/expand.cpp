// The expander: evaluates a parsed CluScript statement by statement into symbolic multivectors and
// records the Kernel (inputs, one value per assignment, outputs, ranges). See expand.hpp, kernel.hpp
// and the "Semantics" section of docs/language.md.
#include "expand/expand.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <sstream>

#include "algebra/algebra.hpp"
#include "expand/algebra_builtins.hpp"
#include "expand/builtins.hpp"
#include "expand/cost.hpp"
#include "expand/hints.hpp"
#include "expand/inverse.hpp"
#include "expand/pragmas.hpp"
#include "expand/words.hpp"
#include "front/parser.hpp"
#include "symbolic/budget.hpp"
#include "symbolic/node_cache.hpp"
#include "symbolic/dag.hpp"
#include "symbolic/multivector.hpp"
#include "symbolic/probes.hpp"
#include "symbolic/select.hpp"
#include "symbolic/zero_test.hpp"

namespace cgagen {
namespace {


using front::CompileError;
using front::Expr;
using front::SourceLoc;
using front::Stmt;
using expand_builtins::blade_list;
using expand_builtins::describe;
using expand_builtins::magnitude;
using symbolic::Multivector;
using GiNaC::ex;

// "0.5" -> 1/2, "1e-3" -> 1/1000, "12" -> 12, exactly.
std::optional<ex> parse_number(const std::string& text) {
  std::string digits;
  int frac = 0;
  size_t i = 0;
  bool dot = false, any = false;
  for (; i < text.size(); ++i) {
    char c = text[i];
    if (c >= '0' && c <= '9') {
      digits += c;
      any = true;
      if (dot) ++frac;
    } else if (c == '.' && !dot) {
      dot = true;
    } else {
      break;
    }
  }
  if (!any) return std::nullopt;
  long exponent = 0;
  if (i < text.size()) {
    if (text[i] != 'e' && text[i] != 'E') return std::nullopt;
    ++i;
    std::string e = text.substr(i);
    if (e.empty()) return std::nullopt;
    size_t j = (e[0] == '+' || e[0] == '-') ? 1 : 0;
    if (j == e.size() || e.find_first_not_of("0123456789", j) != std::string::npos || e.size() > 6)
      return std::nullopt;
    exponent = std::strtol(e.c_str(), nullptr, 10);
  }
  digits.erase(0, std::min(digits.find_first_not_of('0'), digits.size()));
  GiNaC::numeric value = digits.empty() ? GiNaC::numeric(0) : GiNaC::numeric(digits.c_str());
  long scale = exponent - frac;
  GiNaC::numeric ten(10);
  if (scale >= 0) value *= GiNaC::pow(ten, GiNaC::numeric(scale));
  else value /= GiNaC::pow(ten, GiNaC::numeric(-scale));
  return ex(value);
}

bool is_basis_name(const std::string& n) {
  if (!expand_algebra::is_cga()) return expand_algebra::is_basis_name(n);  // the algebra's own names
  static const std::set<std::string> names = {"e1", "e2", "e3", "einf", "e0", "ep", "em"};
  return names.count(n) > 0;
}

Multivector basis(const std::string& n) {
  if (!expand_algebra::is_cga()) return expand_algebra::basis(n);
  if (n == "e1") return Multivector::e1();
  if (n == "e2") return Multivector::e2();
  if (n == "e3") return Multivector::e3();
  if (n == "einf") return Multivector::einf();
  if (n == "e0") return Multivector::e0();
  const Multivector half_inf = Multivector::blade(4, GiNaC::numeric(1, 2));
  if (n == "ep") return half_inf - Multivector::e0();
  return half_inf + Multivector::e0();  // em
}

class Expander : private expand_pragmas::PragmaHost,
                 private expand_builtins::Context,
                 private expand_words::Host {
 public:
  explicit Expander(std::string name) { kernel_.name = std::move(name); }

  Kernel run(const front::Script& script) {
    symbolic::NodeCacheScope caches;
    size_t spent = 0;
    define_algebra_builtins();
    for (const auto& [loc, message] : script.warnings) kernel_.warnings.push_back({loc, message});
    collect_script_names(script.statements);
    for (const auto& s : script.statements) {
      // GiNaC's own faults (a pole, an overflow) anywhere in a statement become a diagnostic, not a crash.
      // The work budget is per statement: a script of many small statements compiles in time linear in
      // its length, and only a statement that is itself too large is refused.
      try {
        symbolic::WorkBudget budget;
        statement_name_ = s->kind == Stmt::Kind::Assign ? s->name : "statement";
        exec_top(*s);
        spent += budget.spent();
      } catch (const CompileError&) {
        throw;
      } catch (const symbolic::BudgetExceeded& ex) {
        std::string what = s->kind == Stmt::Kind::Assign ? "statement '" + s->name + "'" : "this statement";
        throw CompileError(s->loc, what + " is over cgagen's work budget: " + ex.what() +
                                       "; split it into smaller statements or give fewer blades");
      } catch (const std::exception& ex) {
        throw CompileError(s->loc, std::string("cannot evaluate: ") + ex.what());
      }
    }
    if (std::getenv("CGAGEN_TIMING")) std::fprintf(stderr, "cgagen budget: %zu terms\n", spent);
    for (const auto& v : pragmas_.versors())
      if (!globals_.count(v.name))
        throw CompileError(v.loc, "'#pragma versor': '" + v.name + "' is neither an input nor a name the script assigns");
    finish_outputs();
    drop_unused_values();
    pragmas_.apply_in2out(kernel_);
    kernel_.shared_products = words_.report();
    return std::move(kernel_);
  }

 private:
  struct Frame {
    std::string macro;
    const Stmt* def;  // which definition (macros overload by arity)
    std::vector<Multivector> args;
    std::map<std::string, Multivector> locals;
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
  void define_algebra_builtins() {
    const std::string text = expand_algebra::prelude();
    if (text.empty()) return;
    prelude_file_ = std::make_unique<front::SourceFile>("<" + algebra::current().name() + " built-ins>", text);
    prelude_ = std::make_unique<front::Script>(front::parse(*prelude_file_));
    for (const auto& s : prelude_->statements) define_macro(*s);
  }

  bool is_algebra_builtin(const Stmt* def) const {
    if (!prelude_) return false;
    for (const auto& s : prelude_->statements)
      if (s.get() == def) return true;
    return false;
  }

  // ---- statements --------------------------------------------------------------------------------

  // Every name the script assigns or defines as a macro, inside if/else branches too.
  void collect_script_names(const std::vector<front::StmtPtr>& statements) {
    for (const auto& s : statements) {
      if (s->kind == Stmt::Kind::Assign || s->kind == Stmt::Kind::MacroDef) script_names_.insert(s->name);
      if (s->kind == Stmt::Kind::If) {
        collect_script_names(s->body);
        collect_script_names(s->else_body);
      }
    }
  }

  void exec_top(const Stmt& s) {
    switch (s.kind) {
      case Stmt::Kind::Pragma:
        if (!assigned_in_branch_.empty())
          throw CompileError(s.loc, "'#pragma' inside if/else is not supported: put it before the 'if'");
        pragmas_.apply(s, kernel_, *this);
        return;
      case Stmt::Kind::MacroDef: define_macro(s); return;
      case Stmt::Kind::ExprStmt: eval(*s.value); return;
      case Stmt::Kind::If: exec_if(s); return;
      case Stmt::Kind::Assign: break;
    }
    if (s.value && pragmas_.normalize_outputs() && s.marker == front::Marker::Output) {
      // #pragma normalize: x_unnormalized = e; ?x = x_unnormalized / abs(x_unnormalized);
      check_assignable(s);
      Stmt raw = s;
      raw.name = s.name + "_unnormalized";
      raw.marker = front::Marker::None;
      record_value(raw, eval(*s.value));
      const Multivector& u = globals_.at(raw.name);
      record_value(s, divide(u, magnitude(u), *s.value));
    } else if (s.value) {
      check_assignable(s);
      statement_value_ = s.value.get();
      statement_word_.reset();
      Multivector v = eval(*s.value);
      statement_value_ = nullptr;
      record_value(s, v);
      // A name bound to a product chain stands for its word: later chains reuse it (expand/words.hpp).
      if (statement_word_) words_.remember(statement_word_->first, statement_word_->second, globals_.at(s.name), s.name);
    } else if (!globals_.count(s.name) && !last_value_.count(s.name)) {
      throw CompileError(s.loc, "output '" + s.name + "' is never assigned");
    }
    if (s.marker == front::Marker::Output || s.marker == front::Marker::Visual) mark(s.name, s.loc);
  }

  // ---- if / else ----------------------------------------------------------------------------------
  // Both branches are expanded, each from the state before the 'if'. Afterwards every name that either
  // branch assigns holds, per blade, select(condition, its value at the end of the then-branch, its value at
  // the end of the else-branch); a branch that leaves the name alone contributes the value from before the
  // 'if', or 0 where the name had none. No branch is taken at run time: the kernel stays straight-line code.
  std::vector<std::vector<std::string>*> assigned_in_branch_;  // names assigned, per active branch

  void exec_if(const Stmt& s) {
    const symbolic::Condition cond = condition(*s.value);
    const std::map<std::string, Multivector> before = globals_;
    const size_t inputs_at_if = kernel_.inputs.size();
    struct Branch {
      std::vector<std::string> names;  // in order of assignment, with repeats
      std::map<std::string, Multivector> values;
    };
    auto run_branch = [&](const std::vector<front::StmtPtr>& body) {
      Branch b;
      assigned_in_branch_.push_back(&b.names);
      struct Pop {
        std::vector<std::vector<std::string>*>& stack;
        ~Pop() { stack.pop_back(); }
      } pop{assigned_in_branch_};
      for (const auto& st : body) exec_top(*st);
      for (const auto& n : b.names)
        if (auto it = globals_.find(n); it != globals_.end()) b.values[n] = it->second;
      // Back to the state before the 'if', keeping the inputs a branch introduced (a name read before any
      // assignment is an input wherever it is read).
      globals_ = before;
      for (size_t i = inputs_at_if; i < kernel_.inputs.size(); ++i)
        if (!kernel_.inputs[i].is_multivector) globals_[kernel_.inputs[i].name] = Multivector(kernel_.inputs[i].symbols.at(0));
      return b;
    };
    const Branch then_branch = run_branch(s.body);
    const Branch else_branch = run_branch(s.else_body);
    std::vector<std::string> names;
    for (const Branch* b : {&then_branch, &else_branch})
      for (const auto& n : b->names)
        if (std::find(names.begin(), names.end(), n) == names.end()) names.push_back(n);
    for (const auto& n : names) {
      auto side = [&](const Branch& b) {
        if (auto it = b.values.find(n); it != b.values.end()) return it->second;
        if (auto it = globals_.find(n); it != globals_.end()) return it->second;
        return Multivector();
      };
      const Multivector x = side(then_branch), y = side(else_branch);
      std::set<algebra::BladeIndex> blades;
      for (const auto& [b, c] : x.terms()) blades.insert(b);
      for (const auto& [b, c] : y.terms()) blades.insert(b);
      Multivector merged;
      for (auto b : blades) merged.set(b, symbolic::make_select(cond, x.coeff(b), y.coeff(b)));
      Stmt st;
      st.kind = Stmt::Kind::Assign;
      st.loc = s.loc;
      st.name = n;
      record_value(st, merged);
    }
  }

  // An if condition over scalars.
  symbolic::Condition condition(const Expr& e) {
    using Op = symbolic::Condition::Op;
    symbolic::Condition c;
    if (e.kind == Expr::Kind::Logic) {
      c.op = e.text == "!" ? Op::Not : e.text == "&&" ? Op::And : Op::Or;
      c.l = std::make_shared<symbolic::Condition>(condition(*e.args.at(0)));
      if (c.op != Op::Not) c.r = std::make_shared<symbolic::Condition>(condition(*e.args.at(1)));
      return c;
    }
    if (e.kind == Expr::Kind::Compare) {
      static const std::map<std::string, Op> ops = {{"<", Op::Lt}, {"<=", Op::Le}, {">", Op::Gt},
                                                    {">=", Op::Ge}, {"==", Op::Eq}, {"!=", Op::Ne}};
      c.op = ops.at(e.text);
      c.a = condition_operand(*e.args.at(0));
      c.b = condition_operand(*e.args.at(1));
      return c;
    }
    c.op = Op::Ne;  // a scalar alone: true when nonzero
    c.a = condition_operand(e);
    c.b = 0;
    return c;
  }

  ex condition_operand(const Expr& e) {
    const Multivector v = scalar_part_if_scalar(eval(e));
    if (!v.is_scalar())
      throw CompileError(e.loc, "a condition compares scalars; this is " + describe(v) +
                                    " (compare a coefficient, coefficient(v, e1), or a magnitude, abs(v))");
    const ex c = v.scalar();
    if (GiNaC::is_a<GiNaC::numeric>(c) && !GiNaC::ex_to<GiNaC::numeric>(c).is_real())
      throw CompileError(e.loc, "a condition compares real numbers; this one is complex");
    return c;
  }

  void exec_local(const Stmt& s) {
    switch (s.kind) {
      case Stmt::Kind::If:
        throw CompileError(s.loc, "if/else inside a macro is not supported: put the 'if' around the macro's call");
      case Stmt::Kind::Pragma: throw CompileError(s.loc, "'#pragma' is not allowed inside a macro");
      case Stmt::Kind::MacroDef: define_macro(s); return;
      case Stmt::Kind::ExprStmt: eval(*s.value); return;
      case Stmt::Kind::Assign: break;
    }
    const bool output = s.marker == front::Marker::Output || s.marker == front::Marker::Visual;
    if (!s.value) {
      // "?k;" inside a macro: the local's current value becomes an output, as in Gaalop.
      if (!output) return;
      auto it = frames_.back().locals.find(s.name);
      if (it == frames_.back().locals.end()) throw CompileError(s.loc, "output '" + s.name + "' is never assigned");
      macro_output(s, it->second);
      return;
    }
    check_assignable(s);
    Multivector v = eval(*s.value);
    frames_.back().locals[s.name] = v;
    if (output) macro_output(s, v);  // "?k = e;" inside a macro: also an output (Gaalop's QuestionLineMacro)
  }

  // An output marked inside a macro: named after the local, or MACRO_local where the script has a top-level
  // name of that spelling. A macro called twice outputs the value of its last call (the last assignment).
  void macro_output(const Stmt& s, const Multivector& v) {
    Stmt out = s;
    out.name = script_names_.count(s.name) ? frames_.back().macro + "_" + s.name : s.name;
    record_value(out, v, /*bind=*/false);
    mark(out.name, s.loc);
  }

  void check_assignable(const Stmt& s) {
    if (is_basis_name(s.name)) throw CompileError(s.loc, "cannot assign to basis vector '" + s.name + "'");
    if (macros_.count(s.name)) throw CompileError(s.loc, "cannot assign to '" + s.name + "': it is a macro");
  }

  void define_macro(const Stmt& s) {
    if (is_basis_name(s.name)) throw CompileError(s.loc, "cannot define a macro named '" + s.name + "'");
    macros_[s.name][macro_arity(s)] = &s;
    latest_macro_[s.name] = &s;
  }

  std::string unique_symbol_name(const std::string& wanted) {
    std::string n = wanted;
    for (int k = 2; symbol_names_.count(n); ++k) n = wanted + "_" + std::to_string(k);
    symbol_names_.insert(n);
    return n;
  }

  // One KernelValue per assignment; later statements see the name through the value's own symbols.
  void record_value(const Stmt& s, const Multivector& v, bool bind = true) {
    int count = ++assignments_[s.name];
    KernelValue kv = value_of(s.name, count == 1 ? s.name : s.name + "_" + std::to_string(count), s.loc, v);
    if (bind) globals_[s.name] = reference(kv);  // (a macro's output does not become a global name)
    if (bind)
      for (auto* names : assigned_in_branch_) names->push_back(s.name);
    if (s.marker == front::Marker::EvalOnly) evaluated_values_.push_back(static_cast<int>(kernel_.values.size()));
    if (s.marker != front::Marker::EvalOnly) last_value_[s.name] = static_cast<int>(kernel_.values.size());
    kernel_.values.push_back(std::move(kv));
  }

  // A part of the current statement bound to temporaries by the cost model (expand/cost.hpp): a value of
  // the kernel that no name refers to; later products see its blades' symbols.
  Multivector bind_part(const Multivector& v, SourceLoc loc) {
    const std::string name = statement_name_ + "_part" + std::to_string(++parts_[statement_name_]);
    KernelValue kv = value_of(name, name, loc, v);
    Multivector ref = reference(kv);
    kernel_.values.push_back(std::move(kv));
    return ref;
  }

  Multivector bind_if_long(const Multivector& m, SourceLoc loc) override {
    for (const auto& [b, c] : m.terms())
      if (symbolic::tree_larger_than(c, expand_cost::kBindArgumentNodes)) return bind_part(m, loc);
    return m;
  }

  // A product of a and b, with the operands the cost model picks bound to temporaries first.
  Multivector product(algebra::ProductKind kind, Multivector a, Multivector b, SourceLoc loc) {
    const expand_cost::BindPlan plan = expand_cost::plan_product(kind, a, b);
    if (plan.a) a = bind_part(a, loc);
    if (plan.b) b = bind_part(b, loc);
    switch (kind) {
      case algebra::ProductKind::Geometric: return a * b;
      case algebra::ProductKind::Outer: return a ^ b;
      default: return inner(a, b);
    }
  }

  // ---- the products stage (expand/words.hpp) -------------------------------------------------------

  Multivector multiply(algebra::ProductKind kind, const Multivector& a, const Multivector& b, SourceLoc loc) override {
    return product(kind, a, b, loc);
  }

  Multivector bind_word(std::string& name, const Multivector& v, SourceLoc loc) override {
    if (name.empty()) name = statement_name_ + "_prod" + std::to_string(++parts_[statement_name_ + " prod"]);
    KernelValue kv = value_of(name, name, loc, v);
    Multivector ref = reference(kv);
    kernel_.values.push_back(std::move(kv));
    return ref;
  }

  // The product kind of a chain expression: a geometric or outer product, or the reverse of one.
  static std::optional<algebra::ProductKind> chain_kind(const Expr& e) {
    if (e.kind == Expr::Kind::Binary && e.binary_op == front::BinaryOp::Geo) return algebra::ProductKind::Geometric;
    if (e.kind == Expr::Kind::Binary && e.binary_op == front::BinaryOp::Outer) return algebra::ProductKind::Outer;
    if (e.kind == Expr::Kind::Unary && e.unary_op == front::UnaryOp::Reverse) return chain_kind(*e.args.at(0));
    return std::nullopt;
  }

  // The factors of a chain of products of `kind`, in order, each evaluated once, left to right as written.
  void flatten(const Expr& e, algebra::ProductKind kind, expand_words::Word& out) {
    const bool outer = kind == algebra::ProductKind::Outer;
    if (e.kind == Expr::Kind::Binary && e.binary_op == (outer ? front::BinaryOp::Outer : front::BinaryOp::Geo)) {
      if (auto w = outer ? hints::outer_with_number(e) : std::nullopt) hints::warn_once(kernel_.warnings, e.loc, *w);
      flatten(*e.args.at(0), kind, out);
      flatten(*e.args.at(1), kind, out);
      return;
    }
    if (e.kind == Expr::Kind::Unary && e.unary_op == front::UnaryOp::Reverse && chain_kind(*e.args.at(0)) == kind) {
      expand_words::Word inner;
      flatten(*e.args.at(0), kind, inner);
      const expand_words::Word r = expand_words::reversed(inner);
      out.insert(out.end(), r.begin(), r.end());
      return;
    }
    const Multivector v = eval(e);
    const expand_words::Word w = words_.expand(words_.atom(v, e.kind == Expr::Kind::Name ? e.text : ""), kind);
    out.insert(out.end(), w.begin(), w.end());
  }

  Multivector eval_chain(const Expr& e, algebra::ProductKind kind) {
    const bool whole_statement = &e == statement_value_;
    expand_words::Word w;
    flatten(e, kind, w);
    if (whole_statement) statement_word_ = {kind, w};
    return words_.evaluate(kind, w, e.loc, *this);
  }

  static Multivector reference(const KernelValue& kv) {
    Multivector ref;
    for (size_t i = 0; i < kv.blades.size(); ++i) ref.set(kv.blades[i], kv.symbols[i]);
    return ref;
  }

  // v as a kernel value: one symbol per blade whose coefficient is not identically zero.
  KernelValue value_of(const std::string& name, const std::string& symbol_base, SourceLoc loc, const Multivector& v) {
    KernelValue kv;
    kv.name = name;
    kv.loc = loc;
    for (const auto& [b, c] : v.terms()) {
      // A complex constant (sqrt(-4) = 2i, log(-1) = i pi): the targets have real numbers only, and the
      // printers would drop the i (sqrt(-4)*x printed as 2*x). The emitted C would give NaN; say so here.
      // (Each shared node once: coefficients are DAGs whose trees can be exponentially large.)
      if (symbolic::has_nonreal_number(c))
        throw CompileError(loc, "the value of '" + name + "' is complex (a square root or logarithm of a "
                                "negative constant); the generated code computes with real numbers only");
      // Identically zero once earlier values are inlined? Most coefficients are plainly not, and an exact
      // probe says so at once; the others go through the float sample first (sample()).
      std::optional<ex> at_sample;
      if (!zeros_.probably_nonzero(c)) {
        at_sample = zeros_.sample(c);
        if (!at_sample) continue;
      }
      GiNaC::realsymbol sym(unique_symbol_name(symbol_base + "_" + algebra::blade_ident(b)));
      zeros_.define(sym, c, at_sample);
      kv.blades.push_back(b);
      kv.coeffs.push_back(c);
      kv.symbols.push_back(sym);
    }
    return kv;
  }

  // Values that no output needs (directly or through other values) are not part of the kernel: -O0 would
  // emit them as dead temporaries (e.g. the inputs of a rotated point's square that cancels to 0).
  void drop_unused_values() {
    std::set<ex, GiNaC::ex_is_less> needed;
    std::vector<bool> keep(kernel_.values.size(), false);
    for (const auto& o : kernel_.outputs) keep[static_cast<size_t>(o.value)] = true;
    // '!x = e;' and '#pragma onlyEvaluate x' ask for x to be evaluated: their values stay (as in Gaalop).
    for (int i : evaluated_values_) keep[static_cast<size_t>(i)] = true;
    for (size_t i = 0; i < kernel_.values.size(); ++i)
      if (pragmas_.only_evaluate(kernel_.values[i].name)) keep[i] = true;
    for (size_t i = kernel_.values.size(); i-- > 0;) {
      const KernelValue& v = kernel_.values[i];
      if (!keep[i])
        for (const auto& sym : v.symbols)
          if (needed.count(sym)) keep[i] = true;
      if (!keep[i]) continue;
      for (const auto& c : v.coeffs)
        for (auto it = c.preorder_begin(); it != c.preorder_end(); ++it)
          if (GiNaC::is_a<GiNaC::symbol>(*it)) needed.insert(*it);
    }
    std::vector<int> index(kernel_.values.size(), -1);
    std::vector<KernelValue> kept;
    for (size_t i = 0; i < kernel_.values.size(); ++i)
      if (keep[i]) {
        index[i] = static_cast<int>(kept.size());
        kept.push_back(std::move(kernel_.values[i]));
      }
    kernel_.values = std::move(kept);
    for (auto& o : kernel_.outputs) o.value = index[static_cast<size_t>(o.value)];
  }

  void mark(const std::string& name, SourceLoc loc) {
    for (const auto& m : marks_)
      if (m.name == name) return;
    marks_.push_back({name, loc});
  }

  void finish_outputs() {
    pragmas_.check_outputs([&](const std::string& name) {
      return std::any_of(marks_.begin(), marks_.end(), [&](const Mark& m) { return m.name == name; });
    });
    if (marks_.empty()) throw CompileError({1, 1}, "script has no outputs (mark one with ?name)");
    for (const auto& m : marks_) {
      auto it = last_value_.find(m.name);
      if (it == last_value_.end()) throw CompileError(m.loc, "output '" + m.name + "' is never assigned");
      KernelOutput out;
      out.name = m.name;
      out.loc = m.loc;
      out.value = it->second;
      const expand_pragmas::OutputPragma* p = pragmas_.output(m.name);
      out.from_pragma = p != nullptr;
      out.blades = p ? p->blades : kernel_.values[it->second].blades;
      if (out.blades.empty()) out.blades = {0};  // an output that is identically 0: one scalar 0, never a[0]
      kernel_.outputs.push_back(std::move(out));
    }
  }

  // ---- what pragmas ask of the expander (expand/pragmas.hpp) -----------------------------------------

  bool is_basis_name(const std::string& name) const override { return cgagen::is_basis_name(name); }
  bool is_assigned(const std::string& name) const override { return script_names_.count(name) > 0; }
  bool is_defined(const std::string& name) const override { return globals_.count(name) > 0; }
  void declare_input(const std::string& name, const std::vector<algebra::BladeIndex>& blades) override {
    KernelInput in;
    in.name = name;
    in.is_multivector = true;
    in.blades = blades;
    Multivector ref;
    for (auto b : blades) {
      GiNaC::realsymbol sym(unique_symbol_name(name + "_" + algebra::blade_ident(b)));
      zeros_.add_input(sym);
      in.symbols.push_back(sym);
      ref.set(b, sym);
    }
    globals_[name] = ref;
    kernel_.inputs.push_back(std::move(in));
  }

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

  Multivector lookup(const Expr& e) {
    const std::string& n = e.text;
    if (is_basis_name(n)) return basis(n);
    if (!frames_.empty()) {
      auto it = frames_.back().locals.find(n);
      if (it != frames_.back().locals.end()) return it->second;
    }
    auto it = globals_.find(n);
    if (it != globals_.end()) return it->second;
    if (macros_.count(n)) throw CompileError(e.loc, "'" + n + "' is a macro; call it as " + n + "(...)");
    // A free name: a new scalar input, in order of first use.
    warn_if_typo(n, e.loc);
    KernelInput in;
    in.name = n;
    in.blades = {0};
    GiNaC::realsymbol sym(unique_symbol_name(n));  // real: abs(a)^2 is a^2, not a*conjugate(a)
    zeros_.add_input(sym);
    in.symbols = {sym};
    kernel_.inputs.push_back(in);
    Multivector v(sym);
    globals_[n] = v;
    return v;
  }

  // A free name becomes an input; when it is one edit from a name the script or the language knows, that
  // is more likely a typo (eiof for einf) than a new input, and silently wrong code: warn.
  // Variables first (short ones too: Tt for T), then functions (expand/hints.hpp).
  void warn_if_typo(const std::string& n, SourceLoc loc) {
    std::vector<std::string> known = {"e1", "e2", "e3", "einf", "e0", "ep", "em"};
    known.insert(known.end(), script_names_.begin(), script_names_.end());
    const std::vector<std::string> functions = expand_builtins::names();
    if (auto k = hints::for_read(n, known, functions))
      kernel_.warnings.push_back({loc, "'" + n + "' is used before it is assigned and becomes an input; did you mean '" +
                                           *k + "'?"});
  }

  Multivector eval(const Expr& e) {
    switch (e.kind) {
      case Expr::Kind::Number: {
        auto v = parse_number(e.text);
        if (!v) throw CompileError(e.loc, "malformed number '" + e.text + "'");
        return Multivector(*v);
      }
      case Expr::Kind::Name: return lookup(e);
      case Expr::Kind::MacroArg: {
        if (frames_.empty())
          throw CompileError(e.loc, "_P(" + std::to_string(e.index) + ") used outside a macro");
        const Frame& f = frames_.back();
        if (e.index < 1 || e.index > static_cast<int>(f.args.size()))
          throw CompileError(e.loc, "_P(" + std::to_string(e.index) + ") out of range: macro '" + f.macro +
                                        "' was called with " + std::to_string(f.args.size()) + " argument" +
                                        (f.args.size() == 1 ? "" : "s"));
        return f.args[e.index - 1];
      }
      case Expr::Kind::Unary: {
        if (e.unary_op == front::UnaryOp::Reverse)
          if (auto kind = chain_kind(*e.args.at(0))) return eval_chain(e, *kind);
        Multivector a = eval(*e.args.at(0));
        switch (e.unary_op) {
          case front::UnaryOp::Negate: return -a;
          case front::UnaryOp::Reverse: return a.reverse();
          case front::UnaryOp::Dual: return a.dual();
        }
        break;
      }
      case Expr::Kind::Binary: {
        if (auto kind = chain_kind(e)) return eval_chain(e, *kind);
        Multivector a = eval(*e.args.at(0));
        Multivector b = eval(*e.args.at(1));
        switch (e.binary_op) {
          case front::BinaryOp::Add: return a + b;
          case front::BinaryOp::Sub: return a - b;
          case front::BinaryOp::Geo:
          case front::BinaryOp::Outer: break;  // chains (eval_chain)
          case front::BinaryOp::Inner: return product(algebra::ProductKind::Inner, a, b, e.loc);
          case front::BinaryOp::Div: return divide(a, b, *e.args.at(1));
        }
        break;
      }
      case Expr::Kind::Call: return call(e);
      case Expr::Kind::Compare:
      case Expr::Kind::Logic:
        throw CompileError(e.loc, "'" + e.text + "' may only appear in the condition of an 'if'");
    }
    throw CompileError(e.loc, "internal error: unknown expression kind");
  }

  Multivector divide(const Multivector& a, const Multivector& b_in, const Expr& be) override {
    Multivector b = scalar_part_if_scalar(b_in);
    if (b.is_zero()) throw CompileError(be.loc, "division by zero");
    if (b.is_scalar()) return guarded(be.loc, [&] { return a / b.scalar(); });
    return guarded(be.loc, [&] {
      try {
        auto zero = [&](const ex& c) { return vanishes(c); };
        const auto inv = declared_versor(b) ? expand_inverse::versor_inverse(b, zero) : expand_inverse::inverse(b, zero);
        return (a * inv.numerator) / inv.denominator;
      } catch (const expand_inverse::NotInvertible& e) {
        throw CompileError(be.loc, e.message);
      }
    });
  }

  // Is b the value of a name the script declares a versor (`#pragma versor`, or a `normalized` input)?
  bool declared_versor(const Multivector& b) const {
    auto is_value_of = [&](const std::string& name) {
      auto it = globals_.find(name);
      return it != globals_.end() && it->second.terms().size() == b.terms().size() && it->second == b;
    };
    for (const auto& n : pragmas_.versors())
      if (is_value_of(n.name)) return true;
    for (const auto& n : kernel_.normalized)
      if (is_value_of(n.name)) return true;
    return false;
  }

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

  static void check_arity(const Expr& e, const std::vector<size_t>& arities) {
    if (std::find(arities.begin(), arities.end(), e.args.size()) != arities.end()) return;
    std::string counts;
    for (size_t i = 0; i < arities.size(); ++i)
      counts += (i == 0 ? "" : i + 1 == arities.size() ? " or " : ", ") + std::to_string(arities[i]);
    throw CompileError(e.loc, "'" + e.text + "' takes " + counts + " argument" + (arities.back() == 1 ? "" : "s") +
                                  ", got " + std::to_string(e.args.size()));
  }

  Multivector call(const Expr& e) {
    const std::string& fn = e.text;
    std::vector<Multivector> args;
    auto macro = macros_.find(fn);
    if (macro != macros_.end()) {
      for (const auto& a : e.args) args.push_back(eval(*a));
      // The definition for this many arguments, else the latest one (which may use fewer).
      auto by_arity = macro->second.find(args.size());
      const Stmt* def = by_arity != macro->second.end() ? by_arity->second : latest_macro_.at(fn);
      if (!is_algebra_builtin(def)) return call_macro(*def, std::move(args), e);
      try {  // a fault inside a built-in macro is reported at the call: its text is not the script's
        return call_macro(*def, std::move(args), e);
      } catch (const CompileError& x) {
        throw CompileError(e.loc, "in the " + algebra::current().name() + " built-in '" + fn + "': " + x.what());
      }
    }
    const expand_builtins::Builtin* builtin = expand_builtins::find(fn);
    if (!builtin) {
      std::vector<std::string> known = expand_builtins::names();  // functions: macros, built-ins (expand/hints.hpp)
      for (const auto& m : macros_) known.push_back(m.first);
      throw CompileError(e.loc, "unknown function '" + fn + "'" + hints::for_call(fn, known));
    }
    if (builtin->cga_only && !expand_algebra::is_cga())
      throw CompileError(e.loc, "'" + fn + "' is a CGA built-in; the algebra '" + algebra::current().name() +
                                    "' does not have it");
    check_arity(e, builtin->arities);
    for (const auto& a : e.args) args.push_back(eval(*a));
    return guarded(e.loc, [&] { return builtin->define(expand_builtins::Call{fn, args, e, *this}); });
  }

  // The highest _P(n) a macro's body and result use.
  static size_t macro_arity(const Stmt& def) {
    size_t n = 0;
    std::function<void(const Expr&)> walk = [&](const Expr& x) {
      if (x.kind == Expr::Kind::MacroArg && x.index > 0) n = std::max(n, static_cast<size_t>(x.index));
      for (const auto& a : x.args)
        if (a) walk(*a);
    };
    for (const auto& st : def.body)
      if (st->value) walk(*st->value);
    if (def.result) walk(*def.result);
    return n;
  }

  Multivector call_macro(const Stmt& def, std::vector<Multivector> args, const Expr& e) {
    for (size_t i = 0; i < frames_.size(); ++i) {
      if (frames_[i].def != &def) continue;
      std::string chain;
      for (size_t j = i; j < frames_.size(); ++j) chain += "'" + frames_[j].macro + "' -> ";
      throw CompileError(e.loc, "recursive macro call " + chain + "'" + def.name + "'");
    }
    frames_.push_back({def.name, &def, std::move(args), {}});
    for (const auto& s : def.body) exec_local(*s);
    Multivector r = def.result ? eval(*def.result) : Multivector();
    frames_.pop_back();
    return r;
  }
};

}  // namespace

Kernel expand(const front::Script& script, const std::string& kernel_name,
              std::shared_ptr<const algebra::Algebra> algebra) {
  algebra::Using in(std::move(algebra));
  Expander x(kernel_name);
  Kernel k = x.run(script);
  k.algebra = algebra::current_shared();
  return k;
}

}  // namespace cgagen
