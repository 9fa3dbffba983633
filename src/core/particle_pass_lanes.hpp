// The Vec3 helpers and vector types of the per-particle passes (core/particle_passes_simd.hpp):
// included by core/particle_passes_simd.cpp (kick and drift) and core/gather_simd.cpp (the
// gather), inside their per-instruction-set namespace and an anonymous one (no include guard and
// no includes of its own: it is a part of those files, like core/simd_lanes.hpp of the pair
// kernel's). Everything here has internal linkage.
#ifndef GRAINLAB_SIMD_NS
#error "core/particle_pass_lanes.hpp is part of the particle passes' kernel objects"
#endif

#define GRAINLAB_PASS_INLINE [[gnu::always_inline]] inline

// a += s b, component by component (Vec3's a += s * b)
GRAINLAB_PASS_INLINE void add_scaled(double* a, double s, const double* b) {
  a[0] = a[0] + s * b[0];
  a[1] = a[1] + s * b[1];
  a[2] = a[2] + s * b[2];
}
// a += b and a -= b, component by component
GRAINLAB_PASS_INLINE void add(double* a, const double* b) {
  a[0] = a[0] + b[0], a[1] = a[1] + b[1], a[2] = a[2] + b[2];
}
GRAINLAB_PASS_INLINE void subtract(double* a, const double* b) {
  a[0] = a[0] - b[0], a[1] = a[1] - b[1], a[2] = a[2] - b[2];
}

#if defined(__AVX512F__)
// GCC's vectors (no undefined-lane intrinsics): 8 doubles
using v8 = double __attribute__((vector_size(64)));
GRAINLAB_PASS_INLINE v8 splat(double x) {
  return v8{x, x, x, x, x, x, x, x};
}
GRAINLAB_PASS_INLINE v8 load(const double* p) {
  v8 r;
  __builtin_memcpy(&r, p, sizeof r);
  return r;
}
#elif defined(__AVX2__)
// 4 doubles, one 256-bit register
using v4 = double __attribute__((vector_size(32)));
GRAINLAB_PASS_INLINE v4 splat(double x) {
  return v4{x, x, x, x};
}
GRAINLAB_PASS_INLINE v4 load(const double* p) {
  v4 r;
  __builtin_memcpy(&r, p, sizeof r);
  return r;
}
#endif
