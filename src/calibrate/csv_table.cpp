#include "calibrate/csv_table.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "calibrate/input_error.hpp"

namespace grainlab::calibrate {
namespace {

std::string_view trim(std::string_view s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return {};
  const auto last = s.find_last_not_of(" \t\r");
  return s.substr(first, last - first + 1);
}

// Splits one line into fields (RFC 4180 quoting, no embedded newlines).
std::vector<std::string> split_fields(std::string_view line, const std::string& file,
                                      std::size_t line_no) {
  std::vector<std::string> fields;
  std::size_t i = 0;
  while (true) {
    std::string field;
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    if (i < line.size() && line[i] == '"') {
      ++i;
      bool closed = false;
      while (i < line.size()) {
        if (line[i] == '"') {
          if (i + 1 < line.size() && line[i + 1] == '"') {
            field += '"';
            i += 2;
            continue;
          }
          closed = true;
          ++i;
          break;
        }
        field += line[i++];
      }
      if (!closed) throw InputError(fmt::format("{} line {}: unterminated quote", file, line_no));
      while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
      if (i < line.size() && line[i] != ',')
        throw InputError(fmt::format("{} line {}: text after a closing quote", file, line_no));
    } else {
      const auto comma = line.find(',', i);
      const auto end = comma == std::string_view::npos ? line.size() : comma;
      field = std::string(trim(line.substr(i, end - i)));
      i = end;
    }
    fields.push_back(std::move(field));
    if (i >= line.size()) break;
    ++i;  // skip the comma; a trailing comma gives a final empty field
    if (i == line.size()) {
      fields.emplace_back();
      break;
    }
  }
  return fields;
}

bool is_blank_or_comment(std::string_view line) {
  const auto t = trim(line);
  return t.empty() || t.front() == '#';
}

}  // namespace

CsvTable CsvTable::parse(std::string_view text, std::string file_name) {
  CsvTable table;
  table.file_name_ = std::move(file_name);
  if (text.size() >= 3 && text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);  // BOM
  std::size_t line_no = 0;
  std::size_t pos = 0;
  while (pos < text.size()) {
    auto eol = text.find('\n', pos);
    if (eol == std::string_view::npos) eol = text.size();
    const std::string_view line = text.substr(pos, eol - pos);
    pos = eol + 1;
    ++line_no;
    if (is_blank_or_comment(line)) continue;
    auto fields = split_fields(line, table.file_name_, line_no);
    if (table.header_.empty()) {
      for (std::size_t c = 0; c < fields.size(); ++c) {
        if (fields[c].empty())
          throw InputError(fmt::format("{} line {}: header column {} has no name", table.file_name_,
                                       line_no, c + 1));
        for (std::size_t d = 0; d < c; ++d)
          if (fields[d] == fields[c])
            throw InputError(fmt::format("{} line {}: column '{}' appears twice in the header",
                                         table.file_name_, line_no, fields[c]));
      }
      table.header_ = std::move(fields);
      table.header_line_ = line_no;
      continue;
    }
    if (fields.size() != table.header_.size())
      throw InputError(fmt::format("{} line {}: {} fields, but the header (line {}) has {} columns",
                                   table.file_name_, line_no, fields.size(), table.header_line_,
                                   table.header_.size()));
    table.records_.push_back({line_no, std::move(fields)});
  }
  if (table.header_.empty())
    throw InputError(fmt::format("{}: the file is empty (expected a header line of column names)",
                                 table.file_name_));
  if (table.records_.empty())
    throw InputError(fmt::format("{} line {}: a header but no data lines", table.file_name_,
                                 table.header_line_));
  return table;
}

CsvTable CsvTable::read(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(fmt::format("{}: cannot open the file", path));
  std::ostringstream buffer;
  buffer << in.rdbuf();
  return parse(buffer.str(), path);
}

std::optional<std::size_t> CsvTable::find_column(std::string_view name) const {
  for (std::size_t c = 0; c < header_.size(); ++c)
    if (header_[c] == name) return c;
  return std::nullopt;
}

std::size_t CsvTable::column(std::string_view name) const {
  if (auto c = find_column(name)) return *c;
  throw InputError(fmt::format("{} line {}: missing column '{}' (the header has: {})", file_name_,
                               header_line_, name, fmt::join(header_, ", ")));
}

double CsvTable::number(const CsvRecord& record, std::size_t column) const {
  const std::string& cell = record.fields.at(column);
  if (cell.empty())
    throw InputError(fmt::format("{}: column '{}' is empty (expected a number)", where(record),
                                 header_[column]));
  errno = 0;
  char* end = nullptr;
  const double value = std::strtod(cell.c_str(), &end);
  if (end != cell.c_str() + cell.size() || errno == ERANGE || !std::isfinite(value))
    throw InputError(fmt::format("{}: column '{}': '{}' is not a finite number", where(record),
                                 header_[column], cell));
  return value;
}

bool valid_utf8(std::string_view s) {
  for (size_t i = 0; i < s.size();) {
    const auto c = static_cast<unsigned char>(s[i]);
    // Length of the sequence and the smallest code point it may encode (no overlong forms).
    size_t n;
    uint32_t cp, min;
    if (c < 0x80) {
      ++i;
      continue;
    } else if ((c & 0xE0) == 0xC0) {
      n = 2, cp = c & 0x1F, min = 0x80;
    } else if ((c & 0xF0) == 0xE0) {
      n = 3, cp = c & 0x0F, min = 0x800;
    } else if ((c & 0xF8) == 0xF0) {
      n = 4, cp = c & 0x07, min = 0x10000;
    } else {
      return false;
    }
    if (i + n > s.size()) return false;
    for (size_t k = 1; k < n; ++k) {
      const auto b = static_cast<unsigned char>(s[i + k]);
      if ((b & 0xC0) != 0x80) return false;
      cp = (cp << 6) | (b & 0x3F);
    }
    if (cp < min || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return false;
    i += n;
  }
  return true;
}

const std::string& CsvTable::text(const CsvRecord& record, std::size_t column) const {
  const std::string& cell = record.fields.at(column);
  if (cell.empty())
    throw InputError(fmt::format("{}: column '{}' is empty", where(record), header_[column]));
  if (!valid_utf8(cell))
    throw InputError(
        fmt::format("{}: column '{}' is not valid UTF-8 text", where(record), header_[column]));
  return cell;
}

std::string CsvTable::where(const CsvRecord& record) const {
  return fmt::format("{} line {}", file_name_, record.line);
}

}  // namespace grainlab::calibrate
