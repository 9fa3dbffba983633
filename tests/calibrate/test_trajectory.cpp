// Tracked-throw restitution: exact parabolas, impact detection, errors, CI coverage.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "calibrate/input_error.hpp"
#include "calibrate/trajectory.hpp"

using namespace grainlab::calibrate;

namespace {

struct Throw {
  double H = 0.3;  // centre apex height above the plate at launch (m)
  double radius = 0.001;
  double e = 0.58;
  double g = 9.81;
  double fps = 500.0;
  double noise = 0.0;  // sd of z and x (m)
  double t_start = 0.01;
  double after_factor = 1.6;  // track length after impact, in rebound rise times
  bool second_bounce = false;
};

// The analytic trajectory of a bead launched horizontally at its apex, hitting at z = radius.
std::vector<TrackPoint> make_track(const Throw& s, std::uint64_t seed = 0) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> n(0.0, 1.0);
  const double t_fall = std::sqrt(2.0 * (s.H - s.radius) / s.g);
  const double v_out = s.e * s.g * t_fall;
  const double rise = v_out / s.g;
  const double t_end = t_fall + (s.second_bounce ? 2.0 * rise + 0.03 : s.after_factor * rise);
  std::vector<TrackPoint> p;
  for (double t = s.t_start; t < t_end; t += 1.0 / s.fps) {
    double z;
    if (t < t_fall) {
      z = s.H - 0.5 * s.g * t * t;
    } else if (t < t_fall + 2.0 * rise) {
      const double u = t - t_fall;
      z = s.radius + v_out * u - 0.5 * s.g * u * u;
    } else {
      const double u = t - t_fall - 2.0 * rise;
      z = s.radius + s.e * v_out * u - 0.5 * s.g * u * u;
    }
    p.push_back({p.size() + 2, t, 0.5 * t + s.noise * n(rng), z + s.noise * n(rng)});
  }
  return p;
}

}  // namespace

TEST(Trajectory, ExactTrackRecoversImpactAndRestitution) {
  const Throw s;
  for (bool fixed_g : {false, true}) {
    TrajectoryOptions o;
    if (fixed_g) o.gravity = s.g;
    const auto r = analyse_trajectory(make_track(s), "track.csv", o);
    const double t_fall = std::sqrt(2.0 * (s.H - s.radius) / s.g);
    EXPECT_NEAR(r.e_velocity.value, s.e, 1e-9);
    EXPECT_NEAR(r.gravity.value, s.g, 1e-8);
    EXPECT_NEAR(r.impact_time_s.value, t_fall, 1e-10);
    EXPECT_NEAR(r.impact_height_m.value, s.radius, 1e-9);
    EXPECT_NEAR(r.launch_height_m.value, s.H, 1e-9);
    // The rebound apex of the centre is radius + e^2 (H - radius) above the plate.
    const double h = s.radius + s.e * s.e * (s.H - s.radius);
    EXPECT_NEAR(r.rebound_height_m.value, h, 1e-9);
    EXPECT_NEAR(r.e_heights.value, std::sqrt(h / s.H), 1e-9);
    EXPECT_NEAR(r.velocity_before.value, -s.g * t_fall, 1e-8);
    EXPECT_NEAR(r.horizontal_velocity_before, 0.5, 1e-9);
    EXPECT_LT(r.max_abs_residual_m, 1e-10);
    EXPECT_EQ(r.gravity_fitted, !fixed_g);
    EXPECT_TRUE(r.warnings.empty());
  }
}

TEST(Trajectory, PlateHeightShiftsHeightsNotRestitution) {
  Throw s;
  auto track = make_track(s);
  for (auto& q : track) q.z_m += 0.25;  // camera origin 0.25 m below the plate
  TrajectoryOptions o;
  o.plate_z_m = 0.25;
  const auto r = analyse_trajectory(track, "track.csv", o);
  EXPECT_NEAR(r.launch_height_m.value, s.H, 1e-9);
  EXPECT_NEAR(r.e_velocity.value, s.e, 1e-9);
  // Forgetting --plate-z: e from heights is wrong, e from velocities is not, and it says so.
  const auto wrong = analyse_trajectory(track, "track.csv", {});
  EXPECT_NEAR(wrong.e_velocity.value, s.e, 1e-9);
  EXPECT_FALSE(wrong.warnings.empty());
}

TEST(Trajectory, SecondBounceIsCutOff) {
  Throw s;
  s.second_bounce = true;
  const auto r = analyse_trajectory(make_track(s), "track.csv", {});
  EXPECT_NEAR(r.e_velocity.value, s.e, 1e-9);
  ASSERT_FALSE(r.warnings.empty());
  EXPECT_NE(r.warnings[0].find("second impact"), std::string::npos);
}

TEST(Trajectory, NoisyTracksCoverTheTruthAtTheStatedRate) {
  // 200 tracks with 0.3 mm camera noise: the 95 % CI of e (velocities) must cover 0.58 in
  // >= 90 % of them, and the fitted g must cover 9.81 as often.
  Throw s;
  s.noise = 0.0003;
  int covered_e = 0, covered_g = 0;
  for (int seed = 0; seed < 200; ++seed) {
    s.t_start = 0.01 + 0.0019 * (seed % 7) / 7.0;  // frames at different phases
    const auto r = analyse_trajectory(make_track(s, seed), "track.csv", {});
    covered_e += r.e_velocity.ci.contains(s.e);
    covered_g += r.gravity.ci.contains(s.g);
  }
  EXPECT_GE(covered_e, 180) << covered_e;
  EXPECT_GE(covered_g, 180) << covered_g;
  EXPECT_LE(covered_e, 199);
}

TEST(Trajectory, NoImpactIsAnError) {
  Throw s;
  auto track = make_track(s);
  track.resize(80);  // only the fall: the lowest point is the last one
  try {
    analyse_trajectory(track, "track.csv", {});
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("track.csv: no impact found"), std::string::npos)
        << e.what();
  }
}

TEST(Trajectory, TooFewPointsAfterImpactIsAnError) {
  auto track = make_track(Throw{});
  std::size_t lowest = 0;
  for (std::size_t i = 0; i < track.size(); ++i)
    if (track[i].z_m < track[lowest].z_m) lowest = i;
  track.resize(lowest + 2);  // the track stops one frame after the lowest point
  try {
    analyse_trajectory(track, "track.csv", {});
    FAIL() << "no error";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("too few points"), std::string::npos) << msg;
    EXPECT_NE(msg.find("track.csv line"), std::string::npos) << msg;
  }
}

TEST(Trajectory, ReadTrackNeedsIncreasingTime) {
  const auto t = CsvTable::parse("t_s,x_m,z_m\n0.0,0,1\n0.1,0,0.9\n0.1,0,0.8\n", "tr.csv");
  try {
    read_track(t);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("tr.csv line 4"), std::string::npos) << e.what();
  }
  EXPECT_THROW(read_track(CsvTable::parse("t_s,z_m\n0,1\n", "tr.csv")), InputError);
}
