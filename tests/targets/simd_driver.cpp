// The simd driver's source (simd_driver.hpp): a generic harness plus one call adapter per case.
#include "simd_driver.hpp"

namespace targets {

namespace {

const char* kHarness = R"(
// Body inputs: the prepared values first (staged), then the per-element inputs, each In of `size` blades.
struct CaseInfo {
  void (*batch)(size_t, const In*, const Out*);
  void (*prepare)(const float*, float*);  // null unstaged: uniform inputs flat -> prepared[K]
  std::vector<size_t> in_sizes, out_sizes;
  std::vector<int> uniform;
  size_t prepared;
};

struct Stream {
  std::vector<float> data;
  std::vector<std::int32_t> index;
};

// Lays n elements' values (get(i, k), `size` blades) out as layout 0 (structure of arrays), 1 (array of
// structures), 2 (rows in reverse order, gathered through an index stream of stride 2) or 3 (broadcast).
template <class Get>
In lay_out(Stream& s, size_t n, size_t size, int layout, Get get) {
  if (layout == 3) {
    s.data.resize(size);
    for (size_t k = 0; k < size; ++k) s.data[k] = get(0, k);
    return In{s.data.data(), 0, 1, nullptr, 1};
  }
  s.data.assign(n * size, 0.0f);
  if (layout == 0) {
    for (size_t i = 0; i < n; ++i)
      for (size_t k = 0; k < size; ++k) s.data[k * n + i] = get(i, k);
    return In{s.data.data(), 1, static_cast<std::ptrdiff_t>(n), nullptr, 1};
  }
  if (layout == 1) {
    for (size_t i = 0; i < n; ++i)
      for (size_t k = 0; k < size; ++k) s.data[i * size + k] = get(i, k);
    return In{s.data.data(), static_cast<std::ptrdiff_t>(size), 1, nullptr, 1};
  }
  s.index.assign(2 * n, -1);
  for (size_t i = 0; i < n; ++i) {
    const size_t row = n - 1 - i;
    s.index[2 * i] = static_cast<std::int32_t>(row);
    for (size_t k = 0; k < size; ++k) s.data[row * size + k] = get(i, k);
  }
  return In{s.data.data(), static_cast<std::ptrdiff_t>(size), 1, s.index.data(), 2};
}

int run(int which, bool broadcast) {
  const CaseInfo& c = kCases[which];
  size_t nin = 0, nout = 0;
  for (size_t s : c.in_sizes) nin += s ? s : 1;
  for (size_t s : c.out_sizes) nout += s;
  std::vector<double> rows;
  for (double v; std::scanf("%lf", &v) == 1;) rows.push_back(v);
  const size_t n = rows.size() / nin;
  auto value = [&](size_t i, size_t j) { return static_cast<float>(rows[(broadcast ? 0 : i) * nin + j]); };
  std::vector<Stream> streams(c.in_sizes.size() + 1);
  std::vector<In> ins;
  int slot = 0;
  auto layout = [&] { return broadcast ? 3 : (which + slot++) % 3; };
  if (c.prepare) {  // NAME_prepare per row (on its uniform inputs), the prepared values a stream
    std::vector<float> prepared(n * c.prepared);
    for (size_t i = 0; i < n; ++i) {
      std::vector<float> u;
      size_t off = 0;
      for (size_t j = 0; j < c.in_sizes.size(); ++j) {
        const size_t size = c.in_sizes[j] ? c.in_sizes[j] : 1;
        if (c.uniform[j])
          for (size_t k = 0; k < size; ++k) u.push_back(value(i, off + k));
        off += size;
      }
      c.prepare(u.data(), &prepared[i * c.prepared]);
    }
    ins.push_back(lay_out(streams.back(), n, c.prepared, layout(),
                          [&](size_t i, size_t k) { return prepared[i * c.prepared + k]; }));
  }
  size_t off = 0;
  for (size_t j = 0; j < c.in_sizes.size(); ++j) {
    const size_t size = c.in_sizes[j] ? c.in_sizes[j] : 1;
    if (!c.prepare || !c.uniform[j])
      ins.push_back(lay_out(streams[j], n, size, layout(), [&](size_t i, size_t k) { return value(i, off + k); }));
    off += size;
  }
  // Outputs: structure of arrays or (scattered) array of structures, alternately.
  std::vector<std::vector<float>> out_data(c.out_sizes.size());
  std::vector<Out> outs;
  for (size_t o = 0; o < c.out_sizes.size(); ++o) {
    out_data[o].assign(n * c.out_sizes[o], NAN);
    const bool soa = broadcast || (which + o) % 2 == 0;
    outs.push_back(soa ? Out{out_data[o].data(), 1, static_cast<std::ptrdiff_t>(n)}
                       : Out{out_data[o].data(), static_cast<std::ptrdiff_t>(c.out_sizes[o]), 1});
  }
  c.batch(n, ins.data(), outs.data());
  for (size_t i = 0; i < n; ++i) {
    size_t col = 0;
    for (size_t o = 0; o < c.out_sizes.size(); ++o)
      for (size_t k = 0; k < c.out_sizes[o]; ++k, ++col) {
        const bool soa = broadcast || (which + o) % 2 == 0;
        const float v = soa ? out_data[o][k * n + i] : out_data[o][i * c.out_sizes[o] + k];
        std::printf(col ? " %.9g" : "%.9g", static_cast<double>(v));
      }
    std::printf("\n");
  }
  (void)nout;
  return 0;
}
)";

std::string list(const std::vector<size_t>& v) {
  std::string s;
  for (size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + std::to_string(v[i]);
  return s;
}

}  // namespace

std::string simd_driver_source(const std::vector<SimdCase>& cases, bool dispatch, long long not_run) {
  std::string src = "// The simd target's test driver (tests/targets/simd_driver.cpp). Generated; do not edit.\n";
  if (dispatch)
    src += "#define CGAGEN_SIMD_DISPATCH\n"
           "#define HWY_DISABLED_TARGETS (HWY_SVE | HWY_SVE2 | HWY_SVE_256 | HWY_SVE2_128 | HWY_RVV | " +
           std::to_string(not_run) + "LL)\n"
           "#define HWY_TARGET_INCLUDE \"all.simd.hpp\"\n"
           "#include <hwy/foreach_target.h>\n";
  src += "#include \"all.simd.hpp\"\n#include <hwy/targets.h>\n#include <cmath>\n#include <cstdio>\n"
         "#include <cstdlib>\n#include <cstring>\n#include <vector>\n\nusing namespace cga::kernels::simd;\n\n";
  std::string table;
  for (size_t i = 0; i < cases.size(); ++i) {
    const SimdCase& c = cases[i];
    const std::string id = std::to_string(i);
    // The batch call: body inputs (prepared first), then outputs.
    size_t nbody = (c.prepared ? 1 : 0);
    for (size_t j = 0; j < c.in_sizes.size(); ++j) nbody += !(c.prepared && c.uniform[j]);
    std::string args;
    for (size_t j = 0; j < nbody; ++j) args += ", in[" + std::to_string(j) + "]";
    for (size_t o = 0; o < c.out_sizes.size(); ++o) args += ", out[" + std::to_string(o) + "]";
    src += "static void batch" + id + "(size_t n, const In* in, const Out* out) {\n  " + c.fn + "_batch(n" + args +
           ");\n  (void)in;\n}\n";
    std::string prepare = "nullptr";
    if (c.prepared) {
      std::string pargs;
      size_t off = 0;
      for (size_t j = 0; j < c.in_sizes.size(); ++j)
        if (c.uniform[j]) {
          pargs += (pargs.empty() ? "" : ", ") + (c.in_sizes[j] ? "&u[" + std::to_string(off) + "]"
                                                                : "u[" + std::to_string(off) + "]");
          off += c.in_sizes[j] ? c.in_sizes[j] : 1;
        }
      src += "static void prepare" + id + "(const float* u, float* prepared) {\n  " + c.prepare + "(" + pargs +
             ", prepared);\n}\n";
      prepare = "prepare" + id;
    }
    std::vector<size_t> uniform;
    for (bool u : c.uniform) uniform.push_back(u);
    table += "  {batch" + id + ", " + prepare + ", {" + list(c.in_sizes) + "}, {" + list(c.out_sizes) + "}, {" +
             list(uniform) + "}, " + std::to_string(c.prepared) + "},\n";
  }
  src += "struct CaseInfo;\nextern const CaseInfo kCases[];\n";
  std::string harness = kHarness;
  src += harness.substr(0, harness.find("struct Stream")) + "const CaseInfo kCases[] = {\n" + table + "};\n\n" +
         harness.substr(harness.find("struct Stream"));
  // The instruction sets: every one Highway compiled and the CPU runs (dispatch), or the static one.
  src += dispatch ? R"(
int main(int argc, char** argv) {
  if (argc == 2 && std::strcmp(argv[1], "list") == 0) {
    for (int64_t t : hwy::SupportedAndGeneratedTargets())
      std::printf("%lld %s\n", static_cast<long long>(t), t == HWY_EMU128 ? "EMU128" : hwy::TargetName(t));
    return 0;
  }
  if (argc != 4) return 2;
  hwy::SetSupportedTargetsForTest(std::atoll(argv[2]));
  const int rc = run(std::atoi(argv[1]), std::strcmp(argv[3], "broadcast") == 0);
  hwy::SetSupportedTargetsForTest(0);
  return rc;
}
)"
                  : R"(
int main(int argc, char** argv) {
  if (argc == 2 && std::strcmp(argv[1], "list") == 0) {
    std::printf("%lld %s\n", static_cast<long long>(HWY_STATIC_TARGET), hwy::TargetName(HWY_STATIC_TARGET));
    return 0;
  }
  if (argc != 4) return 2;
  return run(std::atoi(argv[1]), std::strcmp(argv[3], "broadcast") == 0);
}
)";
  return src;
}

}  // namespace targets
