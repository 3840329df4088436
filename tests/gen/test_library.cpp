// cgagen --library's front and middle: the spec's located errors, the result types, what is not generated and
// why, the sandwich's normalization per type, and the CLI (usage errors, byte-identical output across runs).
// tests/library runs every generated function against the oracle.
#include <catch2/catch.hpp>

#include <map>
#include <regex>
#include <string>
#include <utility>
#include <vector>

#include "cli_run.hpp"
#include "library/build.hpp"
#include "library/emit.hpp"
#include "library/lanes.hpp"
#include "library/spec.hpp"

using namespace cgagen;

namespace {

// "spec.gal:line:col: error: message" of parsing `text`, or "no error".
std::string spec_error(const std::string& text) {
  front::SourceFile file("spec.gal", text);
  try {
    library::parse_spec(file, "");
  } catch (const front::CompileError& e) {
    return "spec.gal:" + std::to_string(e.loc().line) + ":" + std::to_string(e.loc().col) + ": error: " + e.what();
  }
  return "no error";
}

library::Spec spec_of(const std::string& text) { return library::parse_spec(front::SourceFile("spec.gal", text), ""); }

const library::Function* find(const library::Library& lib, const std::string& op, const std::string& a,
                              const std::string& b = "") {
  for (const auto& f : lib.functions)
    if (f.op->name == op && lib.types[f.a].name == a && (f.op->arity == 1 || lib.types[f.b].name == b)) return &f;
  return nullptr;
}

}  // namespace

TEST_CASE("library spec: every fault is located at its word") {
  const std::string head = "library l\nalgebra 3dpga\n";
  CHECK(spec_error(head + "type plane e0 e1 e2 e3\n") == "no error");
  CHECK(spec_error("library l\nalgebra nope\n") ==
        "spec.gal:2:9: error: unknown algebra 'nope': neither a built-in (2d, 3d, 2dpga, 3dpga, cra, sta, cga, gac, qga, "
        "dcga, ccga) nor a readable definition.csv file");
  CHECK(spec_error(head + "type line e0^e1 e3^e1\n") ==
        "spec.gal:3:17: error: write 'e1^e3' for 'e3^e1' (3dpga's spelling; the coefficient then changes sign)");
  CHECK(spec_error(head + "type p e0 e9\n") ==
        "spec.gal:3:11: error: 'e9' is not a blade of 3dpga (its vectors: e0 e1 e2 e3; blades join them with ^, the "
        "scalar is 1)");
  CHECK(spec_error(head + "type p e0 e1 e0\n") == "spec.gal:3:14: error: blade 'e0' twice in type 'p'");
  CHECK(spec_error(head + "type p e0\ntype p e1\n") == "spec.gal:4:6: error: type 'p' again (first on line 3)");
  CHECK(spec_error(head + "type p e0 e1\ntype q e1 e0\n") ==
        "spec.gal:4:6: error: type 'q' has the blades of 'p' (a result's type would be ambiguous)");
  CHECK(spec_error(head + "type gp e0\n") ==
        "spec.gal:3:6: error: 'gp' is the name of an operation of the library; choose another name");
  CHECK(spec_error(head + "type scalar 1\n").find("spec.gal:3:6: error: 'scalar' is the library's own type") == 0);
  CHECK(spec_error(head + "type 2p e0\n").find("spec.gal:3:6: error: '2p' is not a type name") == 0);
  CHECK(spec_error(head + "type a__b e0\n").find("spec.gal:3:6: error: 'a__b': a type name may not") == 0);
  CHECK(spec_error(head + "type s 1\n") == "spec.gal:3:6: error: the scalar blade alone is the library's type 'scalar'");
  CHECK(spec_error(head + "type p\n") == "spec.gal:3:1: error: 'type' takes a name and at least one blade");
  CHECK(spec_error("library l\ntype p e0\n") == "spec.gal:2:1: error: a type before the 'algebra' line (its blades need the algebra)");
  CHECK(spec_error(head + "library m\n") == "spec.gal:3:1: error: a second 'library' line (the first is on line 1)");
  CHECK(spec_error(head + "types p e0\n").find("spec.gal:3:1: error: unknown declaration 'types'") == 0);
  CHECK(spec_error(head + "alias q p\n") == "spec.gal:3:9: error: 'p' is not a type declared above");
  CHECK(spec_error("algebra 3dpga\ntype p e0\n") == "spec.gal:1:1: error: no 'library NAME' line");
  CHECK(spec_error("library l\n# only a comment\n") == "spec.gal:1:1: error: no 'algebra NAME|FILE' line");
  CHECK(spec_error(head) == "spec.gal:3:1: error: no 'type NAME BLADE...' line");
  CHECK(spec_error("library\nalgebra 3dpga\n") == "spec.gal:1:1: error: 'library' takes one word");
}

TEST_CASE("library build: the smallest declared type holds each result, else a named one") {
  const library::Library lib = library::build(spec_of("library l\nalgebra 3d\ntype vector e1 e2 e3\n"
                                                      "type bivector e1^e2 e1^e3 e2^e3\ntype rotor 1 e1^e2 e1^e3 e2^e3\n"),
                                              opt::Level::O2);
  auto result = [&](const std::string& op, const std::string& a, const std::string& b = "") {
    const library::Function* f = find(lib, op, a, b);
    return f ? lib.types[f->result].name : std::string("(none)");
  };
  CHECK(result("gp", "vector", "vector") == "rotor");        // 1 and e_ij: the rotor, not a new type
  CHECK(result("outer", "vector", "vector") == "bivector");  // e_ij only: the smaller bivector
  CHECK(result("scp", "vector", "vector") == "scalar");
  CHECK(result("norm", "rotor") == "scalar");
  CHECK(result("gp", "vector", "bivector") == "mv_96");      // e1 e2 e3 e1^e2^e3: bits 1 2 4 7, mask 0x96
  CHECK(result("sandwich", "rotor", "vector") == "vector");
  CHECK(result("exp", "bivector") == "rotor");
  // Not generated, with the reason: a result that is always 0, an operand the operator set refuses.
  std::map<std::string, std::string> skipped;
  for (const auto& s : lib.skipped)
    skipped[std::string(s.op->name) + "(" + lib.types[s.a].name + (s.op->arity == 2 ? ", " + lib.types[s.b].name : "") + ")"] = s.reason;
  CHECK(skipped.at("outer(bivector, bivector)") == "the result is 0 for every value of the operands");
  CHECK(skipped.at("exp(vector)").find("'exp' takes a scalar or a bivector") == 0);
  CHECK(skipped.at("log(vector)") == "takes a type with the scalar blade (a rotor, boost or motor)");
  CHECK(find(lib, "outer", "bivector", "bivector") == nullptr);
}

TEST_CASE("library sandwich: a b ~a for a normalized versor, -a b ~a where its norm is never positive") {
  // CGA: a vector's <a ~a>_0 takes both signs; a flat point's is -w^2 (its einf^e0 coefficient squared).
  const library::Spec spec = spec_of("library l\nalgebra cga\ntype plane e1 e2 e3 einf\n"
                                     "type flat_point e1^einf e2^einf e3^einf einf^e0\n");
  const auto& alg = *spec.algebra;
  const std::string plane = library::operation_script(library::operations().at(11), spec.types[0], &spec.types[1], alg);
  const std::string point = library::operation_script(library::operations().at(11), spec.types[1], &spec.types[0], alg);
  REQUIRE(std::string(library::operations().at(11).name) == "sandwich");
  CHECK(plane.find("#pragma normalized a\nm = a * b * ~a;\n?r = grade(m, 2);") != std::string::npos);
  CHECK(point.find("m = -(a * b * ~a);\n?r = grade(m, 1);") != std::string::npos);
  CHECK(point.find("normalized") == std::string::npos);
}

TEST_CASE("library lanes: a bilinear product as 4-wide columns, other kernels left scalar") {
  const library::Library lib = library::build(spec_of("library l\nalgebra 3d\ntype vector e1 e2 e3\n"
                                                      "type rotor 1 e1^e2 e1^e3 e2^e3\n"),
                                              opt::Level::O2);
  // rotor * rotor, as a quaternion product: r0 = a0 b0 - a1 b1 - a2 b2 - a3 b3 (e12 e12 = -1), and
  // r1 (e1^e2) = a0 b1 + a1 b0 - a2 b3 + a3 b2: e1^e3 e2^e3 = e1 e3 e2 e3 = -e1 e2, so a2 b3 has -1.
  const auto form = library::lane_form(find(lib, "gp", "rotor", "rotor")->program);
  REQUIRE(form);
  CHECK(form->na == 4);
  CHECK(form->nb == 4);
  REQUIRE(form->out.size() == 4);
  std::map<std::pair<size_t, size_t>, double> r0, r1;
  for (const auto& t : form->out[0]) r0[{t.i, t.j}] = t.c;
  for (const auto& t : form->out[1]) r1[{t.i, t.j}] = t.c;
  CHECK(r0 == std::map<std::pair<size_t, size_t>, double>{{{0, 0}, 1}, {{1, 1}, -1}, {{2, 2}, -1}, {{3, 3}, -1}});
  CHECK(r1 == std::map<std::pair<size_t, size_t>, double>{{{0, 1}, 1}, {{1, 0}, 1}, {{2, 3}, -1}, {{3, 2}, 1}});
  // One column per a_i: 4 broadcasts, 4 products, 3 sums, -b once and 3 shuffles of b and -b that take the
  // signs with the coefficients (a0's column is b itself), 15 operations against the scalar kernel's 28.
  const library::LaneCode code = library::lane_code(*form);
  CHECK(code.ops == 15);
  CHECK(code.body.find("const v4 nb0 = -b0;") != std::string::npos);
  // a1 (e1^e2) meets -b1 in r0, b0 in r1, b3 in r2 (e12 e23 = e13) and -b2 in r3 (e12 e13 = -e23):
  CHECK(code.body.find("const v4 p1 = perm<5, 0, 3, 6>(b0, nb0);") != std::string::npos);
  CHECK(code.body.find("store<4>(r + 0, (splat<0>(a0) * p0 + splat<1>(a0) * p1) + (splat<2>(a0) * p2 + splat<3>(a0) * p3));") != std::string::npos);
  CHECK(opt::program_stats(find(lib, "gp", "rotor", "rotor")->program).total.total() == 28);
  // A vector (3 coefficients) is one vector with a lane left over; r has the rotor's 4.
  const auto vv = library::lane_form(find(lib, "gp", "vector", "vector")->program);
  REQUIRE(vv);
  CHECK(library::lane_code(*vv).body.find("load<3>(a + 0)") != std::string::npos);
  // rotor * vector: broadcasting the vector's 3 coefficients (3 columns) beats the rotor's 4.
  const auto rv = library::lane_form(find(lib, "gp", "rotor", "vector")->program);
  REQUIRE(rv);
  const library::LaneCode rv_code = library::lane_code(*rv);
  CHECK(rv_code.body.find("splat<0>(b0)") != std::string::npos);
  CHECK(rv_code.body.find("splat<3>(") == std::string::npos);
  CHECK(rv_code.body.find("load<3>(b + 0)") != std::string::npos);  // b's 3 coefficients, not a's 4
  CHECK(rv_code.body.find("load<4>(a + 0)") != std::string::npos);
  // In CGA's null basis a_i can meet several b_j in one lane (cga3's plane times its scaled motor, whose
  // einf^e0 blade is not a product of orthogonal vectors): the terms are sorted by (i, j), as GiNaC's order of a
  // sum's terms changes from run to run and the printed code may not.
  const library::Library cga = library::build(
      spec_of("library c\nalgebra cga\ntype plane e1 e2 e3 einf\ntype scaled_motor 1 e1^e2 e1^e3 e1^einf e2^e3 "
              "e2^einf e3^einf einf^e0 e1^e2^e3^einf e1^e2^einf^e0 e1^e3^einf^e0 e2^e3^einf^e0\n"),
      opt::Level::O2);
  const auto vv_cga = library::lane_form(find(cga, "gp", "plane", "scaled_motor")->program);
  REQUIRE(vv_cga);
  size_t multiple = 0;
  for (const auto& terms : vv_cga->out) {
    for (size_t k = 1; k < terms.size(); ++k) {
      CHECK(std::make_pair(terms[k - 1].i, terms[k - 1].j) < std::make_pair(terms[k].i, terms[k].j));
      if (terms[k - 1].i == terms[k].i) ++multiple;
    }
  }
  CHECK(multiple > 0);
  // Not bilinear: the sandwich (quadratic in a), a unary operation, the norm's square root.
  CHECK_FALSE(library::lane_form(find(lib, "sandwich", "rotor", "vector")->program));
  CHECK_FALSE(library::lane_form(find(lib, "reverse", "rotor")->program));
  CHECK_FALSE(library::lane_form(find(lib, "norm", "rotor")->program));
}

TEST_CASE("library lanes: a sandwich as r = M(a) b, M(a) made from a alone") {
  const library::Library lib = library::build(spec_of("library l\nalgebra 3d\ntype vector e1 e2 e3\n"
                                                      "type rotor 1 e1^e2 e1^e3 e2^e3\n"),
                                              opt::Level::O2);
  const auto& program = find(lib, "sandwich", "rotor", "vector")->program;
  const auto form = library::linear_form(program);
  REQUIRE(form);
  CHECK(form->na == 4);
  CHECK(form->nb == 3);
  REQUIRE(form->out.size() == 3);
  // R v ~R's e1 coefficient times b0 (e1): a0^2 - a1^2 - a2^2 + a3^2 (the e1^e2 and e1^e3 planes turn e1
  // away, e2^e3 leaves it: e23 e1 e32 = e1), which for the normalized versor the library assumes is
  // 2 a0^2 + 2 a3^2 - 1: the -1 is b0 with no factor of a.
  std::map<std::pair<size_t, size_t>, double> m00;
  for (const auto& t : form->out[0])
    if (t.j == 0) m00[{t.p, t.q}] += t.c;
  const size_t none = library::kNone;
  CHECK(m00 == std::map<std::pair<size_t, size_t>, double>{{{0, 0}, 2}, {{3, 3}, 2}, {{none, none}, -1}});
  for (const auto& terms : form->out)
    for (const auto& t : terms) {
      CHECK(t.p <= t.q);  // kNone, the missing factor, sorts last
      CHECK(t.j < 3);
    }
  // b enters only at the end: one store of Σ_k t_k ⊙ perm_k(b), the t_k made from a alone. The rotation's
  // diagonal needs no shuffle of b; its two others are one shuffle each, and nothing else reads b.
  const library::LaneCode code = library::linear_code(*form);
  CHECK(code.body.find("load<3>(b + 0)") != std::string::npos);
  CHECK(code.body.find("store<3>(r + 0, ") != std::string::npos);
  CHECK(code.body.find(" * b0") != std::string::npos);
  size_t reads_b = 0, lines = 0;
  for (size_t at = 0, end; (end = code.body.find('\n', at)) != std::string::npos; at = end + 1, ++lines) {
    const std::string line = code.body.substr(at, end - at);
    if (line.find("b0") == std::string::npos) continue;
    ++reads_b;
    const bool load = line.find("= load<3>(b + 0)") != std::string::npos;
    const bool shuffle = line.find("const v4 sb") != std::string::npos && line.find("(b0, b0)") != std::string::npos;
    const bool store = line.find("store<3>(r + 0, ") != std::string::npos;
    INFO(line);
    CHECK((load || shuffle || store));
  }
  CHECK(reads_b == 4);
  CHECK(code.ops < 30);  // the scalar kernel's count
  // The same code on every run: the search's restarts are seeded.
  CHECK(library::diagonal_code(*form).body == library::diagonal_code(*form).body);
  // Not linear in b: the product of two rotors has terms a_i b_j, fine, but the norm is no polynomial.
  CHECK(library::linear_form(find(lib, "gp", "rotor", "rotor")->program));
  CHECK_FALSE(library::linear_form(find(lib, "norm", "rotor")->program));
  // The library's one call runs the 4-wide sandwich (the result is one vector), its array form the scalar
  // kernel.
  const std::string text = library::emit_library(lib, {}, "l.gal");
  CHECK(text.find("detail::x4::sandwich_rotor_vector(a.v, b.v, r.v);") != std::string::npos);
  CHECK(text.find("for (std::size_t k = 0; k < n; ++k) detail::sandwich_rotor_vector(a[k].v, b[k].v, r[k].v);") !=
        std::string::npos);
}

TEST_CASE("library lanes: the diagonal form shares shuffles of a between M(a)'s diagonals") {
  // 3D PGA's motor on a point (klein's layout of types): the entries of M(a) on a diagonal are the same
  // polynomials of permuted coefficients, so each diagonal is a few products of two shuffles of a.
  const library::Library lib = library::build(spec_of("library p\nalgebra 3dpga\n"
                                                      "type point e0^e2^e3 e0^e1^e3 e0^e1^e2 e1^e2^e3\n"
                                                      "type motor 1 e2^e3 e1^e3 e1^e2 e0^e1 e0^e2 e0^e3 e0^e1^e2^e3\n"),
                                              opt::Level::O2);
  const auto form = library::linear_form(find(lib, "sandwich", "motor", "point")->program);
  REQUIRE(form);
  const library::LaneCode code = library::diagonal_code(*form);
  // The column form took 62 operations (the matrix's columns from broadcasts of a); klein's hand-written
  // sandwich takes 39 instructions, loads and stores included.
  CHECK(code.ops <= 45);
  CHECK(library::linear_code(*form).body == code.body);
  // One store of four products t_k ⊙ perm_k(b): e123's broadcast (the translation's column) and the
  // rotation's three cyclic diagonals.
  size_t stores = 0, targets = 0;
  for (size_t at = 0; (at = code.body.find("store<4>(r + 0, ", at)) != std::string::npos; ++at) ++stores;
  for (size_t at = 0; (at = code.body.find("const v4 t0_", at)) != std::string::npos; ++at) ++targets;
  CHECK(stores == 1);
  CHECK(targets == 4);
  CHECK(code.body.find("splat<3>(b0)") != std::string::npos);
  // The rotation's identity diagonal reads b as loaded.
  CHECK(std::regex_search(code.body, std::regex(R"(t0_\d \* b0\b)")));
}

TEST_CASE("library lanes: a motor on a line turns both halves by one rotation, its diagonals made once") {
  // The line's Euclidean half (e23 e13 e12) reads only that half of b, its ideal half (e01 e02 e03) all of
  // b; grouped so, the rotation's three diagonals serve both halves, and the stored layout (e01 e02 e03 e23 |
  // e13 e12) is shuffled from the two groups at the end. Rows as stored took 118 operations.
  const library::Library lib = library::build(spec_of("library p\nalgebra 3dpga\n"
                                                      "type line e0^e1 e0^e2 e0^e3 e2^e3 e1^e3 e1^e2\n"
                                                      "type motor 1 e2^e3 e1^e3 e1^e2 e0^e1 e0^e2 e0^e3 e0^e1^e2^e3\n"),
                                              opt::Level::O2);
  const auto form = library::linear_form(find(lib, "sandwich", "motor", "line")->program);
  REQUIRE(form);
  const library::LaneCode code = library::diagonal_code(*form);
  CHECK(code.ops <= 87);
  CHECK(library::linear_code(*form).body == code.body);
  // Six targets in all: the rotation's three and the ideal half's three others.
  size_t targets = 0;
  for (size_t at = 0; (at = code.body.find("  const v4 t", at)) != std::string::npos; ++at) ++targets;
  CHECK(targets == 6);
  // The second group is the rotation's three targets on other shuffles of b.
  std::smatch g1;
  REQUIRE(std::regex_search(code.body, g1, std::regex(R"(const v4 g1 = ([^;]*);)")));
  CHECK(std::regex_search(g1[1].str(), std::regex(R"(^\(?t0_\d \* sb\d+ \+ t0_\d \* sb\d+\)? \+ t0_\d \* sb\d+$)")));
  CHECK(code.body.find("store<4>(r + 0, sg") != std::string::npos);
  CHECK(code.body.find("store<2>(r + 4, sg") != std::string::npos);
  CHECK(library::diagonal_code(*form).body == code.body);
}

TEST_CASE("library matrices: matrix(a, of<B>) for each versor with the scalar blade, its columns the sandwiches of B's blades") {
  const library::Library lib = library::build(spec_of("library l\nalgebra 3d\ntype vector e1 e2 e3\n"
                                                      "type rotor 1 e1^e2 e1^e3 e2^e3\n"),
                                              opt::Level::O2);
  // The rotor is the only type with the scalar blade: one matrix per type it moves.
  REQUIRE(lib.matrices.size() == 2);
  const library::Matrix& m = lib.matrices[0];
  CHECK(lib.types[m.a].name == "rotor");
  CHECK(lib.types[m.b].name == "vector");
  CHECK(lib.types[m.result].name == "vector");
  CHECK(lib.functions[m.sandwich].op->sandwich);
  // Column j is the sandwich of the j-th blade, under the sandwich's promise a ~a = 1.
  CHECK(library::matrix_script(lib.types[m.a], lib.types[m.b], *lib.algebra_ptr) ==
        "#pragma input a 1 e1^e2 e1^e3 e2^e3\n#pragma normalized a\n"
        "m0 = a * (e1) * ~a;\n?c0 = grade(m0, 1);\nm1 = a * (e2) * ~a;\n?c1 = grade(m1, 1);\n"
        "m2 = a * (e3) * ~a;\n?c2 = grade(m2, 1);\n");
  REQUIRE(m.program.outputs.size() == 3);
  for (const auto& out : m.program.outputs) CHECK(out.slots.size() == 3);
  // The 4-wide form stores the columns M(a) of the sandwich's linear form, b nowhere.
  const auto form = library::linear_form(lib.functions[m.sandwich].program);
  REQUIRE(form);
  const library::LaneCode code = library::matrix_code(*form);
  for (const char* store : {"store<3>(c0 + 0, m", "store<3>(c1 + 0, m", "store<3>(c2 + 0, m"}) {
    INFO(store);
    CHECK(code.body.find(store) != std::string::npos);
  }
  CHECK(code.body.find("b0") == std::string::npos);
  const std::string text = library::emit_library(lib, {}, "l.gal");
  CHECK(text.find("inline matrix_t<T, vector_t, vector_t> matrix(const rotor_t<T>& a, of_t<vector_t>)") != std::string::npos);
  CHECK(text.find("detail::x4::matrix_rotor_vector(a.v, r.m[0].v, r.m[1].v, r.m[2].v);") != std::string::npos);
}

TEST_CASE("library array forms: a costly kernel on a type of size other than a power of two staged through blocks") {
  const library::Library lib = library::build(spec_of("library l\nalgebra 3d\n"
                                                      "type rotor 1 e1^e2 e1^e3 e2^e3\n"
                                                      "type mv 1 e1 e2 e3 e1^e2 e1^e3 e2^e3 e1^e2^e3\n"
                                                      "type six 1 e1 e2 e3 e1^e2 e1^e3\n"),
                                              opt::Level::O2);
  const std::string text = library::emit_library(lib, {}, "l.gal");
  // The form the pairs' array form takes: the `if constexpr` of its body.
  auto form_of = [&](const std::string& a, const std::string& b) {
    const library::Function* f = find(lib, "gp", a, b);
    REQUIRE(f);
    const std::string r = lib.types[f->result].name;
    const std::string signature = "inline void gp(const " + a + "_t<T>* a, const " + b + "_t<T>* b, " + r + "_t<T>* r";
    const size_t at = text.find(signature);
    REQUIRE(at != std::string::npos);
    const size_t body = text.find("if constexpr (", at);
    REQUIRE(body != std::string::npos);
    return std::to_string(opt::program_stats(f->program).total.total()) + " " +
           text.substr(body, text.find(')', body) - body + 1);
  };
  CHECK(form_of("rotor", "rotor") == "28 if constexpr (false)");  // cheap
  CHECK(form_of("mv", "mv") == "120 if constexpr (false)");       // sizes 8, 8, 8: vectorized directly
  CHECK(form_of("six", "six") == "64 if constexpr (true)");       // size 6
  CHECK(text.find("detail::staged_pairs<6, 6, 8>(") != std::string::npos);
}

TEST_CASE("cli: --library writes OpenCL C, JavaScript, GLSL ES, HLSL and WGSL the same every run") {
  const std::string spec = std::string(CGA_SOURCE_DIR) + "/libraries/e3.gal";
  const std::vector<std::pair<std::string, std::string>> targets = {
      {"opencl", "e3_rotor e3_gp_vector_vector(e3_vector a, e3_vector b) {"},
      {"opencl", "e3_rotor_f64 e3_gp_vector_vector_f64(e3_vector_f64 a, e3_vector_f64 b) {"},
      {"javascript", "define(\"gp\", gp_vector_vector, Rotor, Vector, Vector);"},
      {"glsl-es", "e3_rotor e3_gp(e3_vector a, e3_vector b) {"},
      {"hlsl", "e3_rotor e3_gp(e3_vector_ a, e3_vector_ b) {"},  // HLSL reserves vector
      {"wgsl", "fn e3_gp_vector_vector(a: e3_vector, b: e3_vector) -> e3_rotor {"}};
  for (const auto& [target, signature] : targets) {
    INFO(target);
    const auto a = cga_test::run("--library --target " + target + " " + spec);
    const auto b = cga_test::run("--library --target " + target + " " + spec);
    REQUIRE(a.code == 0);
    CHECK(a.out == b.out);
    CHECK(a.out.find(signature) != std::string::npos);
  }
}

TEST_CASE("cli: --library writes the library, the same bytes every run, and refuses script options") {
  const std::string spec = std::string(CGA_SOURCE_DIR) + "/libraries/e3.gal";
  const auto a = cga_test::run("--library " + spec), b = cga_test::run("--library " + spec);
  REQUIRE(a.code == 0);
  CHECK(a.out == b.out);
  CHECK(a.out.find("namespace e3 {") != std::string::npos);
  CHECK(a.out.find("inline rotor_t<T> gp(const vector_t<T>& a, const vector_t<T>& b)") != std::string::npos);
  const auto stats = cga_test::run("--library --stats " + spec);
  CHECK(stats.code == 0);
  CHECK(stats.out.find("gp(vector, vector) -> rotor: 5 add, 9 mul, 0 div, 0 call\n") != std::string::npos);
  CHECK(cga_test::run("--library --algebra cga " + spec).code == 2);
  CHECK(cga_test::run("--library --gpc " + spec).code == 2);
  const auto dot = cga_test::run("--library --target dot " + spec);  // a target without library templates
  CHECK(dot.code == 1);
  CHECK(dot.out.find("the dot target has no library templates") != std::string::npos);
  const auto bad = cga_test::run("--library " + cga_test::write_temp("bad.gal", "library x\nalgebra 3d\ntype v e1 e4\n"));
  CHECK(bad.code == 1);
  CHECK(bad.out.find("bad.gal:3:11: error: 'e4' is not a blade of 3d") != std::string::npos);
  CHECK(bad.out.find("type v e1 e4\n          ^") != std::string::npos);
}
