// `grainlab calibrate` as a user runs it: exit codes, messages naming file and line, outputs.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <toml++/toml.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

namespace fs = std::filesystem;

namespace {

const std::string exe = GRAINLAB_EXE;
const std::string examples = GRAINLAB_EXAMPLES_DIR;

struct Result {
  int code = -1;
  std::string out, err;
};

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

class Cli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("grainlab_cli_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Writes `content` to `name` in the test's directory and returns the path.
  std::string file(const std::string& name, const std::string& content) {
    std::ofstream(dir_ / name) << content;
    return (dir_ / name).string();
  }

  // Runs grainlab in the test's directory (so file names in messages are short).
  Result run(const std::string& args) {
    const std::string cmd = "cd '" + dir_.string() + "' && GRAINLAB_SCRIPTS_DIR='" +
                            GRAINLAB_SCRIPTS_DIR + "' '" + exe + "' " + args +
                            " >out.txt 2>err.txt";
    const int status = std::system(cmd.c_str());
    Result r;
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = slurp(dir_ / "out.txt");
    r.err = slurp(dir_ / "err.txt");
    return r;
  }

  fs::path dir_;
};

}  // namespace

TEST_F(Cli, RestitutionExampleTable) {
  const Result r = run("calibrate restitution " + examples + "/throws.csv");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("rubber_membrane"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("95 % CI"), std::string::npos) << r.out;
}

TEST_F(Cli, RestitutionJsonHasThePublishedValuesInItsIntervals) {
  const Result r = run("calibrate restitution --json " + examples + "/throws.csv");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto doc = nlohmann::json::parse(r.out);
  EXPECT_EQ(doc["analysis"], "restitution");
  for (const auto& m : doc["materials"]) {
    const double truth = m["material"] == "glass"             ? 0.926
                         : m["material"] == "rubber_membrane" ? 0.58
                                                              : 0.73;
    EXPECT_LE(m["ci"]["low"].get<double>(), truth);
    EXPECT_GE(m["ci"]["high"].get<double>(), truth);
    EXPECT_EQ(m["throws"].size(), 20u);
  }
}

TEST_F(Cli, BothAnalysesMergeIntoOneMaterialsFile) {
  Result r = run("calibrate restitution " + examples +
                 "/throws.csv --materials-out m.toml --rename porous_stone=filter_paper");
  ASSERT_EQ(r.code, 0) << r.err;
  r = run("calibrate friction " + examples + "/slide.csv --materials-out m.toml");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto root = toml::parse_file((dir_ / "m.toml").string());
  int checked = 0;
  for (const auto& node : *root["pair"].as_array()) {
    const auto& t = *node.as_table();
    const auto b = t["materials"][1].value<std::string>().value();
    EXPECT_EQ(t["materials"][0].value<std::string>().value(), "glass");
    if (b == "rubber_membrane") {
      EXPECT_NEAR(t["restitution"].value<double>().value(), 0.58, 0.011);
      EXPECT_NEAR(t["friction"].value<double>().value(), 0.2116, 0.003);
      ++checked;
    }
    if (b == "filter_paper") {
      EXPECT_NEAR(t["restitution"].value<double>().value(), 0.73, 0.012);
      EXPECT_NEAR(t["friction"].value<double>().value(), 0.1791, 0.003);
      ++checked;
    }
  }
  EXPECT_EQ(checked, 2);
  EXPECT_NE(slurp(dir_ / "m.toml").find("# friction: quasi-static"), std::string::npos);
}

TEST_F(Cli, FrictionJsonAndAtSpeed) {
  Result r = run("calibrate friction --json " + examples + "/slide.csv");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto doc = nlohmann::json::parse(r.out);
  EXPECT_EQ(doc["materials"][0]["speed_fit"]["breakpoint_mm_per_min"], 5.0);
  r = run("calibrate friction " + examples + "/slide.csv --at-speed 25 --materials-out m.toml");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(slurp(dir_ / "m.toml").find("at 25 mm/min"), std::string::npos);
  r = run("calibrate friction " + examples + "/slide.csv --at-speed 7 --materials-out n.toml");
  EXPECT_EQ(r.code, 2);
  EXPECT_FALSE(fs::exists(dir_ / "n.toml"));
}

TEST_F(Cli, TrajectoryExample) {
  const Result r = run("calibrate restitution --trajectory " + examples +
                       "/track_rubber_membrane.csv --material rubber_membrane "
                       "--materials-out m.toml");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("e = -v_after/v_before"), std::string::npos) << r.out;
  EXPECT_TRUE(fs::exists(dir_ / "m.toml"));
  // Needs a material name for the materials file, and exactly one input.
  EXPECT_EQ(run("calibrate restitution --trajectory " + examples +
                "/track_rubber_membrane.csv --materials-out x.toml")
                .code,
            2);
  EXPECT_EQ(run("calibrate restitution").code, 2);
}

TEST_F(Cli, ReboundAboveDrop) {
  file("throws.csv",
       "material,H_m,h_m\nglass,0.5,0.4\nglass,0.5,0.41\n# c\n\nglass,0.5,0.42\n"
       "glass,0.5,0.9\n");
  const Result r = run("calibrate restitution throws.csv --materials-out m.toml --plot p.png");
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err,
            "grainlab: error: throws.csv line 7: h_m = 0.9 is larger than H_m = 0.5 (a rebound "
            "cannot exceed the drop)\n");
  EXPECT_TRUE(r.out.empty());
  EXPECT_FALSE(fs::exists(dir_ / "m.toml")) << "no output on bad input";
  EXPECT_FALSE(fs::exists(dir_ / "p.png"));
}

TEST_F(Cli, MissingColumn) {
  file("t.csv", "material,H_m,rebound\nglass,0.5,0.4\n");
  const Result r = run("calibrate restitution t.csv");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("t.csv line 1: missing column 'h_m'"), std::string::npos) << r.err;
}

TEST_F(Cli, NonNumericCell) {
  file("s.csv",
       "material,speed_mm_per_min,normal_load_N,friction_force_N\nrm,25,0.5,0.12\nrm,25,1,n/a\n");
  const Result r = run("calibrate friction s.csv");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("s.csv line 3: column 'friction_force_N': 'n/a' is not a finite number"),
            std::string::npos)
      << r.err;
}

TEST_F(Cli, EmptyFile) {
  file("empty.csv", "");
  Result r = run("calibrate friction empty.csv");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("empty.csv: the file is empty"), std::string::npos) << r.err;
  r = run("calibrate restitution --trajectory empty.csv");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("empty.csv"), std::string::npos) << r.err;
}

TEST_F(Cli, FewerThanTwoLoads) {
  file("s.csv",
       "material,speed_mm_per_min,normal_load_N,friction_force_N\nrm,25,0.5,0.12\nrm,25,1,0.24\n"
       "rm,5,0.75,0.16\n");
  const Result r = run("calibrate friction s.csv --materials-out m.toml");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("s.csv line 4: rm at 5 mm/min has only one normal load"), std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "m.toml"));
}

TEST_F(Cli, MissingFileAndBadOptions) {
  Result r = run("calibrate friction nowhere.csv");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("nowhere.csv: cannot open the file"), std::string::npos) << r.err;
  EXPECT_EQ(run("calibrate friction " + examples + "/slide.csv --rename oops").code, 2);
  EXPECT_EQ(run("calibrate friction " + examples + "/slide.csv --level 2").code, 2);
  EXPECT_EQ(run("calibrate").code, 2);
}

TEST_F(Cli, MaterialsOutRefusesASceneFile) {
  file("scene.toml", "[simulation]\nduration = 1.0\n");
  const Result r =
      run("calibrate restitution " + examples + "/throws.csv --materials-out scene.toml");
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(slurp(dir_ / "scene.toml"), "[simulation]\nduration = 1.0\n");
}

TEST_F(Cli, Plots) {
  if (!fs::exists("/usr/bin/python3")) GTEST_SKIP() << "no /usr/bin/python3";
  for (const std::string& args :
       {"restitution " + examples + "/throws.csv --plot r.png",
        "friction " + examples + "/slide.csv --plot f.png",
        "restitution --trajectory " + examples + "/track_rubber_membrane.csv --plot t.png"}) {
    const Result r = run("calibrate " + args);
    EXPECT_EQ(r.code, 0) << args << "\n" << r.err;
  }
  for (const char* png : {"r.png", "f.png", "t.png"}) {
    ASSERT_TRUE(fs::exists(dir_ / png)) << png;
    EXPECT_EQ(slurp(dir_ / png).substr(1, 3), "PNG");
  }
}

TEST_F(Cli, PublishedSpeedsOnlyGiveNoQuasiStaticValue) {
  // 2.5, 5, 12.5, 25 mm/min (the reference study's speeds) cannot fix a quadratic below
  // 5 mm/min: per-speed results, a warning, exit 0, and no materials file with nothing in it.
  std::string csv = "material,speed_mm_per_min,normal_load_N,friction_force_N\n";
  for (const char* v : {"2.5", "5", "12.5", "25"})
    for (const char* row : {",0.5,0.105\n", ",1.0,0.211\n"}) csv += std::string("rm,") + v + row;
  file("s.csv", csv);
  const Result r = run("calibrate friction s.csv --materials-out m.toml");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("no speed fit"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "m.toml"));
  EXPECT_EQ(run("calibrate friction s.csv --at-speed 25 --materials-out m.toml").code, 0);
  EXPECT_TRUE(fs::exists(dir_ / "m.toml"));
}
