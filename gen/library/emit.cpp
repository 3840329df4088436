// Library files (emit.hpp): the kernels in the target's own syntax, then the templates of
// templates/TARGET/library/ filled per type, per function, per registry entry and per skipped operation.
#include "library/emit.hpp"

#include <cctype>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string_view>

#include "emit/names.hpp"
#include "library/lanes.hpp"

namespace cgagen::library {

namespace {

std::string folder(const std::string& template_dir, const std::string& target) {
  return (template_dir.empty() ? emit::default_template_dir() : template_dir) + "/" + target + "/library";
}

struct Templates {
  std::string dir;
  std::map<std::string, std::string> text;
  const std::string& operator[](const std::string& name) const { return text.at(name); }
  bool has(const std::string& name) const { return text.count(name) != 0; }
  std::string path(const std::string& name) const { return dir + "/" + name + ".in"; }
};

// Every target has the required templates. A target with `lanes_kernel.in` gets the 4-wide float forms of
// its bilinear kernels (library/lanes.hpp) as well, and one with `matrix.in` the sandwiches' matrices.
// matrix_column_NAME.in: one column's piece of a matrix, joined over the columns as {{column_NAME}}.
constexpr std::string_view kColumnPiece = "matrix_column_";

Templates load(const std::string& dir) {
  Templates t{dir, {}};
  auto read = [&](const char* name, bool required) {
    std::ifstream in(t.path(name), std::ios::binary);
    if (!in) {
      if (required) throw std::runtime_error("cannot read library template " + t.path(name));
      return;
    }
    std::ostringstream s;
    s << in.rdbuf();
    t.text[name] = s.str();
  };
  for (const char* name : {"file", "type", "unary", "binary", "unary_operator", "binary_operator", "unary_registry", "binary_registry", "skipped", "alias", "type_registry"})
    read(name, true);
  read("lanes_kernel", false);
  read("matrix", false);  // the sandwiches' matrices (build.hpp's Matrix), listed by matrix_registry
  read("matrix_registry", false);
  std::set<std::string> columns;  // sorted: the same templates read in the same order on every run
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(dir, ec)) {
    const std::string file = e.path().filename().string();
    if (file.rfind(kColumnPiece, 0) == 0 && file.size() > 3 && file.compare(file.size() - 3, 3, ".in") == 0)
      columns.insert(file.substr(0, file.size() - 3));
  }
  for (const std::string& name : columns) read(name.c_str(), true);
  return t;
}

std::string blade_text(const algebra::Algebra& alg, algebra::BladeIndex b) { return b == 0 ? "1" : alg.blade_name(b); }

// The CamelCase form of a spelt type name ({{Type}}), for targets whose types are CamelCase (Rust, Python):
// ideal_line -> IdealLine, mv_1a -> Mv1a. A reserved word (Rust's Self, Python's None) gets a trailing _.
std::string camel(const std::string& spelt, const std::set<std::string>& reserved) {
  std::string out;
  bool up = true;
  for (char c : spelt) {
    if (c == '_') {
      up = true;
      continue;
    }
    out += up ? static_cast<char>(std::toupper(static_cast<unsigned char>(c))) : c;
    up = false;
  }
  return reserved.count(out) ? out + "_" : out;
}

}  // namespace

std::vector<std::string> library_targets(const std::string& template_dir) {
  std::vector<std::string> out;
  for (const emit::Syntax& sx : emit::targets())
    if (std::filesystem::exists(folder(template_dir, sx.name) + "/file.in")) out.push_back(sx.name);
  return out;
}

std::string emit_library(const Library& lib, const emit::EmitOptions& options, const std::string& spec_file) {
  const emit::Syntax& sx = options.target.syntax();
  const std::string dir = folder(options.template_dir, sx.name);
  if (!std::filesystem::exists(dir + "/file.in")) {
    std::string have;
    for (const auto& n : library_targets(options.template_dir)) have += (have.empty() ? "" : ", ") + n;
    throw std::runtime_error("the " + sx.name + " target has no library templates (" + dir + "); targets with a library: " + have);
  }
  const Templates t = load(dir);
  const algebra::Algebra& alg = *lib.algebra_ptr;
  auto type_name = [&](size_t t) { return emit::spell(sx, lib.types[t].name); };
  const std::set<std::string> reserved = emit::reserved_words(sx.name);
  // Dropping the underscores could merge two names (line_2, line2): refused rather than emitted twice.
  std::map<std::string, std::string> camel_of;
  for (size_t i = 0; i < lib.types.size(); ++i) camel_of[type_name(i)] = camel(type_name(i), reserved);
  for (const Alias& al : lib.aliases) camel_of[emit::spell(sx, al.name)] = camel(emit::spell(sx, al.name), reserved);
  std::map<std::string, std::string> name_of_camel;
  for (const auto& [name, c] : camel_of)
    if (!name_of_camel.emplace(c, name).second)
      throw std::runtime_error("types " + name_of_camel[c] + " and " + name + " are both " + c + " in CamelCase");
  auto Type_name = [&](size_t t) { return camel_of.at(type_name(t)); };
  auto fill = [&](const std::string& name, const std::map<std::string, std::string>& v) {
    return emit::fill_template(t[name], v, t.path(name));
  };

  std::vector<const opt::Program*> programs;
  for (const Function& f : lib.functions) programs.push_back(&f.program);
  const bool matrices = t.has("matrix");
  if (matrices)
    for (const Matrix& m : lib.matrices) programs.push_back(&m.program);
  const std::string kernels = emit::emit_functions(programs, options);

  std::string types, type_registry;
  for (size_t i = 1; i < lib.types.size(); ++i) {
    const Type& ty = lib.types[i];
    std::string quoted, layout;
    for (size_t k = 0; k < ty.blades.size(); ++k) {
      quoted += std::string(k ? ", " : "") + "\"" + blade_text(alg, ty.blades[k]) + "\"";
      layout += std::string(k ? " " : "") + blade_text(alg, ty.blades[k]);
    }
    types += fill("type", {{"library", lib.name},
                           {"type", type_name(i)},
                           {"Type", Type_name(i)},
                           {"n", std::to_string(ty.blades.size())},
                           {"blades", quoted},
                           {"layout", layout},
                           {"origin", ty.declared ? "declared in the spec" : "named by the generator for a result"}});
    type_registry += fill("type_registry", {{"type", type_name(i)}, {"Type", Type_name(i)}, {"n", std::to_string(ty.blades.size())}});
  }

  for (const Alias& al : lib.aliases)
    types += fill("alias", {{"library", lib.name},
                            {"alias", emit::spell(sx, al.name)},
                            {"Alias", camel_of.at(emit::spell(sx, al.name))},
                            {"type", emit::spell(sx, al.type)},
                            {"Type", camel_of.at(emit::spell(sx, al.type))}});

  std::string functions, registry, skipped, lanes_kernels;
  for (const Function& f : lib.functions) {
    // The float kernel one call runs: the 4-wide form where the target has one and it pays (lanes.hpp says
    // when). The array forms of the templates run the scalar kernel, which the compiler vectorizes across
    // elements, whatever this picks.
    std::string float_kernel = emit::spell(sx, f.program.name);
    if (t.has("lanes_kernel") && f.op->arity == 2) {
      const long scalar_ops = opt::program_stats(f.program).total.total();
      std::optional<LaneCode> code;
      if (const auto form = lane_form(f.program)) {
        code = lane_code(*form);
        if (static_cast<long>(code->ops) >= scalar_ops) code.reset();
      } else if (const auto linear = linear_form(f.program)) {
        code = linear_code(*linear);
        // Measured with g++ 12 -O3 -march=native on pga3's sandwich(motor, line) (118 vector operations, the
        // scalar kernel 114): 8.7 ns per call against 9.8, and 8.6 ns per element in a loop of calls against 9.4.
        const size_t vectors = (linear->out.size() + 3) / 4;
        const bool keep = vectors == 1 || (vectors == 2 && 10 * static_cast<long>(code->ops) <= 11 * scalar_ops) ||
                          static_cast<long>(code->ops) < scalar_ops;
        if (!keep) code.reset();
      }
      if (code) {
        lanes_kernels += fill("lanes_kernel", {{"library", lib.name},
                                               {"kernel", float_kernel},
                                               {"params", "const float* a, const float* b, float* r"},
                                               {"args", "a, b, r"},
                                               {"ops", std::to_string(code->ops)},
                                               {"scalar_ops", std::to_string(scalar_ops)},
                                               {"body", code->body}});
        float_kernel = "x4::" + float_kernel;
      }
    }
    // The pairs' array form runs blocks through structure-of-arrays scratch (the C++ template's staged form)
    // where a direct loop vectorizes poorly and the kernel is costly enough to pay for the copies: an operand
    // or the result whose size is not a power of two (a line's 6), which leaves the compiler coefficients
    // interleaved by that size, and 40 operations or more. Measured on pga3 (g++ 12 -O3 -march=native,
    // AVX-512), ns per element, staged against direct: sandwich(motor, line) 5.4 against 9.8 in cache (4096
    // elements) and 10.2 against 10.6 in memory (2^20, alternated); with sizes 8, 4 and 4 staging wins in cache
    // but loses in memory (gp(motor, motor) 9.2 against 7.2, sandwich(motor, point) 7.2 against 6.5), and a
    // cheap kernel loses everywhere (gp(rotor, rotor), 28 operations: 1.1 against 0.7 in cache).
    constexpr long kStagedOps = 40;
    const long ops = opt::program_stats(f.program).total.total();
    auto power_of_two = [&](size_t t) {
      const size_t n = lib.types[t].blades.size();
      return (n & (n - 1)) == 0;
    };
    const bool staged = f.op->arity == 2 && ops >= kStagedOps &&
                        !(power_of_two(f.a) && power_of_two(f.b) && power_of_two(f.result));
    auto size = [&](size_t t) { return std::to_string(lib.types[t].blades.size()); };
    const std::map<std::string, std::string> v = {
        {"library", lib.name},
        {"staged", staged ? "true" : "false"},
        {"array_form", std::string(staged ? "staged: " : "direct: ") + std::to_string(ops) + " operations an element"},
        {"na", size(f.a)},
        {"nb", f.op->arity == 2 ? size(f.b) : "0"},
        {"nr", size(f.result)},
        {"fn", f.op->name},
        {"kernel", emit::spell(sx, f.program.name)},
        {"float_kernel", float_kernel},
        {"a", type_name(f.a)},
        {"b", f.op->arity == 2 ? type_name(f.b) : ""},
        {"result", type_name(f.result)},
        {"A", Type_name(f.a)},
        {"B", f.op->arity == 2 ? Type_name(f.b) : ""},
        {"Result", Type_name(f.result)},
        {"symbol", f.op->symbol},
        {"description", f.op->description},
        {"arity", std::to_string(f.op->arity)}};
    const std::string kind = f.op->arity == 2 ? "binary" : "unary";
    functions += fill(kind, v);
    if (*f.op->symbol) functions += fill(kind + "_operator", v);
    registry += fill(kind + "_registry", v);
  }
  std::string matrix_functions, matrix_registry;
  const std::vector<Matrix> no_matrices;
  for (const Matrix& m : matrices ? lib.matrices : no_matrices) {
    const size_t cols = lib.types[m.b].blades.size(), rows = lib.types[m.result].blades.size();
    std::string columns, names, flat, params = "const float* a", args = "a";
    for (size_t j = 0; j < cols; ++j) {
      columns += std::string(j ? ", " : "") + "r.m[" + std::to_string(j) + "].v";
      names += std::string(j ? ", " : "") + "c" + std::to_string(j);
      flat += std::string(j ? ", " : "") + "m + " + std::to_string(j * rows);
      params += ", float* c" + std::to_string(j);
      args += ", c" + std::to_string(j);
    }
    // The float matrix one call makes: the 4-wide columns of the sandwich's form r = M(a) b (lanes.hpp)
    // where the target has them and they take fewer operations than the scalar kernel, or M(a) is one vector
    // a column (a point's or a plane's: four stores, not sixteen).
    std::string float_kernel = emit::spell(sx, m.program.name);
    if (t.has("lanes_kernel"))
      if (const auto linear = linear_form(lib.functions[m.sandwich].program)) {
        const LaneCode code = matrix_code(*linear);
        const long scalar_ops = opt::program_stats(m.program).total.total();
        if (static_cast<long>(code.ops) < scalar_ops || rows <= 4) {
          lanes_kernels += fill("lanes_kernel", {{"library", lib.name},
                                                 {"kernel", float_kernel},
                                                 {"params", params},
                                                 {"args", args},
                                                 {"ops", std::to_string(code.ops)},
                                                 {"scalar_ops", std::to_string(scalar_ops)},
                                                 {"body", code.body}});
          float_kernel = "x4::" + float_kernel;
        }
      }
    std::map<std::string, std::string> v = {{"library", lib.name},
                                            {"kernel", emit::spell(sx, m.program.name)},
                                            {"float_kernel", float_kernel},
                                            {"a", type_name(m.a)},
                                            {"b", type_name(m.b)},
                                            {"result", type_name(m.result)},
                                            {"A", Type_name(m.a)},
                                            {"B", Type_name(m.b)},
                                            {"Result", Type_name(m.result)},
                                            {"cols", std::to_string(cols)},
                                            {"rows", std::to_string(rows)},
                                            {"columns", columns},
                                            {"column_names", names},
                                            {"flat_columns", flat}};
    // Each matrix_column_NAME template, filled per column (its j and the matrix's names) and joined: a list
    // piece ends in ", ", which the last column drops.
    for (const auto& [name, text] : t.text) {
      if (name.rfind(kColumnPiece, 0) != 0) continue;
      std::string joined;
      for (size_t j = 0; j < cols; ++j) {
        std::map<std::string, std::string> column = v;
        column["j"] = std::to_string(j);
        joined += fill(name, column);
      }
      if (joined.size() >= 2 && joined.compare(joined.size() - 2, 2, ", ") == 0) joined.resize(joined.size() - 2);
      v["column_" + name.substr(kColumnPiece.size())] = joined;
    }
    matrix_functions += fill("matrix", v);
    if (t.has("matrix_registry")) matrix_registry += fill("matrix_registry", v);
  }
  for (const Skipped& s : lib.skipped) {
    std::string reason = s.reason;
    for (char& c : reason)
      if (c == '\n') c = ' ';
    skipped += fill("skipped", {{"fn", s.op->name},
                                {"operands", type_name(s.a) + (s.op->arity == 2 ? ", " + type_name(s.b) : "")},
                                {"reason", reason}});
  }
  std::string declared;
  for (size_t i = 1; i < lib.declared; ++i) declared += (declared.empty() ? "" : " ") + type_name(i);
  return fill("file", {{"library", lib.name},
                       {"spec", spec_file},
                       {"algebra", lib.algebra},
                       {"level", std::to_string(programs.empty() ? 2 : static_cast<int>(programs.front()->level))},
                       {"declared", declared},
                       {"function_count", std::to_string(lib.functions.size())},
                       {"skipped_count", std::to_string(lib.skipped.size())},
                       {"kernels", kernels},
                       {"lanes_kernels", lanes_kernels},
                       {"types", types},
                       {"type_registry", type_registry},
                       {"functions", functions},
                       {"registry", registry},
                       {"matrices", matrix_functions},
                       {"matrix_registry", matrix_registry},
                       {"matrix_count", std::to_string(matrices ? lib.matrices.size() : 0)},
                       {"skipped", skipped}});
}

}  // namespace cgagen::library
