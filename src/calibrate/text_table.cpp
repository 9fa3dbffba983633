#include "calibrate/text_table.hpp"

#include <algorithm>
#include <stdexcept>

namespace grainlab::calibrate {
namespace {

// Display width of UTF-8 text: count the bytes that start a code point.
std::size_t display_width(const std::string& s) {
  return static_cast<std::size_t>(
      std::count_if(s.begin(), s.end(), [](char c) { return (c & 0xC0) != 0x80; }));
}

}  // namespace

TextTable::TextTable(std::vector<std::string> headers, std::vector<Align> align)
    : headers_(std::move(headers)), align_(std::move(align)) {
  if (align_.empty()) {
    align_.assign(headers_.size(), Align::right);
    if (!align_.empty()) align_.front() = Align::left;
  }
  if (align_.size() != headers_.size()) throw std::invalid_argument("TextTable: bad alignment");
}

void TextTable::add_row(std::vector<std::string> cells) {
  if (cells.size() != headers_.size()) throw std::invalid_argument("TextTable: bad row");
  rows_.push_back(std::move(cells));
}

std::string TextTable::str(int indent) const {
  std::vector<std::size_t> width(headers_.size());
  for (std::size_t c = 0; c < headers_.size(); ++c) {
    width[c] = display_width(headers_[c]);
    for (const auto& r : rows_) width[c] = std::max(width[c], display_width(r[c]));
  }
  auto line = [&](const std::vector<std::string>& cells) {
    std::string out(static_cast<std::size_t>(indent), ' ');
    for (std::size_t c = 0; c < cells.size(); ++c) {
      const std::string pad(width[c] - display_width(cells[c]), ' ');
      const bool last = c + 1 == cells.size();
      if (align_[c] == Align::left)
        out += cells[c] + (last ? "" : pad);
      else
        out += pad + cells[c];
      if (!last) out += "   ";
    }
    while (!out.empty() && out.back() == ' ') out.pop_back();
    return out + "\n";
  };
  std::string out = line(headers_);
  std::size_t total = 0;
  for (std::size_t c = 0; c < width.size(); ++c) total += width[c] + (c ? 3 : 0);
  out += std::string(static_cast<std::size_t>(indent), ' ') + std::string(total, '-') + "\n";
  for (const auto& r : rows_) out += line(r);
  return out;
}

}  // namespace grainlab::calibrate
