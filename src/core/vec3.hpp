// A 3-vector of doubles: positions, velocities, forces, torques (SI units throughout).
#pragma once

#include <cmath>
#include <vector>

namespace grainlab {

struct Vec3 {
  double x = 0.0, y = 0.0, z = 0.0;

  constexpr Vec3& operator+=(const Vec3& b) {
    x += b.x;
    y += b.y;
    z += b.z;
    return *this;
  }
  constexpr Vec3& operator-=(const Vec3& b) {
    x -= b.x;
    y -= b.y;
    z -= b.z;
    return *this;
  }
  constexpr Vec3& operator*=(double s) {
    x *= s;
    y *= s;
    z *= s;
    return *this;
  }
  constexpr double operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
  constexpr double& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
  friend constexpr bool operator==(const Vec3&, const Vec3&) = default;
};
static_assert(sizeof(Vec3) == 24, "Vec3 must stay three packed doubles (SoA arrays of it are hot)");

// A Vec3 array as its 3 n doubles (x, y, z of each element in turn), for the vectorised loops
// (core/pair_kernel_simd.hpp, core/particle_passes_simd.hpp).
template <class Allocator>
double* components(std::vector<Vec3, Allocator>& v) {
  return reinterpret_cast<double*>(v.data());
}
template <class Allocator>
const double* components(const std::vector<Vec3, Allocator>& v) {
  return reinterpret_cast<const double*>(v.data());
}

constexpr Vec3 operator+(const Vec3& a, const Vec3& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
constexpr Vec3 operator-(const Vec3& a, const Vec3& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
constexpr Vec3 operator-(const Vec3& a) {
  return {-a.x, -a.y, -a.z};
}
constexpr Vec3 operator*(double s, const Vec3& a) {
  return {s * a.x, s * a.y, s * a.z};
}
constexpr Vec3 operator*(const Vec3& a, double s) {
  return {s * a.x, s * a.y, s * a.z};
}
constexpr double dot(const Vec3& a, const Vec3& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
constexpr Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
constexpr double norm2(const Vec3& a) {
  return dot(a, a);
}
inline double norm(const Vec3& a) {
  return std::sqrt(dot(a, a));
}

}  // namespace grainlab
