// The strict CSV reader: line numbers, comments, quoting and the error messages.
#include <gtest/gtest.h>

#include <string>

#include "calibrate/csv_table.hpp"
#include "calibrate/input_error.hpp"

using namespace grainlab::calibrate;

namespace {

// The message of the InputError that `f` throws ("" when it does not throw).
template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(CsvTable, KeepsLineNumbersAcrossCommentsAndBlankLines) {
  const auto t = CsvTable::parse(
      "# comment\n\nmaterial,H_m, h_m\nglass,0.5,0.4\n\n# more\n\"rubber, membrane\",0.5,0.2\r\n",
      "x.csv");
  EXPECT_EQ(t.header_line(), 3u);
  ASSERT_EQ(t.records().size(), 2u);
  EXPECT_EQ(t.records()[0].line, 4u);
  EXPECT_EQ(t.records()[1].line, 7u);
  EXPECT_EQ(t.text(t.records()[1], 0), "rubber, membrane");
  EXPECT_EQ(t.column("h_m"), 2u);  // spaces around names are trimmed
  EXPECT_DOUBLE_EQ(t.number(t.records()[1], 2), 0.2);
}

TEST(CsvTable, MissingColumnNamesFileLineAndHeader) {
  const auto t = CsvTable::parse("# c\nmaterial,H_m\nglass,0.5\n", "throws.csv");
  const std::string msg = error_of([&] { t.column("h_m"); });
  EXPECT_NE(msg.find("throws.csv line 2"), std::string::npos) << msg;
  EXPECT_NE(msg.find("missing column 'h_m'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("material, H_m"), std::string::npos) << msg;
}

TEST(CsvTable, NonNumericCellNamesLineAndColumn) {
  const auto t = CsvTable::parse("material,H_m,h_m\nglass,0.5,0.4\nglass,0.5,abc\n", "t.csv");
  const std::string msg = error_of([&] { t.number(t.records()[1], 2); });
  EXPECT_NE(msg.find("t.csv line 3"), std::string::npos) << msg;
  EXPECT_NE(msg.find("'h_m'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("'abc'"), std::string::npos) << msg;
  for (const char* bad : {"nan", "inf", "1e999", "0.4x", "1,5"}) {
    const auto u = CsvTable::parse(std::string("a\n\"") + bad + "\"\n", "u.csv");
    EXPECT_THROW(u.number(u.records()[0], 0), InputError) << bad;
  }
}

TEST(CsvTable, EmptyAndHeaderOnlyFilesAreErrors) {
  EXPECT_NE(error_of([] { CsvTable::parse("", "e.csv"); }).find("e.csv: the file is empty"),
            std::string::npos);
  EXPECT_NE(error_of([] { CsvTable::parse("# only a comment\n\n", "e.csv"); }).find("empty"),
            std::string::npos);
  EXPECT_NE(error_of([] { CsvTable::parse("a,b\n", "h.csv"); }).find("h.csv line 1: a header but"),
            std::string::npos);
}

TEST(CsvTable, RaggedRowsDuplicateColumnsAndBadQuotes) {
  EXPECT_NE(error_of([] { CsvTable::parse("a,b\n1,2\n1,2,3\n", "r.csv"); }).find("r.csv line 3"),
            std::string::npos);
  EXPECT_NE(error_of([] { CsvTable::parse("a,b\n1\n", "r.csv"); }).find("line 2: 1 fields"),
            std::string::npos);
  EXPECT_NE(error_of([] { CsvTable::parse("a,a\n1,2\n", "d.csv"); }).find("appears twice"),
            std::string::npos);
  EXPECT_NE(error_of([] { CsvTable::parse("a,b\n\"x,2\n", "q.csv"); }).find("q.csv line 2"),
            std::string::npos);
  EXPECT_NE(error_of([] { CsvTable::read("/nonexistent/dir/f.csv"); }).find("cannot open"),
            std::string::npos);
}
