// Helpers the optimizer's files share (levels.cpp, pipeline.cpp, pass_*.cpp): expression predicates,
// fraction and collection forms (forms.cpp), identifier generation and the CGAGEN_TIMING phase timer.
// Not part of the opt library's interface (program.hpp is).
#pragma once

#include <ginac/ginac.h>

#include <chrono>
#include <cstdlib>
#include <iostream>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "opt/program.hpp"
#include "symbolic/dag.hpp"

namespace cgagen::opt::detail {

using ExSet = std::set<GiNaC::ex, GiNaC::ex_is_less>;
using ExMap = std::map<GiNaC::ex, GiNaC::ex, GiNaC::ex_is_less>;
// Memo tables that are only looked up, never iterated (their order cannot reach the output): hashed.
using ExMemo = symbolic::ExHashMap<GiNaC::ex>;

// subs() options for maps whose keys are all symbols: no pattern matching, and no scan of the whole map
// for product patterns at every sum and product (seconds with thousands of keys).
constexpr unsigned kSymbolSubs = GiNaC::subs_options::no_pattern | GiNaC::subs_options::pattern_is_not_product;

// CGAGEN_TIMING=1 prints how long each optimizer phase takes (to stderr), for finding hot spots.
class PhaseTimer {
 public:
  explicit PhaseTimer(std::string what) : what_(std::move(what)), start_(std::chrono::steady_clock::now()) {}
  ~PhaseTimer() {
    static const bool on = std::getenv("CGAGEN_TIMING") != nullptr;
    if (!on) return;
    auto ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count();
    std::cerr << "cgagen timing: " << what_ << " " << ms << " ms\n";
  }
 private:
  std::string what_;
  std::chrono::steady_clock::time_point start_;
};

// The size of e for the work budget: its symbol occurrences. Unlike a node count this does not depend on
// GiNaC's process-dependent choices ((a-b)*x or -(b-a)*x), so budget decisions and notes are the same in
// every process.
size_t tree_size(const GiNaC::ex& e);
// The size of e as printed (lower.hpp's rules): its symbol occurrences with an integer power x^k counted |k|
// times (x*x*...*x), so that a short sum of high powers is as large as the code it becomes.
size_t printed_size(const GiNaC::ex& e);
bool is_atomic(const GiNaC::ex& e);
bool has_denominator(const GiNaC::ex& e);
void collect_symbols(const GiNaC::ex& e, ExSet& out);

// A coefficient as numerator / denominator, both expanded polynomials (in symbols and function calls).
struct Rat {
  GiNaC::ex num, den = 1;
  GiNaC::ex value() const { return den.is_equal(1) ? num : num / den; }
};
Rat canonical(const GiNaC::ex& e);
// Brings a small output coefficient with denominators over one common denominator when that makes it
// shorter (u.u - 1 with u = x/n folds to 0 or to a plain expression).
Rat combine_fractions(const Rat& r);
// True when combine_fractions(r) certainly returns r as it is (no denominator; too many terms; or, with
// large roots and calls kept opaque, no denominator outside them).
bool combine_keeps(const Rat& r);
// An upper estimate of the number of terms of expand(e) when the symbols in `sizes` stand for sums of that
// many terms (used to keep -O1 from expanding products of large values).
double estimate_terms(const GiNaC::ex& e, const std::map<GiNaC::ex, double, GiNaC::ex_is_less>& sizes);
// e (an expanded sum) collected recursively: a polynomial in xs[0] whose coefficients are polynomials in
// xs[1], and so on (see forms.cpp).
GiNaC::ex collect_in(const GiNaC::ex& e, const std::vector<GiNaC::ex>& xs);

// Unique identifier generation, avoiding the inputs' names.
class Namer {
 public:
  explicit Namer(const std::vector<KernelInput>& inputs) {
    for (const auto& in : inputs) {
      taken_.insert(in.name);
      for (const auto& s : in.symbols) taken_.insert(s.get_name());
    }
  }
  // base, or base with as few '_' appended as make it new. The search for a base resumes where its last one
  // ended (a script that assigns one name a thousand times would otherwise retry every shorter name).
  std::string fresh(const std::string& base) {
    auto last = last_.find(base);
    std::string name = last == last_.end() ? base : last->second;
    while (taken_.count(name)) name += "_";
    taken_.insert(name);
    last_[base] = name;
    return name;
  }
 private:
  std::set<std::string> taken_;
  std::map<std::string, std::string> last_;  // base -> the name fresh() gave it last
};

}  // namespace cgagen::opt::detail
