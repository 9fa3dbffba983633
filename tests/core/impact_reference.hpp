// An independent reference for single oblique impacts under the linear spring-dashpot law with a
// Coulomb-capped tangential spring (docs/contact-model.md), written for the tests only: it shares
// no code with grainlab's contact law or integrator.
//
// The motion is planar (x-z plane, spins about y), which is the setting of the oblique-impact
// benchmarks of Chung & Ooi (Granular Matter 13, 2011, tests 4-8: a sphere on a wall and two
// equal spheres, with tangential velocity and with spin). The tangential spring is a scalar s
// along the in-plane tangent t = (n_z, 0, -n_x), which turns with the normal n without changing
// length. An optional spin about the wall normal exercises the twisting spring.
//
// Integration: classical RK4 with a fine step h. Every force is continuous in time once the
// contact has begun (it begins at t = 0 exactly, and the clamped normal force and the capped
// springs only have kinks), so RK4 converges at second order or better through the events; the
// tests check that halving h changes nothing that matters.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>

namespace impact_reference {

struct Constants {
  double k_n, c_n;                         // normal spring and dashpot
  double k_s, c_s, mu;                     // sliding spring, dashpot, friction
  double k_roll = 0, c_roll = 0, arf = 0;  // rolling spring (N m/rad), dashpot, ARF
  double twisting_friction = 0;            // twisting: same k, c as rolling
};

struct Body {
  double radius, mass, inertia;
  double x, z, vx, vz, w;  // w: spin about y
  double w_normal = 0;     // spin about z (twisting; wall case only)
};

struct State {
  Body a, b;
  double spring = 0, roll = 0, twist = 0;  // sliding (m), rolling (rad), twisting (rad)
};

struct Outcome {
  double tangential_restitution;  // -(v_t after)/(v_t before), contact-point velocities
  double spin_a;                  // rad/s after the impact
  double twist_ratio;             // w_normal after / before (wall case)
  double vx_a, vz_a;
};

struct Derivative {
  double dx_a, dz_a, dvx_a, dvz_a, dw_a, dwn_a;
  double dx_b, dz_b, dvx_b, dvz_b, dw_b;
  double dspring, droll, dtwist;
};

// wall: body b is the plane z = 0 (fixed, infinite mass), body a lies above it.
class Integrator {
 public:
  Integrator(const Constants& c, bool wall) : c_(c), wall_(wall) {}

  struct Contact {
    double nx, nz, overlap, lever_a, lever_b, overlap_rate, tangential_rate;
    double normal_force;
  };

  Contact geometry(const State& s) const {
    Contact g{};
    if (wall_) {
      g.nx = 0.0, g.nz = -1.0;
      g.overlap = s.a.radius - s.a.z;
      g.lever_a = s.a.z, g.lever_b = 0.0;
    } else {
      const double dx = s.b.x - s.a.x, dz = s.b.z - s.a.z, d = std::hypot(dx, dz);
      g.nx = dx / d, g.nz = dz / d;
      g.overlap = s.a.radius + s.b.radius - d;
      g.lever_a = s.a.radius - 0.5 * g.overlap, g.lever_b = s.b.radius - 0.5 * g.overlap;
    }
    const double tx = g.nz, tz = -g.nx;
    const double vbx = wall_ ? 0.0 : s.b.vx, vbz = wall_ ? 0.0 : s.b.vz, wb = wall_ ? 0.0 : s.b.w;
    const double rvx = vbx - s.a.vx, rvz = vbz - s.a.vz;
    g.overlap_rate = -(rvx * g.nx + rvz * g.nz);
    // surface velocities: v_a + lever_a w_a t and v_b - lever_b w_b t (w x n = w t in this plane)
    g.tangential_rate = rvx * tx + rvz * tz - g.lever_b * wb - g.lever_a * s.a.w;
    g.normal_force = std::max(0.0, c_.k_n * g.overlap + c_.c_n * g.overlap_rate);
    return g;
  }

  static double capped(double response, double cap) {
    return std::abs(response) > cap ? std::copysign(cap, response) : response;
  }
  double contact_radius(double overlap, const State& s) const {
    if (wall_) {
      const double r = s.a.radius, q = r * r - (r - overlap) * (r - overlap);
      return q > 0 ? std::sqrt(q) : 0.0;
    }
    const double ra = s.a.radius, rb = s.b.radius, d = ra + rb - overlap;
    const double xx = (d * d + rb * rb - ra * ra) / (2 * d), q = rb * rb - xx * xx;
    return q > 0 ? std::sqrt(q) : 0.0;
  }

  Derivative derivative(const State& s) const {
    const Contact g = geometry(s);
    const double tx = g.nz, tz = -g.nx;
    const double f_n = g.normal_force;
    const double f_t = capped(c_.k_s * s.spring + c_.c_s * g.tangential_rate, c_.mu * f_n);
    const double a_radius = contact_radius(g.overlap, s);
    const double roll_rate = (wall_ ? 0.0 : s.b.w) - s.a.w;
    const double m_roll =
        c_.arf > 0 ? capped(c_.k_roll * s.roll + c_.c_roll * roll_rate, c_.arf * a_radius * f_n)
                   : 0.0;
    const double twist_rate = s.a.w_normal;  // (w_b - w_a) . n with n = -z, w_b = 0
    const double m_twist = c_.twisting_friction > 0
                               ? capped(c_.k_roll * s.twist + c_.c_roll * twist_rate,
                                        c_.twisting_friction * a_radius * f_n)
                               : 0.0;
    // force on a: f_t t - f_n n; b gets the opposite. Torque (y) on a: lever_a f_t, on b:
    // lever_b f_t; rolling moment +m on a, -m on b; twisting moment m n on a (z: -m).
    const double fx = f_t * tx - f_n * g.nx, fz = f_t * tz - f_n * g.nz;
    Derivative d{};
    d.dx_a = s.a.vx, d.dz_a = s.a.vz, d.dvx_a = fx / s.a.mass, d.dvz_a = fz / s.a.mass;
    d.dw_a = (g.lever_a * f_t + m_roll) / s.a.inertia;
    d.dwn_a = -m_twist / s.a.inertia;
    if (!wall_) {
      d.dx_b = s.b.vx, d.dz_b = s.b.vz, d.dvx_b = -fx / s.b.mass, d.dvz_b = -fz / s.b.mass;
      d.dw_b = (g.lever_b * f_t - m_roll) / s.b.inertia;
    }
    d.dspring = g.tangential_rate, d.droll = roll_rate, d.dtwist = twist_rate;
    return d;
  }

  static State add(const State& s, const Derivative& d, double h) {
    State r = s;
    r.a.x += h * d.dx_a, r.a.z += h * d.dz_a, r.a.vx += h * d.dvx_a, r.a.vz += h * d.dvz_a;
    r.a.w += h * d.dw_a, r.a.w_normal += h * d.dwn_a;
    r.b.x += h * d.dx_b, r.b.z += h * d.dz_b, r.b.vx += h * d.dvx_b, r.b.vz += h * d.dvz_b;
    r.b.w += h * d.dw_b;
    r.spring += h * d.dspring, r.roll += h * d.droll, r.twist += h * d.dtwist;
    return r;
  }

  // After a step the springs keep only what their caps allow (Cundall-Strack), as in the model.
  void slip(State& s) const {
    const Contact g = geometry(s);
    const double f_n = g.normal_force;
    auto shorten = [](double& spring, double k, double c, double rate, double cap) {
      const double response = k * spring + c * rate;
      if (std::abs(response) > cap) spring = (std::copysign(cap, response) - c * rate) / k;
    };
    shorten(s.spring, c_.k_s, c_.c_s, g.tangential_rate, c_.mu * f_n);
    const double a_radius = contact_radius(g.overlap, s);
    if (c_.arf > 0)
      shorten(s.roll, c_.k_roll, c_.c_roll, (wall_ ? 0.0 : s.b.w) - s.a.w, c_.arf * a_radius * f_n);
    if (c_.twisting_friction > 0)
      shorten(s.twist, c_.k_roll, c_.c_roll, s.a.w_normal, c_.twisting_friction * a_radius * f_n);
  }

  // Integrates from first touch (t = 0) until the bodies have separated and no force acts.
  State run(State s, double h) const {
    for (long step = 0; step < 100'000'000; ++step) {
      const Derivative k1 = derivative(s);
      const Derivative k2 = derivative(add(s, k1, 0.5 * h));
      const Derivative k3 = derivative(add(s, k2, 0.5 * h));
      const Derivative k4 = derivative(add(s, k3, h));
      Derivative d;
      auto mix = [&](double Derivative::*f) {
        d.*f = (k1.*f + 2 * k2.*f + 2 * k3.*f + k4.*f) / 6.0;
      };
      for (auto f : {&Derivative::dx_a, &Derivative::dz_a, &Derivative::dvx_a, &Derivative::dvz_a,
                     &Derivative::dw_a, &Derivative::dwn_a, &Derivative::dx_b, &Derivative::dz_b,
                     &Derivative::dvx_b, &Derivative::dvz_b, &Derivative::dw_b,
                     &Derivative::dspring, &Derivative::droll, &Derivative::dtwist})
        mix(f);
      s = add(s, d, h);
      if (geometry(s).overlap < 0.0 && step > 0) return s;
      slip(s);
    }
    return s;
  }

 private:
  Constants c_;
  bool wall_;
};

// Contact-point tangential velocity (scalar along t) of rigid spheres, for restitution figures.
inline double contact_point_tangential_velocity(const State& s, bool wall) {
  double nx = 0, nz = -1;
  if (!wall) {
    const double dx = s.b.x - s.a.x, dz = s.b.z - s.a.z, d = std::hypot(dx, dz);
    nx = dx / d, nz = dz / d;
  }
  const double tx = nz, tz = -nx;
  const double vbx = wall ? 0 : s.b.vx, vbz = wall ? 0 : s.b.vz, wb = wall ? 0 : s.b.w;
  const double rb = wall ? 0 : s.b.radius;
  return (vbx - s.a.vx) * tx + (vbz - s.a.vz) * tz - rb * wb - s.a.radius * s.a.w;
}

}  // namespace impact_reference
