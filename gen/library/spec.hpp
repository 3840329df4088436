// A library spec (cgagen --library SPEC): an algebra and named types, each a set of blades; the generator
// (library/build.hpp) emits every operation of the operator set between the types. The format is a plain
// table, one declaration per line (docs/library.md):
//
//   # 3D PGA with klein's types            (# starts a comment, anywhere on a line)
//   library pga3                           the library's name: namespace / module, file stem
//   algebra 3dpga                          a built-in algebra, or a Gaalop definition.csv beside the spec
//   type plane e1 e2 e3 e0                 a type: a name, then its blades in storage order
//   type motor 1 e0^e1 ... e0^e1^e2^e3     "1" is the scalar blade
//   alias sphere point                     another name of a declared type (CGA's spheres are points' blades)
//
// Blades are written as the algebra spells them (`cgagen --algebra NAME --eval` lists them; e1^e3, not
// e3^e1). Every fault is a front::CompileError at its word.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "algebra/algebra.hpp"
#include "front/diagnostics.hpp"

namespace cgagen::library {

struct Type {
  std::string name;
  std::vector<algebra::BladeIndex> blades;  // in storage order
  front::SourceLoc loc;
  bool declared = true;  // false: named by the generator for a result no declared type holds
};

struct Alias {
  std::string name, type;
  front::SourceLoc loc;
};

struct Spec {
  std::string name;
  std::vector<Alias> aliases;
  std::string algebra_spelling;
  std::shared_ptr<const algebra::Algebra> algebra;
  std::vector<Type> types;
};

// Parses and checks a spec; `dir` is where a definition.csv named by `algebra` is looked for. Throws
// front::CompileError (located) for: an unknown keyword, a missing or repeated `library` / `algebra` line, a
// bad identifier, an unknown algebra, an unknown or reordered blade (the message gives the algebra's
// spelling), a blade twice in one type, two types with the same name or the same blades, a type before
// `algebra`, no types.
Spec parse_spec(const front::SourceFile& file, const std::string& dir);

// The reserved type name of the scalar blade alone; every library has it (results such as norm and scp).
inline const char* const kScalarType = "scalar";

}  // namespace cgagen::library
