// The print order of a program's assignments (gen/opt/order.hpp): each output element right after the last
// temporary it reads, never before the last temporary that reads a multivector input, and every output after
// the temporaries when an output element reads a multivector input itself. Programs built by hand, so the
// expected orders are exact; then the emitted C++ and GPC statements follow the order, and the arm chain's
// 60 output elements are spread over its temporaries.
#include <catch2/catch.hpp>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "emit/emit.hpp"
#include "emit/statements.hpp"
#include "expand/expand.hpp"
#include "front/parser.hpp"
#include "opt/order.hpp"
#include "opt/program.hpp"

using namespace cgagen;
using GiNaC::ex;
using GiNaC::realsymbol;

namespace {

KernelInput scalar(const std::string& name) {
  KernelInput in;
  in.name = name;
  in.blades = {0};
  in.symbols = {realsymbol(name)};
  return in;
}

KernelInput multivector(const std::string& name, std::vector<algebra::BladeIndex> blades) {
  KernelInput in;
  in.name = name;
  in.is_multivector = true;
  in.blades = blades;
  for (auto b : blades) in.symbols.push_back(realsymbol(name + "_" + std::to_string(b)));
  return in;
}

opt::Temp temp(const std::string& name, const ex& value) { return opt::Temp{name, realsymbol(name), value}; }

// "t0 t1 a.0 ..." for an order: temporaries by name, output elements as NAME.SLOT.
std::string text(const opt::Program& p, const std::vector<opt::Assignment>& order) {
  std::string s;
  for (const auto& a : order) {
    if (!s.empty()) s += " ";
    s += a.kind == opt::Assignment::Kind::Temp ? p.temps[a.index].name
                                               : p.outputs[a.index].name + "." + std::to_string(a.slot);
  }
  return s;
}

// x, y scalar inputs; t0 = x*y, t1 = t0 + x, t2 = t1*t1; output a = {t0, x + y}, b = {t2}, c = {t1 - 1}.
opt::Program scalar_program() {
  opt::Program p;
  p.name = "k";
  p.inputs = {scalar("x"), scalar("y")};
  const ex x = p.inputs[0].symbols[0], y = p.inputs[1].symbols[0];
  p.temps.push_back(temp("t0", x * y));
  p.temps.push_back(temp("t1", p.temps[0].sym + x));
  p.temps.push_back(temp("t2", p.temps[1].sym * p.temps[1].sym));
  p.outputs.push_back({"a", {{1, p.temps[0].sym}, {2, x + y}}});
  p.outputs.push_back({"b", {{0, p.temps[2].sym}}});
  p.outputs.push_back({"c", {{0, p.temps[1].sym - 1}}});
  return p;
}

}  // namespace

TEST_CASE("print order: each output element right after the last temporary it reads", "[emit][order]") {
  const opt::Program p = scalar_program();
  // a.1 reads only inputs: first; a.0 after t0; c.0 after t1; b.0 after t2.
  CHECK(text(p, opt::print_order(p)) == "a.1 t0 a.0 t1 c.0 t2 b.0");
}

TEST_CASE("print order: no output element before the last temporary that reads a multivector input",
          "[emit][order]") {
  opt::Program p = scalar_program();
  p.inputs.push_back(multivector("M", {0, 3}));
  const ex m0 = p.inputs[2].symbols[0], m1 = p.inputs[2].symbols[1];
  // t1 now reads M: a.0 and a.1 wait for it (in output order); c.0 (after t1) and b.0 (after t2) as before.
  p.temps[1].value = p.temps[0].sym + m0 * m1;
  CHECK(text(p, opt::print_order(p)) == "t0 t1 a.0 a.1 c.0 t2 b.0");
}

TEST_CASE("print order: an output element that reads a multivector input keeps every output at the end",
          "[emit][order]") {
  opt::Program p = scalar_program();
  p.inputs.push_back(multivector("M", {0}));
  p.outputs[2].slots[0].value = p.temps[1].sym - p.inputs[2].symbols[0];
  CHECK(text(p, opt::print_order(p)) == "t0 t1 t2 a.0 a.1 b.0 c.0");
}

TEST_CASE("print order: the C++ file and the GPC statements print in it", "[emit][order]") {
  const opt::Program p = scalar_program();
  const std::string code = emit::emit(p, emit::EmitOptions{});
  const std::string fn = code.substr(code.find("inline void k(double"));
  const auto at = [&](const std::string& s) {
    const size_t i = fn.find(s);
    INFO(s);
    REQUIRE(i != std::string::npos);
    return i;
  };
  CHECK(at("a[1] = x + y;") < at("const double t0 = x * y;"));
  CHECK(at("const double t0") < at("a[0] = t0;"));
  CHECK(at("a[0] = t0;") < at("const double t1"));
  CHECK(at("c[0] = t1 - 1.0;") < at("const double t2"));
  CHECK(at("const double t2") < at("b[0] = t2;"));

  emit::StatementOptions so;
  so.type = "double";
  const std::string st = emit::emit_statements(p, so);
  CHECK(st.find("a[1] = x + y;") < st.find("const double t0 = x * y;"));
  CHECK(st.find("c = t1 - 1.0;") < st.find("const double t2"));
}

TEST_CASE("print order: the arm chain's outputs are stored as they are computed", "[emit][order]") {
  std::ifstream f(std::string(CGA_SOURCE_DIR) + "/bench/ik_arm/arm5.clu");
  std::stringstream ss;
  ss << f.rdbuf();
  front::SourceFile file("arm5.clu", ss.str());
  const opt::Program p = opt::optimize(expand(front::parse(file), "arm5"), opt::Level::O2);
  const auto order = opt::print_order(p);
  size_t elements = 0, before_last_temp = 0;
  size_t last_temp = 0;
  for (size_t i = 0; i < order.size(); ++i)
    if (order[i].kind == opt::Assignment::Kind::Temp) last_temp = i;
  for (size_t i = 0; i < order.size(); ++i)
    if (order[i].kind == opt::Assignment::Kind::Output) {
      ++elements;
      before_last_temp += i < last_temp;
    }
  size_t slots = 0;
  for (const auto& o : p.outputs) slots += o.slots.size();
  CHECK(elements == slots);
  CHECK(order.size() == slots + p.temps.size());
  // The rotors R1, R2, R3, T2, R4 and Rg are done before the gripper's last temporary: only some of the
  // gripper point's own elements come after it.
  CHECK(before_last_temp >= slots - 5);
}
