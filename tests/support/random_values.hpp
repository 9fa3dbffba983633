// Random inputs for the kernel tests that compare instruction sets on made-up data.
#pragma once

#include <cstdint>
#include <random>

#include "core/vec3.hpp"

namespace grainlab::test {

// Uniform numbers in [-1, 1) and random vectors of them times a scale.
struct Random {
  std::mt19937_64 engine;
  std::uniform_real_distribution<double> u{-1.0, 1.0};
  explicit Random(unsigned seed) : engine(seed) {}
  double uniform() { return u(engine); }
  Vec3 vec3(double scale) { return {scale * u(engine), scale * u(engine), scale * u(engine)}; }
  uint64_t operator()() { return engine(); }
};

}  // namespace grainlab::test
