// A strict reader for the laboratory CSV files (restitution throws, trajectories, friction).
//
// Format: the first non-comment line is a header of column names; every further non-blank,
// non-comment line is a record with exactly as many fields as the header. Lines starting with
// '#' (after optional spaces) are comments. Fields may be quoted with '"' (RFC 4180, "" is a
// literal quote); surrounding spaces of unquoted fields are trimmed. Every record remembers its
// line number in the file, so every error can say "file line N: ...".
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace grainlab::calibrate {

struct CsvRecord {
  std::size_t line = 0;  // 1-based line number in the file
  std::vector<std::string> fields;
};

class CsvTable {
 public:
  // Parses text; `file_name` is what error messages call the file. Throws InputError.
  static CsvTable parse(std::string_view text, std::string file_name);
  // Reads and parses a file. Throws InputError (also when the file cannot be opened).
  static CsvTable read(const std::string& path);

  const std::string& file_name() const { return file_name_; }
  const std::vector<std::string>& header() const { return header_; }
  const std::vector<CsvRecord>& records() const { return records_; }
  std::size_t header_line() const { return header_line_; }

  // Index of a column, if present.
  std::optional<std::size_t> find_column(std::string_view name) const;
  // Index of a column; throws InputError naming the file, the header line and the columns found.
  std::size_t column(std::string_view name) const;

  // The cell as a finite number; throws InputError "file line N: column 'c': 'x' is not a number".
  double number(const CsvRecord& record, std::size_t column) const;
  // The cell as text, trimmed; throws InputError when it is empty.
  const std::string& text(const CsvRecord& record, std::size_t column) const;

  // "file line N" for messages.
  std::string where(const CsvRecord& record) const;

 private:
  std::string file_name_;
  std::size_t header_line_ = 0;
  std::vector<std::string> header_;
  std::vector<CsvRecord> records_;
};

// Whether `s` is well-formed UTF-8 (no overlong forms, surrogates or code points past U+10FFFF):
// text that ends up in a TOML file must be.
bool valid_utf8(std::string_view s);

}  // namespace grainlab::calibrate
