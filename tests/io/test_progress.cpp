// Progress lines of long runs (io/progress.hpp): a known fraction gives a percentage and an ETA;
// a run that stops on a criterion (unknown fraction) must not show either, since an ETA taken
// from its time limit is wrong by orders of magnitude.
#include <gtest/gtest.h>

#include <thread>

#include "io/progress.hpp"

using namespace grainlab;

namespace {
std::string lines_of(void (*run)(Progress&)) {
  testing::internal::CaptureStderr();
  {
    Progress p("prep", false, 0.0);  // a line at every update (stderr is not a terminal here)
    run(p);
  }
  return testing::internal::GetCapturedStderr();
}
}  // namespace

TEST(Progress, UnknownFractionShowsNeitherPercentNorEta) {
  const std::string out = lines_of([](Progress& p) {
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
    p.update(Progress::unknown_fraction, "holding: unbalanced 1e-2");
  });
  EXPECT_NE(out.find("holding: unbalanced 1e-2"), std::string::npos) << out;
  EXPECT_NE(out.find("elapsed"), std::string::npos) << out;
  EXPECT_EQ(out.find("ETA"), std::string::npos) << out;
  EXPECT_EQ(out.find('%'), std::string::npos) << out;
}

TEST(Progress, KnownFractionAfterUnknownStartsTheEtaThere) {
  // The ETA comes from the rate since the first known fraction: time spent in an unknown stage
  // before it (a re-equilibration) must not count. 1.5 s unknown, then half done in ~0.1 s:
  // ETA ~0.1 s ("ETA 0 s"); counting the unknown stage would give ~1.6 s ("ETA 2 s").
  const std::string out = lines_of([](Progress& p) {
    p.update(Progress::unknown_fraction, "re-equilibrating");
    std::this_thread::sleep_for(std::chrono::milliseconds(1500));
    p.update(0.0, "loading");
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    p.update(0.5, "loading");
  });
  EXPECT_NE(out.find(" 50.0 %"), std::string::npos) << out;
  EXPECT_NE(out.find("ETA 0 s"), std::string::npos) << out;
}
