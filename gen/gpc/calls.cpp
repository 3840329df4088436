// The GPC functions of the C text (calls.hpp): mv_from_array read, to_array / mv_to_array /
// mv_get_bladecoeff replaced.
#include "gpc/calls.hpp"

#include <algorithm>
#include <cctype>
#include <set>

#include "algebra/algebra.hpp"
#include "front/diagnostics.hpp"

namespace cgagen::gpc {

using front::CompileError;

namespace {

struct BladeArg {
  algebra::BladeIndex index;
  int sign;
};

// "e1^e2", "- e2 ^ e1", "1", "1.0": a blade of the current algebra and the sign of the text's order.
BladeArg parse_blade_arg(const Text& t, const Arg& arg, const std::string& fn) {
  std::string b;
  for (char c : arg.text)
    if (!std::isspace(static_cast<unsigned char>(c))) b += c;
  int sign = 1;
  while (!b.empty() && (b[0] == '-' || b[0] == '+')) {
    if (b[0] == '-') sign = -sign;
    b.erase(0, 1);
  }
  if (b == "1.0" || b == "1.0f" || b == "1.f" || b == "1.") b = "1";
  std::optional<algebra::SignedBlade> sb;
  if (!b.empty()) sb = algebra::parse_blade(b);
  if (!sb) {
    std::string names;
    for (const auto& v : algebra::current().vector_names()) names += " " + v;
    throw CompileError(t.loc(arg.begin), "unknown blade '" + arg.text + "' in " + fn + " (the scalar is 1; the " +
                                             algebra::current().name() + " basis vectors are" + names + ")");
  }
  return {sb->index, sign * sb->sign};
}

// The number of '\n' in s[b, e), as a string of newlines: what keeps a replacement's line count.
std::string newlines(const std::string& s, size_t b, size_t e) {
  return std::string(static_cast<size_t>(std::count(s.begin() + static_cast<long>(b), s.begin() + static_cast<long>(e), '\n')), '\n');
}

// `LHS = fn(...)`: the offset where LHS starts (after the last ; { } before it), and LHS without blanks around.
bool assignment_target(const std::string& s, size_t region_begin, size_t name, size_t& lhs_begin, std::string& lhs) {
  size_t p = name;
  while (p > region_begin && std::isspace(static_cast<unsigned char>(s[p - 1]))) --p;
  if (p == region_begin || s[p - 1] != '=') return false;
  const size_t eq = p - 1;
  if (eq > region_begin && std::string("=!<>+-*/%&|^").find(s[eq - 1]) != std::string::npos) return false;
  size_t b = eq;
  while (b > region_begin && s[b - 1] != ';' && s[b - 1] != '{' && s[b - 1] != '}') --b;
  while (b < eq && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
  // Whole lines before the target that are directives or comments are not part of it.
  while (true) {
    const size_t nl = s.find('\n', b);
    if (nl == std::string::npos || nl >= eq) break;
    const std::string line = s.substr(b, nl - b);
    const size_t close = line.find("*/");
    const bool skip = line[0] == '#' || line.compare(0, 2, "//") == 0 ||
                      (line.compare(0, 2, "/*") == 0 && close != std::string::npos &&
                       line.find_first_not_of(" \t\r", close + 2) == std::string::npos);
    if (!skip) break;
    b = nl + 1;
    while (b < eq && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
  }
  size_t e = eq;
  while (e > b && std::isspace(static_cast<unsigned char>(s[e - 1]))) --e;
  lhs_begin = b;
  lhs = s.substr(b, e - b);
  return !lhs.empty();
}

// The ';' after a call's ')', or npos.
size_t statement_end(const std::string& s, size_t close, size_t end) {
  const size_t p = skip_blanks(s, close + 1, end);
  return p < end && s[p] == ';' ? p : std::string::npos;
}

const OutputShape* find_output(const std::vector<BlockOutputs>& blocks, const std::string& name, size_t at) {
  for (auto it = blocks.rbegin(); it != blocks.rend(); ++it) {
    if (it->visible_from > at) continue;
    for (const auto& o : it->outputs)
      if (o.name == name) return &o;
  }
  return nullptr;
}

const BlockOutputs* last_visible(const std::vector<BlockOutputs>& blocks, size_t at) {
  for (auto it = blocks.rbegin(); it != blocks.rend(); ++it)
    if (it->visible_from <= at) return &*it;
  return nullptr;
}

const OutputShape& output_arg(const Text& t, const std::vector<BlockOutputs>& blocks, const Arg& arg,
                              const std::string& fn) {
  const OutputShape* o = is_identifier(arg.text) ? find_output(blocks, arg.text, arg.begin) : nullptr;
  if (o) return *o;
  const BlockOutputs* last = last_visible(blocks, arg.begin);
  std::string known;
  if (last)
    for (const auto& x : last->outputs) known += (known.empty() ? "" : ", ") + x.name;
  throw CompileError(t.loc(arg.begin),
                     "'" + arg.text + "' in " + fn + " is not an output of a gpc block before this line" +
                         (last ? " (block " + std::to_string(last->index) + " outputs " + known + ")"
                               : " (no gpc block comes before it)"));
}

std::string element(const OutputShape& o, size_t k) {
  return o.blades.size() == 1 ? o.name : o.name + "[" + std::to_string(k) + "]";
}

// The coefficient of `blade` in output o, as a C expression.
std::string coefficient(const OutputShape& o, BladeArg blade, const std::string& type) {
  for (size_t k = 0; k < o.blades.size(); ++k)
    if (o.blades[k] == blade.index) return blade.sign < 0 ? "(-" + element(o, k) + ")" : element(o, k);
  return type == "float" ? "0.0f" : "0.0";
}

std::string indexable(const std::string& lhs) {
  bool plain = !lhs.empty();
  for (char c : lhs) plain = plain && (is_ident_char(c) || c == '.' || c == ':');
  return plain ? lhs : "(" + lhs + ")";
}

}  // namespace

void rewrite_calls(const Text& t, size_t begin, size_t end, const std::vector<BlockOutputs>& blocks,
                   const std::string& type, std::vector<InputDecl>* inputs, std::vector<Edit>& edits) {
  static const std::set<std::string> names{"mv_from_array",       "to_array",        "mv_to_array",
                                           "mv_get_bladecoeff",   "mv_from_stridedarray", "mv_from_vector",
                                           "mv_to_stridedarray",  "mv_to_vector",    "mv_to_vecarray"};
  const std::string& s = t.str();
  for (const Call& c : find_calls(t, begin, end, names)) {
    const front::SourceLoc at = t.loc(c.name);
    if (c.fn == "to_array") {
      // Gaalop leaves to_array to the user's C++ (ga-benchmark's std::experimental::to_array); here a call on
      // an output becomes the std::array itself. Other calls are the user's own.
      if (c.args.size() != 1 || !is_identifier(c.args[0].text) || !last_visible(blocks, c.name)) continue;
      const OutputShape& o = output_arg(t, blocks, c.args[0], "to_array");
      std::string r = "std::array<" + type + ", " + std::to_string(o.blades.size()) + ">{";
      for (size_t k = 0; k < o.blades.size(); ++k) r += (k ? ", " : "") + element(o, k);
      edits.push_back({c.name, c.close + 1, r + "}" + newlines(s, c.name, c.close + 1)});
    } else if (c.fn == "mv_get_bladecoeff") {
      if (c.args.size() != 2 || c.args[1].text.empty())
        throw CompileError(at, "mv_get_bladecoeff takes an output and a blade: mv_get_bladecoeff(X, BLADE)");
      const OutputShape& o = output_arg(t, blocks, c.args[0], "mv_get_bladecoeff");
      const BladeArg b = parse_blade_arg(t, c.args[1], "mv_get_bladecoeff");
      edits.push_back({c.name, c.close + 1, coefficient(o, b, type) + newlines(s, c.name, c.close + 1)});
    } else if (c.fn == "mv_to_array") {
      size_t lhs_begin = 0;
      std::string lhs;
      const size_t semi = statement_end(s, c.close, end);
      if (!assignment_target(s, begin, c.name, lhs_begin, lhs) || semi == std::string::npos || c.args[0].text.empty())
        throw CompileError(at, "expected 'ARRAY = mv_to_array(X, BLADE, ...);' (a statement of its own)");
      const OutputShape& o = output_arg(t, blocks, c.args[0], "mv_to_array");
      std::string r;
      const std::string a = indexable(lhs);
      if (c.args.size() == 1) {
        for (size_t k = 0; k < o.blades.size(); ++k)
          r += (k ? " " : "") + a + "[" + std::to_string(k) + "] = " + element(o, k) + ";";
      } else {
        for (size_t k = 1; k < c.args.size(); ++k)
          r += (k > 1 ? " " : "") + a + "[" + std::to_string(k - 1) + "] = " +
               coefficient(o, parse_blade_arg(t, c.args[k], "mv_to_array"), type) + ";";
      }
      edits.push_back({lhs_begin, semi + 1, r + newlines(s, lhs_begin, semi + 1)});
    } else if (c.fn == "mv_from_array") {
      if (!inputs)
        throw CompileError(at, "mv_from_array declares an input of a gpc block: it belongs between "
                               "'#pragma gpc begin' and '#pragma clucalc begin'");
      size_t lhs_begin = 0;
      std::string lhs;
      const size_t semi = statement_end(s, c.close, end);
      if (!assignment_target(s, begin, c.name, lhs_begin, lhs) || semi == std::string::npos || !is_identifier(lhs))
        throw CompileError(at, "expected 'NAME = mv_from_array(ARRAY, BLADE, ...);' (a statement of its own)");
      if (c.args.size() < 2 || c.args[0].text.empty())
        throw CompileError(at, "mv_from_array needs the array and its blades: NAME = mv_from_array(ARRAY, BLADE, ...);");
      InputDecl d{lhs, t.loc(lhs_begin), at, c.args[0].text, {}, {}, {}};
      for (const auto& in : *inputs)
        if (in.name == lhs)
          throw CompileError(d.name_loc, "'" + lhs + "' is already read by mv_from_array at line " +
                                             std::to_string(in.name_loc.line));
      for (size_t k = 1; k < c.args.size(); ++k) {
        const BladeArg b = parse_blade_arg(t, c.args[k], "mv_from_array");
        if (std::find(d.blades.begin(), d.blades.end(), b.index) != d.blades.end())
          throw CompileError(t.loc(c.args[k].begin), "blade '" + c.args[k].text + "' is listed twice in mv_from_array");
        d.blades.push_back(b.index);
        d.signs.push_back(b.sign);
        d.blade_locs.push_back(t.loc(c.args[k].begin));
      }
      inputs->push_back(d);
      size_t from = lhs_begin;  // the blanks before the statement go with it
      while (from > begin && (s[from - 1] == ' ' || s[from - 1] == '\t')) --from;
      edits.push_back({from, semi + 1, newlines(s, from, semi + 1)});
    } else {
      throw CompileError(at, "Gaalop's " + c.fn + " is not supported by cgagen --gpc (use mv_from_array, "
                             "to_array, mv_to_array or mv_get_bladecoeff)");
    }
  }
}

}  // namespace cgagen::gpc
