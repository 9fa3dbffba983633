// Bit-for-bit comparison of two particle states, for the tests whose reference is the same run
// another way (another instruction set, thread count or step schedule).
#pragma once

#include <gtest/gtest.h>

#include <cstring>

#include "core/particles.hpp"

namespace grainlab::test {

// Ids (storage order), positions, velocities, angular velocities, accumulated rotations, forces
// and torques, each compared byte for byte.
inline void expect_same_particle_bits(const ParticleStore& a, const ParticleStore& b) {
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(a.id, b.id);
  const size_t bytes = a.size() * sizeof(Vec3);
  EXPECT_EQ(0, std::memcmp(a.position.data(), b.position.data(), bytes)) << "positions";
  EXPECT_EQ(0, std::memcmp(a.velocity.data(), b.velocity.data(), bytes)) << "velocities";
  EXPECT_EQ(0, std::memcmp(a.angular_velocity.data(), b.angular_velocity.data(), bytes))
      << "angular velocities";
  EXPECT_EQ(0, std::memcmp(a.rotation.data(), b.rotation.data(), bytes)) << "rotations";
  EXPECT_EQ(0, std::memcmp(a.force.data(), b.force.data(), bytes)) << "forces";
  EXPECT_EQ(0, std::memcmp(a.torque.data(), b.torque.data(), bytes)) << "torques";
}

}  // namespace grainlab::test
