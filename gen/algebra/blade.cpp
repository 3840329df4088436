// Blade order, names and parsing (see blade.hpp): the current algebra's answers (algebra.cpp).
#include "algebra/blade.hpp"

#include "algebra/algebra.hpp"

namespace cgagen::algebra {

int blade_count() { return current().blade_count(); }
BladeBits blade_bits(BladeIndex i) { return current().bits(i); }
BladeIndex blade_index(BladeBits bits) { return current().index(bits); }
int blade_grade(BladeIndex i) { return current().grade(i); }
const std::string& blade_name(BladeIndex i) { return current().blade_name(i); }
const std::string& blade_ident(BladeIndex i) { return current().blade_ident(i); }
std::optional<SignedBlade> parse_blade(std::string_view text) { return current().parse_blade(text); }

}  // namespace cgagen::algebra
