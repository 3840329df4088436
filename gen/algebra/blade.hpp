// Blade order, names and parsing of the algebra being compiled (algebra::current(), algebra.hpp).
// In CGA R(4,1), the default, these are the 32 basis blades over the null basis {e1, e2, e3, einf, e0}, in
// Gaalop's order:
//   index 0: 1;  1-5: e1 e2 e3 einf e0;
//   6-15:  the 2-blades, 16-25: the 3-blades, 26-30: the 4-blades, lexicographic in the names' order
//          e1 < e2 < e3 < einf < e0 (so 6 = e1^e2, 7 = e1^e3, 8 = e1^einf, 9 = e1^e0, 10 = e2^e3, ...);
//   31: e1^e2^e3^einf^e0.
// A blade is also named by its bitmap over the user basis: in CGA bit 0 e1, bit 1 e2, bit 2 e3, bit 3 einf,
// bit 4 e0. Every algebra orders its blades the same way: by grade, then lexicographic in its vector order.
// Every generated kernel stores multivectors as coefficients on these blades, in this order.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace cgagen::algebra {

inline constexpr int kBladeCount = 32;  // CGA's blade count; algebra::blade_count() for the current algebra
using BladeIndex = int;           // 0..blade_count()-1, the order above
using BladeBits = std::uint32_t;  // bitmap over the user basis vectors

int blade_count();  // of the current algebra: 2^n
BladeBits blade_bits(BladeIndex i);
BladeIndex blade_index(BladeBits bits);
int blade_grade(BladeIndex i);
// "1", "e1", "e1^e2", "e1^e2^e3^einf^e0"
const std::string& blade_name(BladeIndex i);
// C identifier form: "1" -> "s", "e1^einf" -> "e1inf", "einf^e0" -> "einf0"
const std::string& blade_ident(BladeIndex i);
// Parses "1", "e1", "e1^e2", "einf^e0", also "e0^einf" (returns the index and sign +-1 of the reordering).
// nullopt when the text is not a product of distinct basis vector names.
struct SignedBlade {
  BladeIndex index;
  int sign;
};
std::optional<SignedBlade> parse_blade(std::string_view text);

}  // namespace cgagen::algebra
