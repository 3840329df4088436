// The batch entry's parts (batch.hpp), spelt by the target's batch_* patterns.
#include "emit/batch.hpp"

namespace cgagen::emit {

namespace {

void join(std::string& list, const std::string& item, const char* sep) {
  list += (list.empty() ? "" : sep) + item;
}

}  // namespace

BatchParts batch_parts(const Syntax& sx, const opt::Program& program,
                       const std::function<std::string(const std::string&)>& id) {
  BatchParts b;
  if (sx.batch_in.empty()) return b;
  const std::string sep = "\n" + sx.indent;
  std::string loads, decls;
  auto fields = [&](const std::string& name, size_t n) {
    // lanes_ is a reserved prefix of the target (names.hpp), so lanes_NAME meets no other name of the file.
    return std::map<std::string, std::string>{
        {"name", id(name)}, {"lanes", "lanes_" + id(name)}, {"n", std::to_string(n)}};
  };
  for (const auto& in : program.inputs) {
    const auto v = fields(in.name, in.symbols.size());
    join(b.params, fill_pattern(sx.batch_in, v), ", ");
    join(b.names, v.at("name"), ", ");
    join(loads, fill_pattern(in.is_multivector ? sx.batch_load_mv : sx.batch_load_scalar, v), sep.c_str());
    join(b.args, v.at("lanes"), ", ");
  }
  for (const auto& o : program.outputs) {
    const auto v = fields(o.name, o.slots.size());
    join(b.params, fill_pattern(sx.batch_out, v), ", ");
    join(b.names, v.at("name"), ", ");
    join(decls, fill_pattern(sx.batch_out_decl, v), sep.c_str());
    join(b.args, v.at("lanes"), ", ");
    join(b.stores, fill_pattern(sx.batch_store, v), sep.c_str());
  }
  b.loads = sx.indent + loads + (decls.empty() ? "" : sep + decls);
  if (!b.stores.empty()) b.stores = sx.indent + b.stores;
  return b;
}

}  // namespace cgagen::emit
