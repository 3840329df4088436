// Seeded random motors for the motor tests: random transforms (with or without scale), and blends of a few
// nearby ones as the layers of an animation blend give them.
#pragma once

#include <cmath>
#include <random>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "cga/runtime/motor.hpp"

namespace cga::test {

// Translation within 5 of the origin, any rotation, and a scale in [e^-1.5, e^1.5] (1 without `scaled`).
inline Transform random_transform(std::mt19937& rng, bool scaled = true) {
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  Transform x;
  x.translation = glm::vec3(u(rng), u(rng), u(rng)) * 5.0f;
  x.rotation = glm::normalize(glm::quat(u(rng), u(rng), u(rng), u(rng)));
  x.scale = scaled ? std::exp(1.5f * u(rng)) : 1.0f;
  return x;
}

// A weighted sum of n nearby random motors (weights summing to 1, each motor on the first one's side), times
// w: the first one's transform, the others moved, turned (and with `scaled`, scaled) a little from it.
inline Motor random_blend(std::mt19937& rng, int n, float w, bool scaled = true) {
  std::uniform_real_distribution<float> u(0.05f, 1.0f), d(-1.0f, 1.0f);
  const Transform first = random_transform(rng, scaled);
  std::vector<Motor> m;
  std::vector<float> weight;
  float sum = 0.0f;
  for (int i = 0; i < n; ++i) {
    Transform x = first;
    if (i > 0) {
      x.translation += glm::vec3(d(rng), d(rng), d(rng));
      x.rotation = glm::normalize(x.rotation + 0.4f * glm::quat(d(rng), d(rng), d(rng), d(rng)));
      if (scaled) x.scale *= std::exp(0.3f * d(rng));
    }
    m.push_back(motor_from_transform(x));
    weight.push_back(u(rng));
    sum += weight.back();
  }
  Motor out;
  out.c.fill(0.0f);
  for (int i = 0; i < n; ++i) {
    const float sign = motor_rotor_dot(m[i], m[0]) < 0.0f ? -1.0f : 1.0f;
    for (int c = 0; c < 12; ++c) out.c[c] += w * sign * weight[i] / sum * m[i].c[c];
  }
  return out;
}

}  // namespace cga::test
