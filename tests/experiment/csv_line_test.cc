// CSV cells written and read with RFC 4180 quoting (experiment/csv_line.h), against the
// quoting the RFC spells out: a cell holding a comma, a double quote or a line break is
// enclosed in double quotes, and a quote inside it is doubled.
#include "experiment/csv_line.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "util/error.h"

namespace contactlab {
namespace {

using Cells = std::vector<std::string>;

TEST(CsvLine, CommaQuoteOrLineBreakInACellIsQuotedAsRfc4180Spells) {
  std::string out;
  CsvLine line(&out);
  line.Text("plain");
  line.Text("with, comma");
  line.Text("say \"hi\"");
  line.Text("two\nlines");
  line.Int(3);
  line.Empty();
  EXPECT_EQ(out, "plain,\"with, comma\",\"say \"\"hi\"\"\",\"two\nlines\",3,");
}

TEST(CsvReader, QuotedCellsReadBackWholeWithTheLineEachRecordStartsOn) {
  // RFC 4180's own examples (sec. 2, rules 5-7), with CRLF and LF line ends and a blank line.
  const std::string text =
      "a,b,c\r\n"
      "\"aaa\",\"b\r\nbb\",\"ccc\"\r\n"
      "\n"
      "zzz,\"b\"\"bb\",\n"
      "\"x,y\",,\"\"";
  CsvReader reader(text, "t.csv");
  Cells cells;
  ASSERT_TRUE(reader.Next(&cells));
  EXPECT_EQ(cells, (Cells{"a", "b", "c"}));
  EXPECT_EQ(reader.line(), 1);
  ASSERT_TRUE(reader.Next(&cells));
  EXPECT_EQ(cells, (Cells{"aaa", "b\r\nbb", "ccc"}));
  EXPECT_EQ(reader.line(), 2);
  ASSERT_TRUE(reader.Next(&cells));
  EXPECT_EQ(cells, (Cells{"zzz", "b\"bb", ""}));
  EXPECT_EQ(reader.line(), 5);  // after the record spanning lines 2-3 and the blank line 4
  ASSERT_TRUE(reader.Next(&cells));
  EXPECT_EQ(cells, (Cells{"x,y", "", ""}));
  EXPECT_EQ(reader.line(), 6);
  EXPECT_FALSE(reader.Next(&cells));
}

TEST(CsvReader, WhatCsvLineWritesReadsBackCellForCell) {
  const Cells names = {"exp, \"one\"", "scenes/plate,thin.yaml", "py,model", "line\nbreak", "", "\"", ",,"};
  std::string out;
  for (int row = 0; row < 2; ++row) {
    CsvLine line(&out);
    for (const std::string& n : names) line.Text(n);
    out += '\n';
  }
  CsvReader reader(out, "t.csv");
  Cells cells;
  for (int row = 0; row < 2; ++row) {
    ASSERT_TRUE(reader.Next(&cells));
    EXPECT_EQ(cells, names);
  }
  EXPECT_FALSE(reader.Next(&cells));
}

TEST(CsvReader, UnclosedQuoteOrTextAfterAClosingQuoteIsAnErrorNamingFileAndLine) {
  Cells cells;
  CsvReader cut("a,b\n1,\"cut sh", "cut.csv");
  ASSERT_TRUE(cut.Next(&cells));
  try {
    cut.Next(&cells);
    FAIL() << "an unclosed quote was read";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("cut.csv:2"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("not closed"), std::string::npos) << e.what();
  }
  CsvReader after("\"a\"b,c\n", "after.csv");
  try {
    after.Next(&cells);
    FAIL() << "text after a closing quote was read";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("after.csv:1"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace contactlab
