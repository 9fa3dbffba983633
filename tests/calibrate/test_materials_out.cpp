// The [[pair]] TOML writer: content, read-back, merging, refusal, atomic replacement.
#include <gtest/gtest.h>
#include <toml++/toml.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "calibrate/input_error.hpp"
#include "calibrate/materials_out.hpp"

using namespace grainlab::calibrate;

namespace {

const toml::table* find_pair(const toml::table& root, const std::string& a, const std::string& b) {
  for (const auto& node : *root["pair"].as_array()) {
    const auto& t = *node.as_table();
    const auto& m = *t["materials"].as_array();
    if (m[0].value<std::string>() == a && m[1].value<std::string>() == b) return &t;
  }
  return nullptr;
}

}  // namespace

TEST(MaterialsOut, NewFileHasPairsWithValuesAndProvenance) {
  const std::string text = merge_materials_toml(
      "", "m.toml",
      {{"glass", "rubber_membrane", {{"restitution", 0.58012, "mean of 20 throws in t.csv"}}},
       {"glass", "glass", {{"restitution", 0.926, "x"}}}});
  const auto root = toml::parse(text);
  const auto* p = find_pair(root, "glass", "rubber_membrane");
  ASSERT_NE(p, nullptr);
  EXPECT_DOUBLE_EQ((*p)["restitution"].value<double>().value(), 0.5801);
  EXPECT_FALSE(p->contains("friction"));
  EXPECT_NE(text.find("# restitution: mean of 20 throws in t.csv\nrestitution = 0.5801"),
            std::string::npos)
      << text;
  EXPECT_NE(find_pair(root, "glass", "glass"), nullptr);
}

TEST(MaterialsOut, MergeUpdatesKnownKeysAndKeepsTheRest) {
  const std::string first = merge_materials_toml(
      "", "m.toml", {{"glass", "rubber_membrane", {{"restitution", 0.58, "from throws"}}}});
  // A user's own key survives, the pair is found with its materials in either order.
  std::string edited = first + "rns = 0.4\n";
  const std::string merged =
      merge_materials_toml(edited, "m.toml",
                           {{"rubber_membrane", "glass", {{"friction", 0.2116, "from slide"}}},
                            {"glass", "filter_paper", {{"friction", 0.1791, "from slide too"}}}});
  const auto root = toml::parse(merged);
  EXPECT_EQ(root["pair"].as_array()->size(), 2u);
  const auto* p = find_pair(root, "glass", "rubber_membrane");
  ASSERT_NE(p, nullptr);
  EXPECT_DOUBLE_EQ((*p)["restitution"].value<double>().value(), 0.58);
  EXPECT_DOUBLE_EQ((*p)["friction"].value<double>().value(), 0.2116);
  EXPECT_DOUBLE_EQ((*p)["rns"].value<double>().value(), 0.4);
  EXPECT_NE(merged.find("# restitution: from throws"), std::string::npos) << merged;
  EXPECT_NE(merged.find("# friction: from slide\n"), std::string::npos) << merged;
  // Kept values are written back as short as they read (not 0.57999999999999996).
  EXPECT_NE(merged.find("materials = [\"glass\", \"rubber_membrane\"]\n# restitution: from "
                        "throws\nrestitution = 0.58\n"),
            std::string::npos)
      << merged;
  // Re-running replaces the value and its comment, nothing is duplicated.
  const std::string again = merge_materials_toml(
      merged, "m.toml", {{"glass", "rubber_membrane", {{"restitution", 0.6, "new"}}}});
  EXPECT_EQ(again.find("from throws"), std::string::npos);
  EXPECT_DOUBLE_EQ((*find_pair(toml::parse(again), "glass", "rubber_membrane"))["restitution"]
                       .value<double>()
                       .value(),
                   0.6);
}

TEST(MaterialsOut, RefusesFilesWithOtherContent) {
  EXPECT_THROW(merge_materials_toml("[simulation]\ndt = 1\n", "scene.toml", {}), InputError);
  EXPECT_THROW(merge_materials_toml("pair = 3\n", "m.toml", {}), InputError);
  EXPECT_THROW(merge_materials_toml("[[pair]]\nrestitution = 0.5\n", "m.toml", {}), InputError);
  try {
    merge_materials_toml("[[pair]\n", "bad.toml", {});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.toml line 1"), std::string::npos) << e.what();
  }
}

TEST(MaterialsOut, WritesAtomicallyAndMerges) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / "grainlab_test_materials_out";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string path = (dir / "m.toml").string();
  write_materials_toml(path, {{"glass", "porous_stone", {{"restitution", 0.73, "a"}}}});
  write_materials_toml(path, {{"glass", "porous_stone", {{"friction", 0.18, "b"}}}});
  const auto root = toml::parse_file(path);
  const auto* p = find_pair(root, "glass", "porous_stone");
  ASSERT_NE(p, nullptr);
  EXPECT_DOUBLE_EQ((*p)["restitution"].value<double>().value(), 0.73);
  EXPECT_DOUBLE_EQ((*p)["friction"].value<double>().value(), 0.18);
  std::size_t files = 0;
  for (const auto& entry : fs::directory_iterator(dir)) files += entry.is_regular_file();
  EXPECT_EQ(files, 1u) << "a temporary file was left behind";
  EXPECT_THROW(write_file_atomically((dir / "no_such_dir" / "x.toml").string(), "x"),
               std::runtime_error);
  fs::remove_all(dir);
}
