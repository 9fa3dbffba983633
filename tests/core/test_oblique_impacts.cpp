// Oblique impacts against an independent reference integration (impact_reference.hpp): the
// benchmarks of Chung & Ooi (Granular Matter 13, 2011, tests 4-8) re-posed for the linear
// spring-dashpot law with a Coulomb-capped tangential spring. A sphere hits a wall, or two equal
// spheres hit each other, with a tangential impact velocity of Psi mu v_n (Psi from 0.5, sticking,
// to 10, gross sliding), without spin, with back-spin and with top-spin, for k_s/k_n = 2/7 and 1
// and e = 0.5 and 1. grainlab's tangential restitution must lie within 0.005 of the reference at
// 50 steps per contact, and its error must fall at second order when the step is halved; the same
// for rolling resistance and twisting. The error figures are printed as a table.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "contact/time_step.hpp"
#include "core/impact_reference.hpp"
#include "support/scenes.hpp"

using namespace grainlab;
using namespace grainlab::test;
namespace ref = impact_reference;

namespace {

constexpr double radius = 1e-3;       // m
constexpr double normal_speed = 0.5;  // m/s, approach speed along the normal
constexpr double friction = 0.3;

enum class Spin { none, back, top };

struct ImpactCase {
  bool wall;
  double psi;  // contact-point tangential impact speed / (mu v_n)
  Spin spin;
  double rns, restitution;
  double rzs = 0.0, arf = 0.0, twisting_friction = 0.0;
  double normal_spin = 0.0;             // rad/s about the wall normal (twisting; wall only)
  double rolling_damping_ratio = -1.0;  // eta_theta; < 0: the normal zeta (grainlab's default)

  std::string name() const {
    const char* s = spin == Spin::none ? "no spin" : spin == Spin::back ? "back-spin" : "top-spin";
    return fmt::format(
        "{} psi={} {} ks/kn={:.3f} e={}{}{}{}{}", wall ? "wall" : "pair", psi, s, rns, restitution,
        rzs > 0 ? fmt::format(" rzs={}", rzs) : "", arf > 0 ? fmt::format(" arf={}", arf) : "",
        twisting_friction > 0 ? fmt::format(" twist={} w_n={}", twisting_friction, normal_spin)
                              : "",
        rolling_damping_ratio == 0.0 ? " eta=0" : "");
  }
};

PairTable table_for(const ImpactCase& c) {
  PairTable t({Material{"glass", glass_E, 0.245, glass_density}, Material{"wall", {}, {}, {}}});
  PairProperties p;
  p.restitution = c.restitution;
  p.friction = friction;
  p.rns = c.rns;
  p.rzs = c.rzs;
  p.arf = c.arf;
  p.twisting_friction = c.twisting_friction;
  p.rolling_damping_ratio = c.rolling_damping_ratio;
  t.set(0, 0, p);
  t.set(0, 1, p);
  return t;
}

// The initial state, shared by grainlab and the reference. Wall: the sphere touches the plane
// z = 0 from above. Pair: a at the origin, b touching it above; each carries half the relative
// velocity. The contact-point tangential velocity is psi mu v_n in every spin variant; back-spin
// and top-spin split it between the centre's velocity and the spin.
ref::State initial_state(const ImpactCase& c) {
  const double m = sphere_mass(radius), inertia = 0.4 * m * radius * radius;
  const double vt = c.psi * friction * normal_speed;
  // centre part and spin part (radius * w) of the contact-point velocity
  const double centre = c.spin == Spin::none ? vt : c.spin == Spin::back ? 0.5 * vt : 1.5 * vt;
  const double spin_part = vt - centre;
  ref::State s;
  s.a = {radius, m, inertia, 0, 0, 0, 0, 0, 0};
  s.b = {radius, m, inertia, 0, 0, 0, 0, 0, 0};
  if (c.wall) {
    // v_t (along t = -x) = v_ax - r w_a: a slides towards +x over the wall.
    s.a.z = radius;
    s.a.vz = -normal_speed;
    s.a.vx = centre;
    s.a.w = -spin_part / radius;
    s.a.w_normal = c.normal_spin;
  } else {
    // n = +z, t = +x: v_t = (v_bx - v_ax) - r (w_a + w_b)
    s.b.z = 2.0 * radius;
    s.a.vz = 0.5 * normal_speed, s.b.vz = -0.5 * normal_speed;
    s.a.vx = -0.5 * centre, s.b.vx = 0.5 * centre;
    s.a.w = s.b.w = -0.5 * spin_part / radius;
  }
  return s;
}

ref::Constants reference_constants(const ImpactCase& c, const PairTable& t) {
  const PairParams& p = t(0, 0);
  const double m = sphere_mass(radius), inertia = 0.4 * m * radius * radius;
  const double r_star = c.wall ? radius : 0.5 * radius, m_star = c.wall ? m : 0.5 * m;
  const double i_star = c.wall ? inertia : 0.5 * inertia;
  ref::Constants k{};
  k.k_n = std::numbers::pi * glass_E * r_star;  // Eq. 4
  k.c_n = 2.0 * p.damping_ratio * std::sqrt(k.k_n * m_star);
  k.k_s = c.rns * k.k_n;
  k.c_s = c.rzs * k.c_n;
  k.mu = friction;
  k.k_roll = 4.0 * r_star * r_star * k.k_s;  // Eq. 6
  k.c_roll = p.rolling_damping_ratio * 2.0 * std::sqrt(i_star * k.k_roll);
  k.arf = c.arf;
  k.twisting_friction = c.twisting_friction;
  return k;
}

double contact_time(const ImpactCase& c) {
  return collision_duration(radius, glass_density, glass_E, c.restitution);
}

ref::Outcome outcome_of(const ref::State& before, const ref::State& after, bool wall) {
  ref::Outcome o{};
  o.tangential_restitution = -ref::contact_point_tangential_velocity(after, wall) /
                             ref::contact_point_tangential_velocity(before, wall);
  o.spin_a = after.a.w;
  o.twist_ratio = before.a.w_normal != 0 ? after.a.w_normal / before.a.w_normal : 0.0;
  o.vx_a = after.a.vx, o.vz_a = after.a.vz;
  return o;
}

ref::Outcome reference_outcome(const ImpactCase& c, double steps_per_contact) {
  const PairTable t = table_for(c);
  const ref::Integrator integrator(reference_constants(c, t), c.wall);
  const ref::State s0 = initial_state(c);
  return outcome_of(s0, integrator.run(s0, contact_time(c) / steps_per_contact), c.wall);
}

// The same impact run by grainlab with dt = t_c / steps_per_contact. The bodies start apart, in
// free flight, so that they first touch a fraction `touch_phase` (0 <= phase < 1) into the first
// step: the error of a fixed-step scheme depends on where in a step the contact begins.
ref::Outcome grainlab_outcome(const ImpactCase& c, double steps_per_contact, double touch_phase) {
  const ref::State s0 = initial_state(c);
  const double dt = contact_time(c) / steps_per_contact, lead = touch_phase * dt;
  ParticleStore p;
  std::vector<Wall> walls;
  auto add = [&](uint32_t id, const ref::Body& b) {
    p.add(id, 0, b.radius, glass_density, {b.x - lead * b.vx, 0, b.z - lead * b.vz},
          {b.vx, 0, b.vz}, {0, b.w, b.w_normal}, false);
  };
  add(0, s0.a);
  if (c.wall)
    walls.push_back(plane_wall({0, 0, 0}, {0, 0, 1}));
  else
    add(1, s0.b);
  SimulationSettings settings = settings_for(radius, c.restitution, 1.0 / steps_per_contact);
  settings.time_step = dt;
  Simulation sim(std::move(p), walls, table_for(c), settings);
  auto state = [&] {
    ref::State s = s0;
    const ParticleStore& q = sim.particles();
    for (size_t i = 0; i < q.size(); ++i) {
      ref::Body& b = q.id[i] == 0 ? s.a : s.b;
      b.x = q.position[i].x, b.z = q.position[i].z;
      b.vx = q.velocity[i].x, b.vz = q.velocity[i].z;
      b.w = q.angular_velocity[i].y, b.w_normal = q.angular_velocity[i].z;
    }
    return s;
  };
  auto overlap = [&](const ref::State& s) {
    return c.wall ? radius - s.a.z : 2.0 * radius - std::hypot(s.b.x - s.a.x, s.b.z - s.a.z);
  };
  bool touched = false;
  for (long step = 0; step < 100 * static_cast<long>(steps_per_contact); ++step) {
    sim.step();
    const double now = overlap(state());
    touched = touched || now > 0.0;
    if (touched && now < 0.0) break;
  }
  return outcome_of(s0, state(), c.wall);
}

// Steps per contact N = 50 2^k up to 3200: six halvings of the step.
constexpr int resolutions = 7;
constexpr double reference_steps_per_contact = 80000;
double steps_per_contact(int k) {
  return 50.0 * (1 << k);
}

// Where in the first step the bodies first touch; the error figure is the largest over these.
constexpr double touch_phases[8] = {0.0, 0.125, 0.25, 0.375, 0.5, 0.625, 0.75, 0.875};

struct ErrorRow {
  std::string name;
  double error[resolutions];  // max over touch_phases of |figure - reference| at N(k)
  double order;               // observed order over the six halvings
};

// Where the error at 50 steps per contact is below this, the finer steps reach the level the
// comparison resolves (the reference's own error, ~1e-9 to 1e-7) and no order can be measured;
// such rows must stay below it at every step.
constexpr double measurable_error = 1e-4;

std::vector<ErrorRow> run_cases(const std::vector<ImpactCase>& cases,
                                double ref::Outcome::*figure) {
  std::vector<ErrorRow> rows;
  for (const ImpactCase& c : cases) {
    const ref::Outcome r = reference_outcome(c, reference_steps_per_contact);
    ErrorRow row{c.name(), {}, 0.0};
    for (int k = 0; k < resolutions; ++k)
      for (double phase : touch_phases) {
        const double e =
            std::abs(grainlab_outcome(c, steps_per_contact(k), phase).*figure - r.*figure);
        if (!(e <= row.error[k])) row.error[k] = e;  // a NaN figure is kept as the error
      }
    // Observed order: least-squares slope of -log2(error) against log2(N) over the six halvings.
    // Stick-slip transitions and the end of the contact fall at a different phase of the step at
    // each N, so the error of one run wanders around C/N^2 by a factor of a few and may pass
    // through zero; the worst case over the touch phases and the fit over six halvings keep that
    // noise out of the order.
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (int k = 0; k < resolutions; ++k) {
      const double y = -std::log2(row.error[k]);
      sx += k, sy += y, sxx += k * k, sxy += k * y;
    }
    row.order = (resolutions * sxy - sx * sy) / (resolutions * sxx - sx * sx);
    rows.push_back(row);
  }
  return rows;
}

void print(const std::vector<ErrorRow>& rows, const char* figure) {
  fmt::print("{:<62} {:>9} {:>9} {:>9} {:>9} {:>9} {:>6}\n", fmt::format("case ({} error)", figure),
             "N=50", "N=100", "N=200", "N=400", "N=3200", "order");
  for (const ErrorRow& r : rows)
    fmt::print("{:<62} {:>9.2e} {:>9.2e} {:>9.2e} {:>9.2e} {:>9.2e} {:>6.2f}\n", r.name, r.error[0],
               r.error[1], r.error[2], r.error[3], r.error[6],
               r.error[0] > measurable_error ? r.order : NAN);
}

// Within `tolerance` at 50 steps per contact, and an observed order of at least 1.8 when the
// step is halved (where the error is large enough to measure one); otherwise the error must stay
// at that level.
void check(const std::vector<ErrorRow>& rows, double tolerance) {
  for (const ErrorRow& r : rows) {
    SCOPED_TRACE(r.name);
    EXPECT_LT(r.error[0], tolerance);
    if (r.error[0] > measurable_error) {
      EXPECT_GE(r.order, 1.8) << "errors " << r.error[0] << " -> " << r.error[resolutions - 1];
    } else {
      for (double e : r.error) EXPECT_LT(e, measurable_error);
    }
  }
}

std::vector<ImpactCase> sliding_cases(bool wall) {
  std::vector<ImpactCase> cases;
  for (double e : {0.5, 1.0})
    for (double rns : {2.0 / 7.0, 1.0})
      for (Spin spin : {Spin::none, Spin::back, Spin::top})
        for (double psi : {0.5, 1.0, 2.0, 4.0, 10.0}) cases.push_back({wall, psi, spin, rns, e});
  return cases;
}

}  // namespace

TEST(ObliqueImpactReference, ConvergesWhenItsStepIsHalved) {
  // The reference must be far more accurate than the differences the tests resolve (~1e-5).
  for (const ImpactCase& c : {ImpactCase{true, 1.0, Spin::back, 2.0 / 7.0, 0.5},
                              ImpactCase{false, 2.0, Spin::top, 1.0, 0.5},
                              ImpactCase{true, 0.5, Spin::none, 1.0, 1.0, 0.0, 20.0}}) {
    SCOPED_TRACE(c.name());
    EXPECT_NEAR(reference_outcome(c, 20000).tangential_restitution,
                reference_outcome(c, 40000).tangential_restitution, 1e-7);
  }
}

TEST(ObliqueImpactReference, GrossSlidingMatchesTheClosedForm) {
  // A sphere without spin sliding throughout the contact (Psi large): the tangential impulse is
  // mu times the normal one, so v_x' = v_x - mu (1 + e) v_n and w' = -(5/2) mu (1 + e) v_n / r'
  // (Chung & Ooi test 5, analytical). The reference must reproduce it (the lever is r - U_n, which
  // shifts the spin by ~U_n/r; compare the translational part).
  // Only for e = 1: with a dashpot the normal force jumps at first touch while the tangential
  // spring starts empty, so the force is not on the cap for the first instant.
  for (double e : {1.0}) {
    const ImpactCase c{true, 10.0, Spin::none, 2.0 / 7.0, e};
    const ref::State s0 = initial_state(c);
    const ref::Integrator integrator(reference_constants(c, table_for(c)), true);
    const ref::State s1 = integrator.run(s0, contact_time(c) / 20000);
    EXPECT_NEAR(s1.a.vz / normal_speed, e, 1e-6 * e);
    EXPECT_NEAR(s1.a.vx, s0.a.vx - friction * (normal_speed + s1.a.vz), 1e-6 * s0.a.vx);
  }
}

TEST(ObliqueImpacts, SphereOnWallSecondOrder) {
  const auto rows = run_cases(sliding_cases(true), &ref::Outcome::tangential_restitution);
  print(rows, "e_t");
  check(rows, 0.005);
}

TEST(ObliqueImpacts, TwoSpheresSecondOrder) {
  const auto rows = run_cases(sliding_cases(false), &ref::Outcome::tangential_restitution);
  print(rows, "e_t");
  check(rows, 0.005);
}

TEST(ObliqueImpacts, TangentialDashpotSecondOrder) {
  // c_s = c_n (RZS = 1) while the spring sticks (Psi = 0.5) and in gross sliding (Psi = 10).
  // In partial slip (Psi = 2) a Kelvin-Voigt slider is not smooth enough for the order test: the
  // reference integration itself converges only at first order there (e_t = -0.032760,
  // -0.032939, -0.032984 at 5,000, 20,000, 80,000 RK4 steps per contact), so that case is
  // reported in docs/contact-model.md, not asserted here.
  std::vector<ImpactCase> cases;
  for (bool wall : {true, false})
    for (double psi : {0.5, 10.0})
      for (Spin spin : {Spin::none, Spin::back})
        cases.push_back({wall, psi, spin, 2.0 / 7.0, 0.5, /*rzs=*/1.0});
  const auto rows = run_cases(cases, &ref::Outcome::tangential_restitution);
  print(rows, "e_t");
  check(rows, 0.005);
}

TEST(ObliqueImpacts, RollingResistanceSecondOrder) {
  // ARF large enough that the rolling moment matters during one impact (a ~ 1.6e-5 m at the
  // largest overlap): the rolling spring sticks, then slips on its cap. Figure: rebound spin,
  // relative to the spin scale v_n / r. With a relative spin at first touch, the rolling dashpot
  // meets a cap of zero (mu_theta = ARF a, a = 0 at touch) and the continuous solution is not
  // smooth enough for an order (the reference converges as slowly as grainlab); those cases run
  // without the rolling dashpot (eta_theta = 0), the spin-free ones with grainlab's default.
  std::vector<ImpactCase> cases;
  for (bool wall : {true, false})
    for (Spin spin : {Spin::none, Spin::back, Spin::top})
      for (double psi : {0.5, 2.0})
        for (double arf : {5.0, 50.0}) {
          ImpactCase c{wall, psi, spin, 2.0 / 7.0, 0.5, 0.0, arf};
          if (spin != Spin::none) c.rolling_damping_ratio = 0.0;
          cases.push_back(c);
        }
  auto rows = run_cases(cases, &ref::Outcome::spin_a);
  for (ErrorRow& r : rows)
    for (double& e : r.error) e *= radius / normal_speed;
  print(rows, "w r/v_n");
  check(rows, 0.005);
}

TEST(ObliqueImpacts, TwistingSecondOrder) {
  // A sphere spinning about the wall normal (20 and 200 rad/s) hits the wall obliquely; the
  // twisting spring sticks and slips on mu_t a F_n. Figure: the rebound spin about the normal.
  // The spin is present at first touch, so the twisting dashpot is off (see the rolling case).
  std::vector<ImpactCase> cases;
  for (double spin : {20.0, 200.0})
    for (double mu_t : {5.0, 50.0}) {
      ImpactCase c{true, 1.0, Spin::none, 2.0 / 7.0, 0.5, 0.0, 0.0, mu_t, spin};
      c.rolling_damping_ratio = 0.0;
      cases.push_back(c);
    }
  auto rows = run_cases(cases, &ref::Outcome::twist_ratio);
  // as for rolling: the error of the spin about the normal, relative to the spin scale v_n / r
  for (size_t i = 0; i < rows.size(); ++i)
    for (double& e : rows[i].error) e *= cases[i].normal_spin * radius / normal_speed;
  print(rows, "w_n r/v_n");
  check(rows, 0.005);
}
