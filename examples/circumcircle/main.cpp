// cga-circumcircle x1 y1 z1 x2 y2 z2 x3 y3 z3: the circle through three points, computed by the C++ that
// cgagen generated at build time from circumcircle.clu (see CMakeLists.txt), and by plain vector geometry for
// comparison. Exit status 1 when the two disagree, 2 on bad usage.
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include <circumcircle.hpp>  // generated: cga::kernels::circumcircle(x1, ..., z3, m[5], r[1])

namespace {

using Vec = std::array<double, 3>;
Vec sub(Vec a, Vec b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Vec cross(Vec a, Vec b) { return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}; }
double dot(Vec a, Vec b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// Circumcentre of a triangle: a + (|u|² (v × w) + |v|² (w × u)) / (2 |w|²) with u = b - a, v = c - a, w = u × v.
Vec circumcentre(Vec a, Vec b, Vec c) {
  const Vec u = sub(b, a), v = sub(c, a), w = cross(u, v);
  const Vec p = cross(v, w), q = cross(w, u);
  const double s = 2.0 * dot(w, w);
  return {a[0] + (dot(u, u) * p[0] + dot(v, v) * q[0]) / s, a[1] + (dot(u, u) * p[1] + dot(v, v) * q[1]) / s,
          a[2] + (dot(u, u) * p[2] + dot(v, v) * q[2]) / s};
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 10) {
    std::fprintf(stderr, "usage: cga-circumcircle x1 y1 z1 x2 y2 z2 x3 y3 z3\n");
    return 2;
  }
  double in[9];
  for (int i = 0; i < 9; ++i) {
    char* end = nullptr;
    in[i] = std::strtod(argv[i + 1], &end);
    if (end == argv[i + 1] || *end != '\0' || !std::isfinite(in[i])) {
      std::fprintf(stderr, "cga-circumcircle: '%s' is not a finite number\n", argv[i + 1]);
      return 2;
    }
  }
  const Vec a{in[0], in[1], in[2]}, b{in[3], in[4], in[5]}, c{in[6], in[7], in[8]};
  if (dot(cross(sub(b, a), sub(c, a)), cross(sub(b, a), sub(c, a))) == 0.0) {
    std::fprintf(stderr, "cga-circumcircle: the points are collinear, no circle passes through them\n");
    return 2;
  }

  double m[5], r[1];  // m over the blades cga::kernels::circumcircle_m_blades (e1 e2 e3 einf e0)
  cga::kernels::circumcircle(in[0], in[1], in[2], in[3], in[4], in[5], in[6], in[7], in[8], m, r);
  std::printf("generated: centre (%.9g, %.9g, %.9g), radius %.9g\n", m[0], m[1], m[2], r[0]);

  const Vec centre = circumcentre(a, b, c);
  const double radius = std::sqrt(dot(sub(a, centre), sub(a, centre)));
  std::printf("geometry:  centre (%.9g, %.9g, %.9g), radius %.9g\n", centre[0], centre[1], centre[2], radius);

  const double error = std::fabs(m[0] - centre[0]) + std::fabs(m[1] - centre[1]) + std::fabs(m[2] - centre[2]) +
                       std::fabs(r[0] - radius);
  const double scale = 1.0 + std::sqrt(dot(a, a) + dot(b, b) + dot(c, c));
  if (!(error <= 1e-9 * scale) || std::fabs(m[4] - 1.0) > 1e-12) {
    std::fprintf(stderr, "cga-circumcircle: generated and plain results differ by %g\n", error);
    return 1;
  }
  return 0;
}
