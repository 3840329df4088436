// cga-klein-bench: the generated 3D PGA library (libraries/pga3.gal through cgagen --library) against klein
// (jeremyong/klein, hand-written SSE), on the operations klein's own perf/ measures: rotor and motor
// composition, a motor applied to a point, a line and a plane, motor to 3x4 matrix, exp and log.
//
// Both sides get the same seeded random elements (drawn as klein values, converted by convert.hpp) and every
// result is compared, element by element, before anything is timed: a relative difference above 1e-4 prints the
// inputs and both results and the run exits with status 1.
//
// Three figures per operation and side:
//  - one call: a dependent chain, the result is the next call's argument (x = x * r[i], x = m[i](x)), so a call
//    starts when the previous one ends; the other argument is the next of 1024 elements (in L1), so nothing is
//    loop-invariant. The result's full value is carried, every coefficient. exp and log have no such chain
//    alone (their result is the other type), so they are timed as the pair x = log(exp(x)).
//  - loop: out[i] = op(a[i], b[i]), the time per element, over 4096 elements (in cache: the arithmetic) and
//    over N (default 2^20, arrays of 16-32 MB, in memory): klein's operation in a loop, the generated library's
//    array form op(a, b, out, n). Plus each side's batch form of one motor applied to an array of points
//    (klein's motor::operator()(point*, point*, size_t), the generated sandwich(m, points, out, n)).
// Each figure is the median of --klein_repetitions runs; the two sides of an operation run back to back.
//
//   cga-klein-bench [--klein_check_only] [--klein_markdown=FILE] [--klein_repetitions=5] [--klein_n=1048576]
//                   [Google Benchmark flags]
#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "counted.hpp"

namespace {

constexpr std::size_t kRing = 1024;   // the other argument of the one-call chains
constexpr std::size_t kCache = 4096;  // the in-cache loop: 3 arrays of at most 32 B per element, 384 KiB in L2
constexpr double kTolerance = 1e-4;   // relative to the largest coefficient of klein's result (at least 1)

struct Options {
  bool check_only = false;
  std::string markdown;
  int repetitions = 5;
  std::size_t n = std::size_t{1} << 20;
};

Options parse(int& argc, char** argv) {
  Options o;
  int out = 1;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&](const char* key) -> const char* {
      const std::size_t k = std::strlen(key);
      return a.compare(0, k, key) == 0 ? argv[i] + k : nullptr;
    };
    if (a == "--klein_check_only") o.check_only = true;
    else if (const char* v = value("--klein_markdown=")) o.markdown = v;
    else if (const char* v = value("--klein_repetitions=")) o.repetitions = std::max(1, std::atoi(v));
    else if (const char* v = value("--klein_n=")) o.n = std::max<std::size_t>(kRing, std::strtoull(v, nullptr, 10));
    else argv[out++] = argv[i];  // Google Benchmark's
  }
  argc = out;
  return o;
}

// ---- Inputs --------------------------------------------------------------------------------------------------

template <class K, class P>
struct Set {
  std::vector<K> k;
  std::vector<P> p;
};

// Each draw's numbers are taken in a fixed order (locals, not function arguments, whose order is unspecified),
// so the inputs are the same with every compiler.
class Draw {
 public:
  explicit Draw(unsigned seed) : rng_(seed) {}
  kln::rotor rotor() {  // angle in (0, 2 pi): the scalar part takes both signs
    const float angle = u(0.05f, 6.2f);
    float x, y, z;
    axis(x, y, z);
    return kln::rotor(angle, x, y, z);
  }
  kln::motor motor() {  // normalized: a unit rotor times a translator
    const kln::rotor r = rotor();
    const float d = u(-5.f, 5.f);
    float x, y, z;
    axis(x, y, z);
    return r * kln::translator(d, x, y, z);
  }
  kln::point point() {
    const float x = u(-10.f, 10.f), y = u(-10.f, 10.f), z = u(-10.f, 10.f);
    return kln::point(x, y, z);
  }
  kln::plane plane() {  // a x + b y + c z + d = 0
    const float a = u(-1.f, 1.f), b = u(-1.f, 1.f), c = u(-1.f, 1.f), d = u(-10.f, 10.f);
    return kln::plane(a, b, c, d);
  }
  kln::line line() {  // Pluecker coordinates a e01 + b e02 + c e03 + d e23 + e e31 + f e12
    const float a = u(-1.f, 1.f), b = u(-1.f, 1.f), c = u(-1.f, 1.f);
    const float d = u(-1.f, 1.f), e = u(-1.f, 1.f), f = u(-1.f, 1.f);
    return kln::line(a, b, c, d, e, f);
  }
  // exp's argument: a general bivector whose Euclidean part has norm in (0.01, 3), below pi so that log(exp(x))
  // is x again; the small norms take the generated exp's series branch (norm below 0.1).
  kln::line bivector() {
    const float a = u(-3.f, 3.f), b = u(-3.f, 3.f), c = u(-3.f, 3.f), norm = u(0.01f, 3.f);
    float x, y, z;
    axis(x, y, z);
    const float s = norm / std::sqrt(x * x + y * y + z * z);
    return kln::line(a, b, c, s * x, s * y, s * z);
  }

 private:
  float u(float lo, float hi) { return std::uniform_real_distribution<float>(lo, hi)(rng_); }
  void axis(float& x, float& y, float& z) {
    do {
      x = u(-1.f, 1.f), y = u(-1.f, 1.f), z = u(-1.f, 1.f);
    } while (x * x + y * y + z * z < 0.01f);
  }
  std::mt19937 rng_;
};

template <class K, class P, class F>
Set<K, P> draw(std::size_t n, unsigned seed, F f) {
  Draw d(seed);
  Set<K, P> s;
  s.k.reserve(n);
  s.p.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    s.k.push_back(f(d));
    s.p.push_back(kb::to_pga3(s.k.back()));
  }
  return s;
}

struct Inputs {
  Set<kln::rotor, pga3::rotor> rotors, rotors2;
  Set<kln::motor, pga3::motor> motors, motors2;
  Set<kln::point, pga3::point> points;
  Set<kln::line, pga3::line> lines, bivectors;
  Set<kln::plane, pga3::plane> planes;
};

Inputs make_inputs(std::size_t n) {
  Inputs in;
  in.rotors = draw<kln::rotor, pga3::rotor>(n, 1, [](Draw& d) { return d.rotor(); });
  in.rotors2 = draw<kln::rotor, pga3::rotor>(n, 2, [](Draw& d) { return d.rotor(); });
  in.motors = draw<kln::motor, pga3::motor>(n, 3, [](Draw& d) { return d.motor(); });
  in.motors2 = draw<kln::motor, pga3::motor>(n, 4, [](Draw& d) { return d.motor(); });
  in.points = draw<kln::point, pga3::point>(n, 5, [](Draw& d) { return d.point(); });
  in.lines = draw<kln::line, pga3::line>(n, 6, [](Draw& d) { return d.line(); });
  in.bivectors = draw<kln::line, pga3::line>(n, 7, [](Draw& d) { return d.bivector(); });
  in.planes = draw<kln::plane, pga3::plane>(n, 8, [](Draw& d) { return d.plane(); });
  // The last elements are the special cases of exp and log, which random draws do not reach: the identity, a
  // translation alone, an exact half turn (scalar part 0) with a translation, a rotation by 0.001 radian; a zero
  // bivector, an ideal one (a translation), one of Euclidean norm 1e-4.
  const kln::motor motors[] = {kln::motor(1, 0, 0, 0, 0, 0, 0, 0), kln::motor(kln::translator(2.f, 1, 0, 0)),
                               kln::motor(0, 0, 0, 1, 0.5f, 0.2f, 0, 0),
                               kln::rotor(1e-3f, 1, 2, 3) * kln::translator(3.f, 0, 1, 0)};
  const kln::line bivectors[] = {kln::line(0, 0, 0, 0, 0, 0), kln::line(1, 2, 3, 0, 0, 0),
                                 kln::line(0.1f, 0, 0, 1e-4f, 0, 0)};
  for (std::size_t k = 0; k < std::size(motors); ++k) {
    in.motors.k[n - 1 - k] = motors[k];
    in.motors.p[n - 1 - k] = kb::to_pga3(motors[k]);
  }
  for (std::size_t k = 0; k < std::size(bivectors); ++k) {
    in.bivectors.k[n - 1 - k] = bivectors[k];
    in.bivectors.p[n - 1 - k] = kb::to_pga3(bivectors[k]);
  }
  return in;
}

// ---- Checks --------------------------------------------------------------------------------------------------

template <std::size_t N>
double rel_diff(const float (&want)[N], const float (&got)[N]) {
  double scale = 1, d = 0;
  for (std::size_t k = 0; k < N; ++k) scale = std::max(scale, std::abs(double(want[k])));
  for (std::size_t k = 0; k < N; ++k) d = std::max(d, std::abs(double(want[k]) - double(got[k])));
  return d / scale;
}

template <class T>
std::string show(const T& x) {
  std::ostringstream s;
  s.precision(9);
  for (std::size_t k = 0; k < std::size(x.v); ++k) s << (k ? " " : "") << x.blades[k] << '=' << x.v[k];
  return s.str();
}

// A Euclidean point, for the check of the layout map.
struct Xyz {
  float v[3];
  static constexpr std::array<std::string_view, 3> blades = {"x", "y", "z"};
};

// Where the two sides differ, an arbiter (for log) may say which one is right: it returns how far each side's
// result misses the defining property (for log: exp(result) against the motor, through klein's own exp).
struct NoArbiter {};

struct Checker {
  int failed_ops = 0;
  // want(i): klein's result in pga3's layout, got(i): the generated one; args(i): the inputs, printed on a fault.
  template <class Want, class Got, class Args, class Arbiter = NoArbiter>
  void run(const char* op, std::size_t n, Want want, Got got, Args args, Arbiter arbiter = {}) {
    std::size_t bad = 0, klein_off = 0, worst_i = 0;
    double worst = 0, klein_miss = 0, cgagen_miss = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const auto w = want(i);
      const auto g = got(i);
      const double d = rel_diff(w.v, g.v);
      if (!(d <= worst)) worst = d, worst_i = i;
      if (d <= kTolerance) continue;
      if constexpr (!std::is_same_v<Arbiter, NoArbiter>) {
        const auto [miss_k, miss_c] = arbiter(i);
        if (miss_c <= kTolerance / 10 && miss_c < miss_k) {  // the generated result is the right one
          if (klein_off++ < 3)
            std::printf("check %s element %zu: klein's result is the less accurate one (relative difference %.2g;"
                        " misses by klein %.2g, cgagen %.2g)\n  inputs: %s\n  klein:  %s\n  cgagen: %s\n",
                        op, i, d, miss_k, miss_c, args(i).c_str(), show(w).c_str(), show(g).c_str());
          klein_miss = std::max(klein_miss, miss_k), cgagen_miss = std::max(cgagen_miss, miss_c);
          continue;
        }
      }
      if (bad++ < 3)
        std::fprintf(stderr, "cga-klein-bench: WRONG %s element %zu: relative difference %g\n  inputs: %s\n"
                             "  klein:  %s\n  cgagen: %s\n",
                     op, i, d, args(i).c_str(), show(w).c_str(), show(g).c_str());
    }
    std::printf("check %-32s %zu elements: %s (largest relative difference %.2g, element %zu)\n", op, n,
                bad ? "DIFFERENT" : klein_off ? "equal but where klein is the less accurate" : "equal", worst,
                worst_i);
    if (klein_off)
      std::printf("check %-32s %zu elements where klein's result is the less accurate (misses by up to %.2g;"
                  " cgagen's by up to %.2g)\n", op, klein_off, klein_miss, cgagen_miss);
    if (bad) {
      std::printf("check %-32s %zu of %zu elements differ beyond %g\n", op, bad, n, kTolerance);
      ++failed_ops;
    }
  }
};

// How far exp(l) (klein's exp) misses the motor m, relative to its largest coefficient.
double exp_miss(const kln::line& l, const kln::motor& m) {
  const pga3::motor want = kb::to_pga3(m), got = kb::to_pga3(kln::exp(l));
  return rel_diff(want.v, got.v);
}

// Both sides' out-of-line functions (counted.hpp) on the elements of sets a and b, klein's result converted.
template <class KA, class KB, class KR, class CA, class CB, class CR>
void check_binary(Checker& c, const char* op, const Set<KA, CA>& a, const Set<KB, CB>& b,
                  void (*klein)(const KA*, const KB*, KR*), void (*cgagen)(const CA*, const CB*, CR*)) {
  c.run(op, a.k.size(),
        [&](std::size_t i) { KR r; klein(&a.k[i], &b.k[i], &r); return kb::to_pga3(r); },
        [&](std::size_t i) { CR r; cgagen(&a.p[i], &b.p[i], &r); return r; },
        [&](std::size_t i) { return show(a.p[i]) + " | " + show(b.p[i]); });
}

int check(const Inputs& in) {
  const std::size_t n = in.motors.k.size();
  Checker c;
  using kb::to_pga3;
  check_binary(c, "gp(rotor, rotor)", in.rotors, in.rotors2, kb_klein_gp_rotor_rotor, kb_cgagen_gp_rotor_rotor);
  check_binary(c, "gp(motor, motor)", in.motors, in.motors2, kb_klein_gp_motor_motor, kb_cgagen_gp_motor_motor);
  check_binary(c, "sandwich(motor, point)", in.motors, in.points, kb_klein_sandwich_motor_point,
               kb_cgagen_sandwich_motor_point);
  // The same, read as Euclidean points (klein's x(), y(), z() against the generated point divided by its
  // e1^e2^e3): the layout map of convert.hpp on its own terms.
  c.run("sandwich(motor, point) as x y z", n,
        [&](std::size_t i) {
          const kln::point r = in.motors.k[i](in.points.k[i]);
          return Xyz{{r.x() / r.w(), r.y() / r.w(), r.z() / r.w()}};
        },
        [&](std::size_t i) {
          const pga3::point r = pga3::sandwich(in.motors.p[i], in.points.p[i]);
          return Xyz{{-r.v[0] / r.v[3], r.v[1] / r.v[3], -r.v[2] / r.v[3]}};
        },
        [&](std::size_t i) { return show(in.motors.p[i]) + " | " + show(in.points.p[i]); });
  check_binary(c, "sandwich(motor, line)", in.motors, in.lines, kb_klein_sandwich_motor_line,
               kb_cgagen_sandwich_motor_line);
  check_binary(c, "sandwich(motor, plane)", in.motors, in.planes, kb_klein_sandwich_motor_plane,
               kb_cgagen_sandwich_motor_plane);
  // The matrices differ in layout (klein's acts on x y z 1, the generated one on the point's blade
  // coefficients): each is checked by the points it moves.
  c.run("motor -> mat3x4 (applied)", n,
        [&](std::size_t i) {
          kln::mat3x4 m;
          kb_klein_motor_to_mat3x4(&in.motors.k[i], &m);
          const pga3::point p = in.points.p[i];
          const float xyz1[4] = {-p.v[0] / p.v[3], p.v[1] / p.v[3], -p.v[2] / p.v[3], 1.f};
          alignas(16) float r[4];
          _mm_store_ps(r, m(_mm_loadu_ps(xyz1)));
          return kb::point_of_xyzw(r);
        },
        [&](std::size_t i) {
          const pga3::point p = in.points.p[i];
          const pga3::point unit{{p.v[0] / p.v[3], p.v[1] / p.v[3], p.v[2] / p.v[3], 1.f}};
          pga3::matrix_t<float, pga3::point_t, pga3::point_t> m;
          kb_cgagen_motor_to_matrix(&in.motors.p[i], &m);
          return m(unit);
        },
        [&](std::size_t i) { return show(in.motors.p[i]) + " | " + show(in.points.p[i]); });
  c.run("exp(line)", n,
        [&](std::size_t i) { kln::motor r; kb_klein_exp_line(&in.bivectors.k[i], &r); return to_pga3(r); },
        [&](std::size_t i) { pga3::motor r; kb_cgagen_exp_line(&in.bivectors.p[i], &r); return r; },
        [&](std::size_t i) { return show(in.bivectors.p[i]); });
  c.run("log(motor)", n,
        [&](std::size_t i) { kln::line r; kb_klein_log_motor(&in.motors.k[i], &r); return to_pga3(r); },
        [&](std::size_t i) { pga3::line r; kb_cgagen_log_motor(&in.motors.p[i], &r); return r; },
        [&](std::size_t i) { return show(in.motors.p[i]); },
        [&](std::size_t i) {
          const kln::motor& m = in.motors.k[i];
          return std::pair{exp_miss(kln::log(m), m), exp_miss(kb::to_klein(pga3::log(in.motors.p[i])), m)};
        });
  std::printf("cga-klein-bench: %s\n", c.failed_ops ? "results DIFFER (nothing timed)" : "every result equal");
  return c.failed_ops;
}

// ---- Timing --------------------------------------------------------------------------------------------------

// Keeps a chain's last value alive through a copy: DoNotOptimize takes the address of what it is given, and GCC
// keeps an aggregate whose address is taken (the library's types are structs of a float array) in memory for
// its whole life, so the chain itself would store and reload it at every call. klein's types are vector
// registers either way.
template <class X>
void keep(const X& x) {
  X kept = x;
  benchmark::DoNotOptimize(kept);
}

// One call: x = step(x, ring[i]), the full result carried into the next call.
template <class X, class R, class F>
void chain(benchmark::State& s, X x, const std::vector<R>& ring, F step) {
  std::size_t i = 0;
  for (auto _ : s) x = step(x, ring[i++ & (kRing - 1)]);
  keep(x);
}

// The loop: out[i] = f(a[i], b[i]) over the first s.range(0) elements; the time of one pass.
template <class A, class B, class F>
void loop(benchmark::State& s, const std::vector<A>& a, const std::vector<B>& b, F f) {
  using R = decltype(f(a[0], b[0]));
  const auto n = static_cast<std::size_t>(s.range(0));
  std::vector<R> out(n);  // value-initialized: its pages are in place before the timing
  for (auto _ : s) {
    for (std::size_t i = 0; i < n; ++i) out[i] = f(a[i], b[i]);
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
}

// The generated library's array form of the same loop: f(a, b, out, n) over the first s.range(0) elements,
// R the result's type.
template <class R, class A, class B, class F>
void array_loop(benchmark::State& s, const std::vector<A>& a, const std::vector<B>& b, F f) {
  const auto n = static_cast<std::size_t>(s.range(0));
  std::vector<R> out(n);
  for (auto _ : s) {
    f(a.data(), b.data(), out.data(), n);
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
}

// A matrix has no value chain (it is not a motor): the next motor's index depends on the previous matrix
// instead (a comparison of its last column's first entry that never holds), so each conversion starts when the
// previous one ends.
void chain_mat3x4(benchmark::State& s, const std::vector<kln::motor>& ring) {
  kln::mat3x4 m = ring[0].as_mat3x4();
  std::size_t i = 0;
  for (auto _ : s) {
    const std::size_t j = (i++ + (_mm_cvtss_f32(m.cols[3]) > 1e30f)) & (kRing - 1);
    m = ring[j].as_mat3x4();
  }
  keep(m);
}
void chain_matrix(benchmark::State& s, const std::vector<pga3::motor>& ring) {
  auto m = pga3::matrix(ring[0], pga3::of<pga3::point_t>);
  std::size_t i = 0;
  for (auto _ : s) {
    const std::size_t j = (i++ + (m.m[3].v[0] > 1e30f)) & (kRing - 1);
    m = pga3::matrix(ring[j], pga3::of<pga3::point_t>);
  }
  keep(m);
}

struct Row {
  std::string op;     // the table's first column
  std::string stats;  // its `cgagen --stats` function, "" for none
  std::string note;   // where the generated library has no counterpart
  std::function<void(benchmark::State&)> klein_call, cgagen_call, klein_loop, cgagen_loop;
};

// The operations as each side spells them. The chains carry their first argument: x = x * r, and x = m(x)
// through flip.
constexpr auto klein_gp = [](const auto& a, const auto& b) { return a * b; };
constexpr auto cgagen_gp = [](const auto& a, const auto& b) { return pga3::gp(a, b); };
constexpr auto klein_apply = [](const auto& m, const auto& x) { return m(x); };
constexpr auto cgagen_apply = [](const auto& m, const auto& x) { return pga3::sandwich(m, x); };
constexpr auto cgagen_gp_n = [](const auto* a, const auto* b, auto* r, std::size_t n) { pga3::gp(a, b, r, n); };
constexpr auto cgagen_apply_n = [](const auto* m, const auto* x, auto* r, std::size_t n) {
  pga3::sandwich(m, x, r, n);
};
constexpr auto flip = [](auto f) { return [f](const auto& x, const auto& m) { return f(m, x); }; };
constexpr auto klein_exp = [](const kln::line& l, const kln::line&) { return kln::exp(l); };
constexpr auto cgagen_exp = [](const pga3::line& l, const pga3::line&) { return pga3::exp(l); };
constexpr auto klein_log = [](const kln::motor& m, const kln::motor&) { return kln::log(m); };
constexpr auto cgagen_log = [](const pga3::motor& m, const pga3::motor&) { return pga3::log(m); };
constexpr auto klein_exp_log = [](const kln::line& l, const kln::line&) { return kln::log(kln::exp(l)); };
constexpr auto cgagen_exp_log = [](const pga3::line& l, const pga3::line&) { return pga3::log(pga3::exp(l)); };
constexpr auto klein_mat = [](const kln::motor& m, const kln::motor&) { return m.as_mat3x4(); };
constexpr auto cgagen_mat = [](const pga3::motor& m, const pga3::motor&) { return pga3::matrix(m, pga3::of<pga3::point_t>); };

// The four figures of a binary operation on sets a (the chained argument's first value, and the loop's first
// argument) and b.
template <class A, class B, class K, class C, class N>
Row binary(const char* op, const char* stats, const A& a, const B& b, K k, C c, N cn) {
  return {op, stats, "",
          [&a, &b, k](auto& s) { chain(s, a.k[0], b.k, k); },
          [&a, &b, c](auto& s) { chain(s, a.p[0], b.p, c); },
          [&a, &b, k](auto& s) { loop(s, a.k, b.k, k); },
          [&a, &b, c, cn](auto& s) { array_loop<decltype(c(a.p[0], b.p[0]))>(s, a.p, b.p, cn); }};
}

// A motor applied to the set x: chained through x, the loop over (motor, x) pairs.
template <class X>
Row apply(const char* op, const char* stats, const Inputs& in, const X& x) {
  const auto& m = in.motors;
  return {op, stats, "",
          [&m, &x](auto& s) { chain(s, x.k[0], m.k, flip(klein_apply)); },
          [&m, &x](auto& s) { chain(s, x.p[0], m.p, flip(cgagen_apply)); },
          [&m, &x](auto& s) { loop(s, m.k, x.k, klein_apply); },
          [&m, &x](auto& s) {
            array_loop<decltype(cgagen_apply(m.p[0], x.p[0]))>(s, m.p, x.p, cgagen_apply_n);
          }};
}

std::vector<Row> rows(const Inputs& in) {
  std::vector<Row> r;
  r.push_back(binary("rotor * rotor", "gp(rotor, rotor)", in.rotors, in.rotors2, klein_gp, cgagen_gp, cgagen_gp_n));
  r.push_back(binary("motor * motor", "gp(motor, motor)", in.motors, in.motors2, klein_gp, cgagen_gp, cgagen_gp_n));
  r.push_back(apply("motor(point)", "sandwich(motor, point)", in, in.points));
  r.push_back(apply("motor(line)", "sandwich(motor, line)", in, in.lines));
  r.push_back(apply("motor(plane)", "sandwich(motor, plane)", in, in.planes));
  // klein's batch form: one motor, its motor-only work done once, over every point.
  const auto* p = &in;
  r.push_back({"motor(point), one motor over the array", "sandwich(motor, point)", "", nullptr, nullptr,
               [p](auto& s) {
                 std::vector<kln::point> out(static_cast<std::size_t>(s.range(0)));
                 auto* x = const_cast<kln::point*>(p->points.k.data());  // klein's signature; it only reads it
                 for (auto _ : s) {
                   p->motors.k[0](x, out.data(), out.size());
                   benchmark::DoNotOptimize(out.data());
                   benchmark::ClobberMemory();
                 }
               },
               [p](auto& s) {
                 std::vector<pga3::point> out(static_cast<std::size_t>(s.range(0)));
                 const pga3::motor m = p->motors.p[0];
                 for (auto _ : s) {
                   pga3::sandwich(m, p->points.p.data(), out.data(), out.size());
                   benchmark::DoNotOptimize(out.data());
                   benchmark::ClobberMemory();
                 }
               }});
  r.push_back({"motor -> mat3x4", "matrix(motor, point)", "", [p](auto& s) { chain_mat3x4(s, p->motors.k); },
               [p](auto& s) { chain_matrix(s, p->motors.p); },
               [p](auto& s) { loop(s, p->motors.k, p->motors.k, klein_mat); },
               [p](auto& s) { loop(s, p->motors.p, p->motors.p, cgagen_mat); }});
  r.push_back({"log(exp(line)), chained", "", "",
               [p](auto& s) { chain(s, p->bivectors.k[0], p->bivectors.k, klein_exp_log); },
               [p](auto& s) { chain(s, p->bivectors.p[0], p->bivectors.p, cgagen_exp_log); }, nullptr, nullptr});
  r.push_back({"exp(line)", "exp(line)", "", nullptr, nullptr,
               [p](auto& s) { loop(s, p->bivectors.k, p->bivectors.k, klein_exp); },
               [p](auto& s) { loop(s, p->bivectors.p, p->bivectors.p, cgagen_exp); }});
  r.push_back({"log(motor)", "log(motor)", "", nullptr, nullptr,
               [p](auto& s) { loop(s, p->motors.k, p->motors.k, klein_log); },
               [p](auto& s) { loop(s, p->motors.p, p->motors.p, cgagen_log); }});
  return r;
}

// Keeps the median real time of each benchmark's repetitions and prints one short line per figure.
class Collector : public benchmark::BenchmarkReporter {
 public:
  std::map<std::string, double> median;  // name -> ns per iteration
  bool ReportContext(const Context&) override { return true; }
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& r : runs) {
      // "klein/motor(point)/loop/4096": the registered name and the loop's length
      const std::string name = r.run_name.function_name + (r.run_name.args.empty() ? "" : "/" + r.run_name.args);
      if (r.error_occurred) {
        std::printf("%-52s ERROR %s\n", name.c_str(), r.error_message.c_str());
        continue;
      }
      const bool single = r.run_type == Run::RT_Iteration && r.repetitions <= 1;  // no aggregate then
      if (!single && (r.run_type != Run::RT_Aggregate || r.aggregate_name != "median")) continue;
      median[name] = r.GetAdjustedRealTime();
      std::printf("%-52s %12.3f ns per iteration\n", name.c_str(), median[name]);
      std::fflush(stdout);
    }
  }
};

// `cgagen --library libraries/pga3.gal --stats`, generated beside pga3.hpp: "gp(motor, motor) -> motor: 40 add,
// 48 mul, 0 div, 0 call" per function.
std::map<std::string, std::string> read_stats(const char* path) {
  std::map<std::string, std::string> out;
  std::ifstream f(path);
  std::string line;
  while (std::getline(f, line)) {
    const std::size_t arrow = line.find(" -> "), colon = line.find(": ");
    if (arrow == std::string::npos || colon == std::string::npos) continue;
    int add = 0, mul = 0, div = 0, call = 0;
    if (std::sscanf(line.c_str() + colon + 2, "%d add, %d mul, %d div, %d call", &add, &mul, &div, &call) != 4)
      continue;
    char cell[64];
    std::snprintf(cell, sizeof cell, "%d / %d / %d / %d", add, mul, div, call);
    out[line.substr(0, arrow)] = cell;
  }
  return out;
}

std::string cell(double ns) {
  char b[32];
  std::snprintf(b, sizeof b, ns < 10 ? "%.2f" : ns < 100 ? "%.1f" : "%.0f", ns);
  return b;
}

std::string ratio(double cg, double kl, double target) {
  char b[48];
  std::snprintf(b, sizeof b, "%.2f (%s)", cg / kl, cg / kl <= target ? "met" : "missed");
  return b;
}

std::string table(const std::vector<Row>& rs, const Collector& c, std::size_t n) {
  const auto stats = read_stats(KB_STATS_FILE);
  auto get = [&](const std::string& name, std::size_t per) {
    const auto it = c.median.find(name);
    return it == c.median.end() ? -1.0 : it->second / double(per);
  };
  std::ostringstream t;
  t << "| operation | one call: klein (ns) | cgagen (ns) | cgagen/klein (target ≤ 1.0) | loop of " << kCache
    << ", per element: klein (ns) | cgagen (ns) | cgagen/klein | loop of " << n
    << ", per element: klein (ns) | cgagen (ns) | cgagen/klein (target ≤ 0.8) | cgagen add / mul / div / call |\n"
    << "|---|---:|---:|---|---:|---:|---|---:|---:|---|---|\n";
  for (const Row& r : rs) {
    const std::string none = r.note.empty() ? "—" : r.note;
    auto figure = [&](const std::string& suffix, std::size_t per, double target) {
      const double kl = get("klein/" + r.op + suffix, per), cg = get("cgagen/" + r.op + suffix, per);
      t << " " << (kl > 0 ? cell(kl) : "—") << " | " << (cg > 0 ? cell(cg) : none) << " | ";
      if (kl > 0 && cg > 0 && target > 0) t << ratio(cg, kl, target) << " |";
      else if (kl > 0 && cg > 0) t << cell(cg / kl) << " |";
      else t << "— |";
    };
    t << "| " << r.op << " |";
    figure("/call", 1, 1.0);
    figure("/loop/" + std::to_string(kCache), kCache, 0);
    figure("/loop/" + std::to_string(n), n, 0.8);
    const auto st = stats.find(r.stats);
    t << " " << (r.stats.empty() ? "—" : st == stats.end() ? "(no stats)" : st->second) << " |\n";
  }
  return t.str();
}

}  // namespace

int main(int argc, char** argv) {
  Options opt = parse(argc, argv);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 2;

  const Inputs in = make_inputs(opt.n);
  if (check(in)) return 1;
  if (opt.check_only) return 0;

  // Each operation's sides back to back, klein first in every other figure. The loops run twice: over kCache
  // elements (in cache: the arithmetic's throughput) and over all of them (in memory).
  const std::vector<Row> rs = rows(in);
  int k = 0;
  for (const Row& r : rs) {
    for (const std::size_t n : {std::size_t{0}, kCache, opt.n}) {  // 0: one call
      const bool call = n == 0;
      const char* kind = call ? "call" : "loop";
      std::vector<std::pair<std::string, const std::function<void(benchmark::State&)>*>> sides = {
          {"klein", call ? &r.klein_call : &r.klein_loop}, {"cgagen", call ? &r.cgagen_call : &r.cgagen_loop}};
      if (k++ % 2) std::swap(sides[0], sides[1]);
      for (const auto& [side, fn] : sides) {
        if (!*fn) continue;
        auto* b = benchmark::RegisterBenchmark((side + "/" + r.op + "/" + kind).c_str(), *fn);
        if (!call) b->Arg(static_cast<std::int64_t>(n));
        b->Repetitions(opt.repetitions)->ReportAggregatesOnly(true)->DisplayAggregatesOnly(true);
      }
    }
  }
  Collector collector;
  benchmark::RunSpecifiedBenchmarks(&collector);
  benchmark::Shutdown();

  const std::string t = table(rs, collector, opt.n);
  std::printf("\n%s", t.c_str());
  if (!opt.markdown.empty()) std::ofstream(opt.markdown) << t;
  return 0;
}
