// The script generator of the differential fuzzer (see generator.hpp). Values stay well conditioned:
// inputs in [0.5, 1.5) with either sign, divisors that are invertible by construction, square roots of
// absolute values, trees a few levels deep.
#include "generator.hpp"

#include <vector>

namespace diff {
namespace {

class Gen {
 public:
  explicit Gen(std::uint64_t seed) : state_(seed * 0x9E3779B97F4A7C15ull + 0x632BE59BD9B4E019ull) { next(); }

  Program program() {
    Program p;
    for (const char* n : {"a", "b", "c", "x", "y"}) {
      double m = 0.5 + uniform();
      p.inputs[n] = pick(2) ? -m : m;
    }
    std::string& t = p.text;
    if (pick(3) == 0) t += "#pragma range -2 <= a <= 2\n";
    // A macro or two, over their arguments.
    if (pick(2)) {
      t += "M1 = {\n  t = _P(1) * _P(2);\n  t + _P(1)\n}\n";
      macros_.push_back("M1");
    }
    if (pick(2)) {
      t += "M2 = { " + mv(1, "_P(1)") + " }\n";
      macros1_.push_back("M2");
    }
    const int statements = 1 + pick(4);
    for (int i = 0; i < statements; ++i) {
      std::string name = "v" + std::to_string(i);
      bool out = i == statements - 1 || pick(3) == 0;
      if (out && pick(4) == 0) {
        // An output pragma listing some blades, the scalar as Gaalop writes it (1.0) among them.
        t += "#pragma output " + name + " 1.0 e1 e1^e2 einf\n";
      }
      if (!out && pick(3) == 0) {
        // if/else: the name assigned in one or both branches (else a name assigned before, or none), an
        // output marked inside a branch now and then, sometimes an else-if chain.
        const std::string other = names_.empty() || pick(2) ? name : names_[static_cast<size_t>(pick(static_cast<int>(names_.size())))];
        t += "if (" + condition(2) + ") {\n  " + std::string(pick(3) == 0 ? "?" : "") + name + " = " + mv(2) + ";\n}";
        if (pick(3) == 0) t += " else if (" + condition(1) + ") {\n  " + name + " = " + mv(2) + ";\n}";
        if (pick(4) != 0) t += " else {\n  " + other + " = " + mv(2) + ";\n}";
        t += "\n";
        names_.push_back(name);
        continue;
      }
      t += std::string(out ? "?" : "") + name + " = " + mv(3) + ";\n";
      names_.push_back(name);
    }
    return p;
  }

 private:
  std::uint64_t next() {
    state_ ^= state_ >> 12;
    state_ ^= state_ << 25;
    state_ ^= state_ >> 27;
    return state_ * 0x2545F4914F6CDD1Dull;
  }
  int pick(int n) { return static_cast<int>(next() % static_cast<std::uint64_t>(n)); }
  double uniform() { return static_cast<double>(next() >> 11) / 9007199254740992.0; }

  std::string input() { return std::string(1, "abcxy"[pick(5)]); }
  std::string number() {
    static const char* n[] = {"2", "0.5", "3", "1.25", "1e-1", "0.75"};
    return n[pick(6)];
  }

  // An if condition: comparisons of scalars joined by && || !, a scalar alone now and then.
  std::string condition(int depth) {
    static const char* ops[] = {"<", "<=", ">", ">=", "!=", "=="};
    switch (depth <= 0 ? 0 : pick(6)) {
      case 1: return condition(depth - 1) + " && " + condition(depth - 1);
      case 2: return condition(depth - 1) + " || " + condition(depth - 1);
      case 3: return "!(" + condition(depth - 1) + ")";
      case 4: return "(" + condition(depth - 1) + ")";
      case 5: return sc(1);
      default: {
        const int op = pick(6);
        // == on two computed values is almost never true: compare an input with itself (or its negation).
        if (op == 5) {
          const std::string x = input();
          return x + " == " + (pick(2) ? x : "-" + x);
        }
        return sc(1) + " " + ops[op] + " " + sc(1);
      }
    }
  }

  // A scalar expression.
  std::string sc(int depth) {
    if (depth <= 0) return pick(3) ? input() : number();
    switch (pick(12)) {
      case 0: return sc(depth - 1) + " + " + sc(depth - 1);
      case 1: return sc(depth - 1) + "*" + sc(depth - 1);
      case 2: return "(" + sc(depth - 1) + " - " + sc(depth - 1) + ")";
      case 3: return "sin(" + sc(depth - 1) + ")";
      case 4: return "cos(" + sc(depth - 1) + ")";
      case 5: return "sqrt(abs(" + sc(depth - 1) + "))";
      case 6: return "atan2(" + sc(depth - 1) + ", 2)";
      case 7: return "abs(" + sc(depth - 1) + ")";
      case 8: return "coefficient(" + mv(depth - 1) + ", " + blade() + ")";
      case 9: return "(" + sc(depth - 1) + ")/(" + number() + " + abs(" + sc(depth - 1) + "))";
      case 10: return pick(2) ? "floor(2.5)*" + input() : "ceil(" + number() + ")*" + input();
      default: return "-" + sc(depth - 1);
    }
  }

  std::string blade() {
    static const char* b[] = {"e1", "e2", "e3", "einf", "e0", "e1^e2", "e2^e1", "e1^einf", "e3^e0", "einf^e0", "1"};
    return b[pick(11)];
  }
  std::string basis() {
    static const char* b[] = {"e1", "e2", "e3", "einf", "e0"};
    return b[pick(5)];
  }

  // An invertible divisor: a nonzero scalar, a non-null vector, a translator, a rotor, or exp of a blade.
  std::string divisor() {
    switch (pick(5)) {
      case 0: return "(" + number() + " + abs(" + sc(1) + "))";
      case 1: return "(" + input() + "*e1 + " + number() + "*e2)";
      case 2: return "TranslatorN3(" + sc(1) + ", " + sc(0) + ", " + sc(0) + ")";
      case 3: return "RotorN3(" + input() + ", 1, " + input() + ", " + sc(1) + ")";
      default: return "exp(" + sc(0) + "*e1^e2)";
    }
  }

  std::string mv(int depth, const std::string& extra_leaf = "") {
    if (depth <= 0) {
      switch (pick(extra_leaf.empty() ? 4 : 5)) {
        case 0: return input();
        case 1: return basis();
        case 2: return names_.empty() ? number() : names_[static_cast<size_t>(pick(static_cast<int>(names_.size())))];
        case 3: return input() + "*" + basis();
        default: return extra_leaf;
      }
    }
    const int d = depth - 1;
    switch (pick(24)) {
      case 0: return mv(d, extra_leaf) + " + " + mv(d, extra_leaf);
      case 1: return mv(d, extra_leaf) + " - " + mv(d, extra_leaf);
      case 2: return mv(d, extra_leaf) + "*" + mv(d, extra_leaf);
      case 3: return mv(d, extra_leaf) + "^" + mv(d, extra_leaf);
      case 4: return mv(d, extra_leaf) + " . " + mv(d, extra_leaf);  // spaced: e0.3 would read as e0 .3
      case 5: return "(" + mv(d, extra_leaf) + ")/" + divisor();
      case 6: return "(" + mv(d, extra_leaf) + " + " + mv(d, extra_leaf) + ")*" + mv(d, extra_leaf);
      case 7: return "-" + mv(d, extra_leaf);
      case 8: return "~(" + mv(d, extra_leaf) + ")";
      case 9: return "*(" + mv(d, extra_leaf) + ")";
      case 10: return "VecN3(" + sc(1) + ", " + sc(1) + ", " + sc(0) + ")";
      case 11: return "createPoint(" + sc(0) + ", " + sc(1) + ", " + sc(0) + ")";
      case 12: return pick(2) ? "SphereN3(" + sc(0) + ", " + sc(0) + ", " + sc(0) + ", " + sc(1) + ")"
                              : "SphereN3(VecN3(" + sc(0) + ", " + sc(0) + ", " + sc(0) + "), " + sc(0) + ")";
      case 13: return "TranslatorN3(" + sc(1) + ", " + sc(0) + ", " + sc(0) + ")";
      case 14: return "RotorN3(" + input() + ", 1, " + input() + ", " + sc(1) + ")";
      case 15: return "exp(" + sc(1) + "*" + (pick(2) ? "e1^e2" : "einf^e0") + ")";
      case 16: return sc(2) + "*" + mv(d, extra_leaf);
      case 17: return "Dual(" + mv(d, extra_leaf) + ")";
      case 18: return "invert(" + divisor() + ")";
      case 19: return "Normalize(" + number() + "*VecN3(" + input() + ", " + number() + ", " + input() + "))";
      case 20: return "abs(" + mv(d, extra_leaf) + ")";
      case 21: return mv(d, extra_leaf) + "/" + divisor() + "*" + mv(d, extra_leaf);
      case 22:
        if (!macros_.empty()) return macros_[0] + "(" + mv(d, extra_leaf) + ", " + mv(d, extra_leaf) + ")";
        return "(" + mv(d, extra_leaf) + ")";
      default:
        if (!macros1_.empty()) return macros1_[0] + "(" + mv(d, extra_leaf) + ")";
        return mv(d, extra_leaf) + " . " + mv(d, extra_leaf) + "^" + mv(d, extra_leaf);
    }
  }

  std::uint64_t state_;
  std::vector<std::string> names_, macros_, macros1_;
};

}  // namespace

Program generate(std::uint64_t seed) { return Gen(seed).program(); }

}  // namespace diff
