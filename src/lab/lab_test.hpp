// Virtual laboratory tests. A config with a `[test]` table is run by the test named in
// `test.type`; each test is one small file in src/lab/ plus one row in the registry
// (registry.cpp). A test reads the sections of the config it needs (io/scene_config.hpp), builds
// its specimen, walls and controllers, runs the core, measures like the laboratory does and
// writes its results (always summary.json) into the output directory.
#pragma once

#include <toml++/toml.h>

#include <string>
#include <vector>

#include "io/scene_run.hpp"

namespace grainlab {

using LabTestRunner = void (*)(const std::string& config_path, const toml::table& root,
                               const RunOptions& options);

struct LabTestEntry {
  const char* type;         // value of test.type
  const char* description;  // one line for --help and errors
  LabTestRunner run;
};

const std::vector<LabTestEntry>& lab_tests();

// Runs the test named by root["test"]["type"]; ConfigError when it is missing or unknown.
void run_lab_test(const std::string& config_path, const toml::table& root,
                  const RunOptions& options);

}  // namespace grainlab
