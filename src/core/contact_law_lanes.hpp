// The contact law on the lanes (8, or 4 in the AVX2 pair rows), for pairs and walls alike
// (contact_response of contact/contact_law.hpp without the optional pieces): included by the
// kernel objects core/pair_kernel_simd.cpp and core/wall_kernel_simd.cpp, after
// core/simd_lanes.hpp, inside their per-instruction-set namespace and an anonymous one (no include
// guard and no includes of its own: it is a part of those files).
#ifndef GRAINLAB_SIMD_NS
#error "core/contact_law_lanes.hpp is part of the kernel objects"
#endif

// The constants of each lane's pair (contact/pair_params.hpp): k_n per unit r*, the damping
// ratio, the tangential stiffness and damping ratios and the friction coefficient.
struct LaneConstants {
  vd stiffness_per_radius, damping_ratio, rns, rzs, friction;
  GRAINLAB_LANES_INLINE void set(int l, const PairParams& pair) {
    stiffness_per_radius[l] = pair.stiffness_per_radius;
    damping_ratio[l] = pair.damping_ratio;
    rns[l] = pair.rns;
    rzs[l] = pair.rzs;
    friction[l] = pair.friction;
  }
};

// set_step_displacement with the half-step velocities, body A (the particle of the row, or the
// particle on a wall) and body B: dv = v_B - v_A, the overlap's increment over the drift, and the
// springs' increment. lever_shrink as the scalar law's: 1/2 for two particles, 1 on a wall (whose
// zero spin and lever the lanes multiply and add as the scalar law does: a zero's sign counts).
struct StepIncrement {
  V3 dv;
  vd overlap_increment;
  V3 tangential_displacement;
};
GRAINLAB_LANES_INLINE StepIncrement step_increment(const V3& n, double drift, double lever_shrink,
                                                   const V3& v_a, const V3& w_a, vd lever_a,
                                                   const V3& v_b, const V3& w_b, vd lever_b) {
  const V3 dv = v_b - v_a;
  const vd overlap_increment = -drift * dot(dv, n);
  const vd shift = lever_shrink * 0.5 * overlap_increment;
  const V3 step_relative = dv - cross((lever_b + shift) * w_b + (lever_a + shift) * w_a, n);
  return {dv, overlap_increment, drift * (step_relative - dot(step_relative, n) * n)};
}
// set_relative_velocity with the end-of-step estimates: the dashpots' rates, dU_n/dt and the
// tangential velocity.
struct ContactRates {
  vd overlap_rate;
  V3 tangential_velocity;
};
GRAINLAB_LANES_INLINE ContactRates contact_rates(const V3& n, const V3& v_a, const V3& w_a,
                                                 vd lever_a, const V3& v_b, const V3& w_b,
                                                 vd lever_b) {
  const V3 relative = v_b - v_a - cross(lever_b * w_b + lever_a * w_a, n);
  const vd normal_speed = dot(relative, n);
  return {-normal_speed, relative - normal_speed * n};
}

// What the law gives a contact (contact_response without the optional pieces): the force on
// body A (the particle of the row, or the particle on a wall), the torque arm n x F_t, F_n and
// the spring after the step.
struct LawResult {
  V3 force_on_a, arm;
  vd normal_force;
  V3 spring;
};
// contact_response from the normal force on, for pairs and walls alike: F_n, the spring turned
// into the tangent plane, advanced and capped. k_n, c_n: normal_params; k: the pair's constants;
// spring: the stored history.
GRAINLAB_LANES_INLINE LawResult contact_law(const V3& n, vd overlap, vd overlap_rate,
                                            const V3& tangential_displacement,
                                            const V3& tangential_velocity, vd normal_stiffness,
                                            vd normal_damping, const LaneConstants& k, V3 spring) {
  // normal_force: F_n = k_n U_n + c_n dU_n/dt, clamped at 0
  const vd f = normal_stiffness * overlap + normal_damping * overlap_rate;
  const vd normal_force = f > 0.0 ? f : vd{};
  const vd sliding_stiffness = k.rns * normal_stiffness, sliding_damping = k.rzs * normal_damping;

  // keep_in_tangent_plane: turn the spring into the current tangent plane, length kept
  {
    const vd length2 = dot(spring, spring);
    const V3 in_plane = spring - dot(spring, n) * n;
    const vd in_plane2 = dot(in_plane, in_plane);
    const V3 scaled = lane_sqrt(length2 / in_plane2) * in_plane;
    spring = select(length2 == 0.0, spring, select(in_plane2 > 0.0, scaled, in_plane));
  }
  // spring_slider: advance, respond, cap at mu F_n (slip shortens the spring)
  spring = spring + tangential_displacement;
  V3 tangential = sliding_stiffness * spring + sliding_damping * tangential_velocity;
  {
    const vd cap = k.friction * normal_force;
    const vd magnitude2 = dot(tangential, tangential);
    const vmask slip = magnitude2 > cap * cap;
    const V3 capped = (cap / lane_sqrt(magnitude2)) * tangential;
    const V3 slipped_spring =
        select(sliding_stiffness > 0.0,
               (1.0 / sliding_stiffness) * (capped - sliding_damping * tangential_velocity), V3{});
    tangential = select(slip, capped, tangential);
    spring = select(slip, slipped_spring, spring);
  }
  // the force on A and the torque arm n x F_t (each body's torque is its lever times the arm)
  return {tangential - normal_force * n, cross(n, tangential), normal_force, spring};
}
