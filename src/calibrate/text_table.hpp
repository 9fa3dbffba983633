// A small aligned text table: columns sized to their widest cell, numbers right-aligned.
#pragma once

#include <string>
#include <vector>

namespace grainlab::calibrate {

class TextTable {
 public:
  enum class Align { left, right };
  // One header per column; `align` defaults to left for the first column, right for the rest.
  explicit TextTable(std::vector<std::string> headers, std::vector<Align> align = {});
  void add_row(std::vector<std::string> cells);
  // Rows with a rule under the header, each line indented by `indent` spaces.
  std::string str(int indent = 2) const;

 private:
  std::vector<std::string> headers_;
  std::vector<Align> align_;
  std::vector<std::vector<std::string>> rows_;
};

}  // namespace grainlab::calibrate
