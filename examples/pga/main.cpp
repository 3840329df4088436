// The PGA example's check: the generated 3D PGA motor kernel (pga_motor.clu, built with --algebra 3dpga)
// against plain vector maths on 1000 random points and motors. Exit 0 when every point agrees to 1e-12.
#include <cmath>
#include <cstdio>
#include <random>

#include "pga_motor.hpp"

int main() {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  double worst = 0.0;
  for (int i = 0; i < 1000; ++i) {
    const double a = u(rng), tx = u(rng), ty = u(rng), tz = u(rng), x = u(rng), y = u(rng), z = u(rng);
    double q[4];  // e0^e1^e2, e0^e1^e3, e0^e2^e3, e1^e2^e3 (pga_motor_Q_blades)
    cga::kernels::pga_motor(a, tx, ty, tz, x, y, z, q);
    // A point is e1^e2^e3 - x e0^e2^e3 + y e0^e1^e3 - z e0^e1^e2 (3dpga createPoint), scaled by its weight.
    const double w = q[3], px = -q[2] / w, py = q[1] / w, pz = -q[0] / w;
    // The same motion in vector maths: rotate by a about z, then translate by t.
    const double ex = std::cos(a) * x - std::sin(a) * y + tx, ey = std::sin(a) * x + std::cos(a) * y + ty, ez = z + tz;
    worst = std::fmax(worst, std::fmax(std::fabs(px - ex), std::fmax(std::fabs(py - ey), std::fabs(pz - ez))));
  }
  std::printf("pga_motor: largest difference from vector maths over 1000 points: %.3g\n", worst);
  return worst < 1e-12 ? 0 : 1;
}
