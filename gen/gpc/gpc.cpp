// cgagen --gpc (gpc.hpp): the blocks of a source found and checked, each compiled by the pipeline
// (front -> expand -> opt -> emit/statements), and the source stitched back with `#line` directives.
#include "gpc/gpc.hpp"

#include <algorithm>
#include <map>
#include <memory>
#include <set>

#include "algebra/algebra.hpp"
#include "emit/statements.hpp"
#include "expand/expand.hpp"
#include "front/parser.hpp"
#include "gpc/calls.hpp"
#include "gpc/scan.hpp"
#include "symbolic/node_cache.hpp"

namespace cgagen::gpc {

using front::CompileError;

namespace {

struct Block {
  int index = 0;  // 1-based
  PragmaLine begin, clu_begin, clu_end, end;
};

const char* pragma_text(PragmaKind k) {
  switch (k) {
    case PragmaKind::GpcBegin: return "'#pragma gpc begin'";
    case PragmaKind::GpcEnd: return "'#pragma gpc end'";
    case PragmaKind::ClucalcBegin: return "'#pragma clucalc begin'";
    case PragmaKind::ClucalcEnd: return "'#pragma clucalc end'";
  }
  return "";
}

// The pragma lines as blocks: gpc begin, clucalc begin, clucalc end, gpc end, in this order, not nested.
std::vector<Block> find_blocks(const std::vector<PragmaLine>& pragmas) {
  std::vector<Block> blocks;
  enum { Outside, Pre, Script, Post } state = Outside;
  Block cur;
  for (const PragmaLine& p : pragmas) {
    switch (p.kind) {
      case PragmaKind::GpcBegin:
        if (state != Outside)
          throw CompileError(p.loc, "'#pragma gpc begin' inside the gpc block that begins at line " +
                                        std::to_string(cur.begin.line) + " (blocks do not nest; close it with '#pragma gpc end')");
        cur = Block{static_cast<int>(blocks.size()) + 1, p, {}, {}, {}};
        state = Pre;
        break;
      case PragmaKind::ClucalcBegin:
        if (state == Outside)
          throw CompileError(p.loc, "'#pragma clucalc begin' outside a gpc block (write it between '#pragma gpc "
                                    "begin' and '#pragma gpc end')");
        if (state == Post)
          throw CompileError(p.loc, "a second '#pragma clucalc begin' in the gpc block that begins at line " +
                                        std::to_string(cur.begin.line) + " (a block holds one script)");
        cur.clu_begin = p;
        state = Script;
        break;
      case PragmaKind::ClucalcEnd:
        if (state != Script) throw CompileError(p.loc, "'#pragma clucalc end' without '#pragma clucalc begin'");
        cur.clu_end = p;
        state = Post;
        break;
      case PragmaKind::GpcEnd:
        if (state == Outside) throw CompileError(p.loc, "'#pragma gpc end' without '#pragma gpc begin'");
        if (state == Script)
          throw CompileError(cur.clu_begin.loc, "'#pragma clucalc begin' without '#pragma clucalc end' before "
                                                "'#pragma gpc end' (line " + std::to_string(p.line) + ")");
        if (state == Pre)
          throw CompileError(cur.begin.loc, "the gpc block has no script: write it between '#pragma clucalc "
                                            "begin' and '#pragma clucalc end'");
        cur.end = p;
        blocks.push_back(cur);
        state = Outside;
        break;
    }
  }
  if (state == Script)
    throw CompileError(cur.clu_begin.loc, std::string(pragma_text(PragmaKind::ClucalcBegin)) +
                                              " without '#pragma clucalc end'");
  if (state != Outside)
    throw CompileError(cur.begin.loc, "'#pragma gpc begin' without '#pragma gpc end'");
  return blocks;
}

// The script text of a block: its lines at their own line numbers, every other line empty, so that the
// parser's locations are the original file's.
std::string script_text(const Text& t, const Block& b) {
  std::string s;
  for (int line = 1; line < b.clu_end.line; ++line) {
    if (line > b.clu_begin.line) s += t.str().substr(t.line_start(line), t.line_end(line) - t.line_start(line));
    s += '\n';
  }
  return s;
}

std::string quoted(const std::string& path) {
  std::string q = "\"";
  for (char c : path) {
    if (c == '\\' || c == '"') q += '\\';
    q += c;
  }
  return q + "\"";
}

// The line of each name's first use: where it is read (a Name) or declared by `#pragma input`.
void first_uses(const front::Expr& e, std::map<std::string, int>& lines) {
  if (e.kind == front::Expr::Kind::Name) {
    auto [it, added] = lines.emplace(e.text, e.loc.line);
    if (!added) it->second = std::min(it->second, e.loc.line);
  }
  for (const auto& a : e.args)
    if (a) first_uses(*a, lines);
}
void first_uses(const std::vector<front::StmtPtr>& statements, std::map<std::string, int>& lines) {
  for (const auto& s : statements) {
    if (s->kind == front::Stmt::Kind::Pragma && s->words.size() > 1 && s->words[0] == "input") {
      auto [it, added] = lines.emplace(s->words[1], s->loc.line);
      if (!added) it->second = std::min(it->second, s->loc.line);
    }
    if (s->value) first_uses(*s->value, lines);
    if (s->result) first_uses(*s->result, lines);
    first_uses(s->body, lines);
    first_uses(s->else_body, lines);
  }
}

// The source line of each statement, for the `#line` before it (emit/statements.hpp). A compiler error in
// a statement is about a name the user wrote: a misspelt scalar input, an undeclared array of mv_from_array.
// So a statement gets the line where the inputs it reads are first used (the latest of them, when it reads
// several); temporaries are cgagen's own names and count only for a statement that reads no input (the
// latest line of those it reads). An output's declaration, and a statement that reads neither, get the line
// that assigns the output.
void statement_lines(const front::Script& script, const Kernel& kernel, const opt::Program& program, int fallback,
                     emit::StatementOptions& so) {
  std::map<std::string, int> uses;
  first_uses(script.statements, uses);
  std::map<GiNaC::ex, int, GiNaC::ex_is_less> input_line, temp_line;
  for (const auto& in : program.inputs) {
    auto it = uses.find(in.name);
    for (const auto& sym : in.symbols) input_line[sym] = it != uses.end() ? it->second : fallback;
  }
  auto line = [&](const GiNaC::ex& value, int otherwise) {
    int inputs = 0, temps = 0;
    for (auto it = value.preorder_begin(); it != value.preorder_end(); ++it)
      if (GiNaC::is_a<GiNaC::symbol>(*it)) {
        if (auto l = input_line.find(*it); l != input_line.end()) inputs = std::max(inputs, l->second);
        if (auto l = temp_line.find(*it); l != temp_line.end()) temps = std::max(temps, l->second);
      }
    return inputs > 0 ? inputs : temps > 0 ? temps : otherwise;
  };
  for (const auto& t : program.temps) {
    so.temp_lines.push_back(line(t.value, fallback));
    temp_line[t.sym] = so.temp_lines.back();
  }
  for (const auto& o : program.outputs) {
    int own = fallback;
    for (const auto& ko : kernel.outputs)
      if (ko.name == o.name) own = ko.value >= 0 ? kernel.values.at(static_cast<size_t>(ko.value)).loc.line : ko.loc.line;
    so.output_lines.push_back(own);
    so.slot_lines.emplace_back();
    for (const auto& slot : o.slots) so.slot_lines.back().push_back(line(slot.value, own));
  }
}

// A block compiled: the statements for its script section and its outputs.
struct Compiled {
  std::string statements;
  std::vector<OutputShape> outputs;
  std::vector<std::string> input_names;
};

Compiled compile_block(const front::SourceFile& file, const Text& t, const Block& b, const std::vector<InputDecl>& inputs,
                       const Options& o, const std::string& path, std::vector<front::Warning>& warnings) {
  const front::SourceFile script_file(file.path(), script_text(t, b));
  front::Script script = front::parse(script_file);
  // Each mv_from_array is the script's `#pragma input NAME BLADE...`, located where the user wrote it.
  std::vector<front::StmtPtr> statements;
  for (const InputDecl& d : inputs) {
    auto p = std::make_shared<front::Stmt>();
    p->kind = front::Stmt::Kind::Pragma;
    p->loc = d.name_loc;
    p->words = {"input", d.name};
    p->word_locs = {d.fn_loc, d.name_loc};
    for (size_t k = 0; k < d.blades.size(); ++k) {
      p->words.push_back(algebra::blade_name(d.blades[k]));
      p->word_locs.push_back(d.blade_locs[k]);
    }
    statements.push_back(p);
  }
  statements.insert(statements.end(), script.statements.begin(), script.statements.end());
  script.statements = std::move(statements);

  symbolic::NodeCacheScope caches;
  Kernel kernel;
  try {
    kernel = expand(script, "gpc_block_" + std::to_string(b.index));
  } catch (const CompileError& e) {
    // A fault of the script as a whole ("no outputs") has no place in it: report it at the section's pragma.
    bool placed = e.loc().line > b.clu_begin.line && e.loc().line < b.clu_end.line;
    for (const InputDecl& d : inputs) {
      placed = placed || e.loc().line == d.name_loc.line || e.loc().line == d.fn_loc.line;
      for (const auto& l : d.blade_locs) placed = placed || e.loc().line == l.line;
    }
    if (placed) throw;
    throw CompileError(b.clu_begin.loc, e.what());
  }
  warnings.insert(warnings.end(), kernel.warnings.begin(), kernel.warnings.end());
  const opt::Program program = opt::optimize(kernel, o.level);

  emit::StatementOptions so;
  so.target = o.target;
  so.type = o.type;
  so.indent = b.clu_begin.indent;  // or that of the script's first line
  for (int line = b.clu_begin.line + 1; line < b.clu_end.line; ++line) {
    const size_t ls = t.line_start(line), le = t.line_end(line);
    size_t p = ls;
    while (p < le && (t.str()[p] == ' ' || t.str()[p] == '\t')) ++p;
    if (p < le && t.str()[p] != '\r') {
      so.indent = t.str().substr(ls, p - ls);
      break;
    }
  }
  so.temp_prefix = "gpc" + std::to_string(b.index) + "_";
  for (const InputDecl& d : inputs) {
    const std::string a = is_identifier(d.array) ? d.array : "(" + d.array + ")";
    auto& e = so.elements[d.name];
    for (size_t k = 0; k < d.blades.size(); ++k) {
      const std::string x = a + "[" + std::to_string(k) + "]";
      e.push_back(d.signs[k] < 0 ? "(-" + x + ")" : x);
    }
  }
  so.line_file = path;
  statement_lines(script, kernel, program, b.clu_begin.line + 1, so);
  Compiled c;
  c.statements = emit::emit_statements(program, so);
  for (const auto& out : program.outputs) {
    OutputShape shape{out.name, {}};
    for (const auto& slot : out.slots) shape.blades.push_back(slot.blade);
    c.outputs.push_back(shape);
  }
  for (const auto& in : program.inputs) c.input_names.push_back(in.name);
  return c;
}

// Appends C text [b, e) with its edits, and a `#line` after each conditional directive once `resync` holds
// (a generated section inside an #if group that the compiler skips would leave the count of the lines after
// the group off, as the `#line` after it is skipped too).
void append_c(std::string& out, const Text& t, size_t b, size_t e, const std::vector<Edit>& edits, bool resync,
              const std::string& path) {
  const std::string& s = t.str();
  std::string text;
  size_t p = b;
  for (const Edit& ed : edits) {
    if (ed.begin < b || ed.end > e) continue;
    text.append(s, p, ed.begin - p);
    text += ed.text;
    p = ed.end;
  }
  text.append(s, p, e - p);
  if (!resync) {
    out += text;
    return;
  }
  int line = t.loc(b).line;
  size_t q = 0;
  bool directive = false;
  while (q < text.size()) {
    size_t nl = text.find('\n', q);
    const bool last = nl == std::string::npos;
    if (last) nl = text.size();
    const std::string l = text.substr(q, nl - q);
    out += l;
    if (!last) out += '\n';
    directive = directive || is_conditional_directive(l);
    const bool continued = !l.empty() && (l.back() == '\\' || (l.size() > 1 && l.back() == '\r' && l[l.size() - 2] == '\\'));
    if (directive && !continued && !last) {
      out += "#line " + std::to_string(line + 1) + " " + path + "\n";
      directive = false;
    }
    ++line;
    q = nl + 1;
  }
}

std::string level_text(opt::Level l) { return "-O" + std::to_string(static_cast<int>(l)); }

}  // namespace

Result rewrite(const front::SourceFile& file, const Options& o) {
  Result result;
  const Text t(file.text());
  const std::string& s = t.str();
  const std::vector<Block> blocks = find_blocks(find_pragmas(t));
  const std::string path = quoted(o.line_path.empty() ? file.path() : o.line_path);

  std::vector<BlockOutputs> compiled;
  std::vector<Edit> edits;
  std::string& out = result.text;
  out = "#line 1 " + path + "\n";
  size_t pos = 0;  // start of the C text not yet written
  bool resync = false;
  for (const Block& b : blocks) {
    // The C text before the block, and the block's own text before its script.
    const size_t begin_at = t.line_start(b.begin.line), pre_at = t.line_start(b.begin.line + 1);
    const size_t clu_at = t.line_start(b.clu_begin.line);
    rewrite_calls(t, pos, begin_at, compiled, o.type, nullptr, edits);
    std::vector<InputDecl> inputs;
    rewrite_calls(t, pre_at, clu_at, compiled, o.type, &inputs, edits);
    const Compiled c = compile_block(file, t, b, inputs, o, path, result.warnings);
    const size_t post_at = t.line_start(b.clu_end.line + 1), end_at = t.line_start(b.end.line);
    compiled.push_back({b.index, post_at, c.outputs});
    rewrite_calls(t, post_at, end_at, compiled, o.type, nullptr, edits);

    append_c(out, t, pos, begin_at, edits, resync, path);
    std::string ins, outs;
    for (const auto& n : c.input_names) ins += (ins.empty() ? "" : ", ") + n;
    for (const auto& x : c.outputs) outs += (outs.empty() ? "" : ", ") + x.name;
    out += b.begin.indent + "// gpc block " + std::to_string(b.index) + ": generated by cgagen --gpc " +
           level_text(o.level) + " " + o.type + " (inputs: " + (ins.empty() ? "none" : ins) + "; outputs: " + outs + ")\n";
    append_c(out, t, pre_at, clu_at, edits, resync, path);
    const int first = b.clu_begin.line + 1, last = b.clu_end.line - 1;
    out += b.clu_begin.indent + "// gpc block " + std::to_string(b.index) + ": the script of " +
           (first >= last ? "line " + std::to_string(first) : "lines " + std::to_string(first) + "-" + std::to_string(last)) +
           ", compiled\n";
    out += c.statements;
    out += "#line " + std::to_string(b.clu_end.line + 1) + " " + path + "\n";
    resync = true;
    append_c(out, t, post_at, end_at, edits, resync, path);
    out += b.end.indent + "// end of gpc block " + std::to_string(b.index) + "\n";
    pos = t.line_start(b.end.line + 1);
  }
  rewrite_calls(t, pos, s.size(), compiled, o.type, nullptr, edits);
  append_c(out, t, pos, s.size(), edits, resync, path);
  return result;
}

}  // namespace cgagen::gpc
