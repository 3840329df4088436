// Blade order, names and parsing (see blade.hpp for the order).
#include "algebra/blade.hpp"

#include <algorithm>
#include <bit>
#include <vector>

namespace cgagen::algebra {
namespace {

constexpr std::array<const char*, 5> kVectorNames = {"e1", "e2", "e3", "einf", "e0"};
constexpr std::array<const char*, 5> kVectorIdents = {"e1", "e2", "e3", "inf", "0"};

struct Tables {
  std::array<BladeBits, kBladeCount> bits{};
  std::array<BladeIndex, kBladeCount> index_of{};
  std::array<std::string, kBladeCount> names;
  std::array<std::string, kBladeCount> idents;

  Tables() {
    // Gaalop order: by grade, then lexicographic in the vector order e1 < e2 < e3 < einf < e0.
    std::vector<BladeBits> all;
    for (int b = 0; b < kBladeCount; ++b) all.push_back(static_cast<BladeBits>(b));
    auto key = [](BladeBits b) {
      std::vector<int> v;
      for (int k = 0; k < 5; ++k)
        if (b & (1 << k)) v.push_back(k);
      return std::pair{static_cast<int>(v.size()), v};
    };
    std::stable_sort(all.begin(), all.end(), [&](BladeBits a, BladeBits b) { return key(a) < key(b); });
    for (int i = 0; i < kBladeCount; ++i) {
      bits[i] = all[i];
      index_of[all[i]] = i;
      std::string name, ident;
      for (int k = 0; k < 5; ++k) {
        if (!(all[i] & (1 << k))) continue;
        if (!name.empty()) name += "^";
        name += kVectorNames[k];
        // e1^e2 -> e12 ; e1^einf -> e1inf ; einf^e0 -> einf0
        std::string part = kVectorIdents[k];
        if (ident.empty()) ident = (k < 3) ? part : "e" + part;
        else ident += (k < 3) ? part.substr(1) : part;
      }
      names[i] = name.empty() ? "1" : name;
      idents[i] = ident.empty() ? "s" : ident;
    }
  }
};

const Tables& tables() {
  static const Tables t;
  return t;
}

}  // namespace

BladeBits blade_bits(BladeIndex i) { return tables().bits.at(i); }
BladeIndex blade_index(BladeBits bits) { return tables().index_of.at(bits & 31); }
int blade_grade(BladeIndex i) { return std::popcount(static_cast<unsigned>(blade_bits(i))); }
const std::string& blade_name(BladeIndex i) { return tables().names.at(i); }
const std::string& blade_ident(BladeIndex i) { return tables().idents.at(i); }

std::optional<SignedBlade> parse_blade(std::string_view text) {
  if (text == "1") return SignedBlade{0, 1};
  std::vector<int> order;
  size_t pos = 0;
  while (pos <= text.size()) {
    size_t end = text.find('^', pos);
    if (end == std::string_view::npos) end = text.size();
    std::string_view part = text.substr(pos, end - pos);
    auto it = std::find(kVectorNames.begin(), kVectorNames.end(), part);
    if (it == kVectorNames.end()) return std::nullopt;
    int k = static_cast<int>(it - kVectorNames.begin());
    if (std::find(order.begin(), order.end(), k) != order.end()) return std::nullopt;
    order.push_back(k);
    pos = end + 1;
  }
  // Sign of sorting the vectors into increasing order: one minus per transposition (they anticommute).
  int sign = 1;
  for (size_t a = 0; a < order.size(); ++a)
    for (size_t b = a + 1; b < order.size(); ++b)
      if (order[a] > order[b]) sign = -sign;
  BladeBits bits = 0;
  for (int k : order) bits |= static_cast<BladeBits>(1 << k);
  return SignedBlade{blade_index(bits), sign};
}

}  // namespace cgagen::algebra
