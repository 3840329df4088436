// consumer: checks, in a project outside cgagen's tree, (1) the kernel cgagen generated at build time from
// reflect.clu against plain vector math, in float and double, and (2) cgagen::runtime's motors against GLM.
// Exit status 0 when every check passes, 1 otherwise.
#include <cmath>
#include <cstdio>
#include <random>

#include <cga/runtime/motor.hpp>  // cgagen::runtime (with the kernels it was built from, cgagen::kernels)
#include <e3.hpp>                 // generated from the installed libraries/e3.gal: namespace e3
#include <reflect.hpp>            // generated: cga::kernels::reflect(x, y, z, nx, ny, nz, d, q[5])

namespace {

int failures = 0;

void check(bool ok, const char* what, double error) {
  if (!ok) {
    std::fprintf(stderr, "consumer: %s: error %g\n", what, error);
    ++failures;
  }
}

// Mirror image of p in the plane n.x = d: p - 2 (n.p - d) / |n|^2 n.
template <class T>
void reflect_plain(const T p[3], const T n[3], T d, T out[3]) {
  const T s = 2 * (n[0] * p[0] + n[1] * p[1] + n[2] * p[2] - d) / (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  for (int i = 0; i < 3; ++i) out[i] = p[i] - s * n[i];
}

template <class T>
double reflect_error(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-10.0, 10.0);
  T p[3], n[3];
  for (int i = 0; i < 3; ++i) p[i] = static_cast<T>(u(rng)), n[i] = static_cast<T>(u(rng));
  const T d = static_cast<T>(u(rng));
  T q[5];  // over cga::kernels::reflect_q_blades: e1 e2 e3 einf e0
  cga::kernels::reflect(p[0], p[1], p[2], n[0], n[1], n[2], d, q);
  T plain[3];
  reflect_plain(p, n, d, plain);
  // q is a normalized conformal point: e0 = 1, einf = |q|^2 / 2.
  const double half_norm = 0.5 * (double(plain[0]) * plain[0] + double(plain[1]) * plain[1] + double(plain[2]) * plain[2]);
  double e = std::fabs(double(q[4]) - 1.0) + std::fabs(double(q[3]) - half_norm) / (1.0 + half_norm);
  for (int i = 0; i < 3; ++i) e += std::fabs(double(q[i]) - double(plain[i]));
  return e;
}

}  // namespace

int main() {
  static_assert(cga::kernels::reflect_q_blades.size() == 5);
  std::mt19937 rng(12);
  double worst_d = 0, worst_f = 0;
  for (int i = 0; i < 1000; ++i) {
    worst_d = std::fmax(worst_d, reflect_error<double>(rng));
    worst_f = std::fmax(worst_f, reflect_error<float>(rng));
  }
  check(worst_d < 1e-9, "generated reflect (double) vs plain vector math", worst_d);
  check(worst_f < 1e-2, "generated reflect (float) vs plain vector math", worst_f);
  std::printf("reflect: worst error over 1000 random points and planes: double %.3g, float %.3g\n", worst_d, worst_f);

  // The generated e3 library: the geometric product of two vectors is a rotor, their dot product plus their
  // wedge (e1^e2, e1^e3, e2^e3 in the library's layout).
  const e3::vector u{{1.0f, 2.0f, 3.0f}}, v{{-2.0f, 0.5f, 4.0f}};
  const e3::rotor r = u * v;
  const float want[4] = {1 * -2.0f + 2 * 0.5f + 3 * 4.0f, 1 * 0.5f - 2 * -2.0f, 1 * 4.0f - 3 * -2.0f, 2 * 4.0f - 3 * 0.5f};
  double worst_l = 0;
  for (int k = 0; k < 4; ++k) worst_l = std::fmax(worst_l, std::fabs(double(r[k]) - want[k]));
  check(worst_l < 1e-6, "generated e3 library: vector * vector", worst_l);
  std::printf("e3 library: u * v off by %.3g\n", worst_l);

  // cgagen::runtime: the motor of a scale, rotation and translation moves points as GLM's s R p + t does, and
  // decomposes back to the same transform (motor_to_transform is compiled into libcga_runtime.a).
  cga::Transform x;
  x.translation = glm::vec3(1.0f, -2.0f, 0.5f);
  x.rotation = glm::angleAxis(0.7f, glm::normalize(glm::vec3(1.0f, 2.0f, -1.0f)));
  x.scale = 1.5f;
  const cga::Motor m = cga::motor_from_transform(x);
  double worst_m = 0;
  for (const glm::vec3 p : {glm::vec3(0.0f), glm::vec3(1.0f, 0.0f, 0.0f), glm::vec3(-3.0f, 2.0f, 5.0f)}) {
    const glm::vec3 a = cga::motor_transform_point(m, p);
    const glm::vec3 b = x.scale * (x.rotation * p) + x.translation;
    worst_m = std::fmax(worst_m, double(glm::length(a - b)));
  }
  check(worst_m < 1e-4, "cga::motor_transform_point vs GLM", worst_m);
  const cga::Transform y = cga::motor_to_transform(m);
  const double back = glm::length(y.translation - x.translation) + std::fabs(y.scale - x.scale) +
                      std::fabs(std::fabs(glm::dot(y.rotation, x.rotation)) - 1.0f);
  check(back < 1e-4, "cga::motor_to_transform(motor_from_transform(x)) vs x", back);
  std::printf("runtime: motor vs GLM %.3g, round trip %.3g\n", worst_m, back);

  std::printf("%s\n", failures == 0 ? "consumer: all checks passed" : "consumer: FAILED");
  return failures == 0 ? 0 : 1;
}
