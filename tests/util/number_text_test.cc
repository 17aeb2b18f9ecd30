// The number text of every export (util/number_text.h): each value reads back bit for bit, and a
// non-finite value is refused, naming the file, with nothing written.
#include "util/number_text.h"

#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>

#include "test_support.h"
#include "util/atomic_file.h"

namespace contactlab {
namespace {

template <typename T>
T ReadBack(const std::string& text) {
  T v{};
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  EXPECT_EQ(ec, std::errc()) << text;
  EXPECT_EQ(ptr, text.data() + text.size()) << text;
  return v;
}

// Random bit patterns (fixed seed) and values that decimal cannot hold (1/3, 0.1, subnormals,
// the largest double): the text reads back as the same bits, in at most 17 (double) or 9
// (float) significant digits.
TEST(NumberText, EveryFiniteValueReadsBackBitForBit) {
  std::mt19937_64 rng(20081);
  std::vector<double> doubles = {1.0 / 3, 0.1, -2.0 / 3e-7, 5e-324, std::numeric_limits<double>::max(),
                                 std::numeric_limits<double>::min(), 0.0, -0.0, 1e308, 123456789.123456789};
  std::vector<float> floats = {1.f / 3, 0.1f, 1e-45f, std::numeric_limits<float>::max(), -0.f, 3.14159265f};
  while (doubles.size() < 5000) {
    const std::uint64_t bits = rng();
    double d;
    std::memcpy(&d, &bits, sizeof d);
    if (std::isfinite(d)) doubles.push_back(d);
    const std::uint32_t fbits = std::uint32_t(rng());
    float f;
    std::memcpy(&f, &fbits, sizeof f);
    if (std::isfinite(f)) floats.push_back(f);
  }
  auto digits = [](const std::string& s) {
    // From the first to the last non-zero digit of the mantissa.
    std::string mantissa;
    for (const char c : s.substr(0, s.find('e'))) {
      if (c >= '0' && c <= '9') mantissa += c;
    }
    const auto first = mantissa.find_first_not_of('0');
    if (first == std::string::npos) return 1;
    return int(mantissa.find_last_not_of('0') - first + 1);
  };
  for (const double d : doubles) {
    const std::string text = NumberText(d);
    const double back = ReadBack<double>(text);
    EXPECT_EQ(std::memcmp(&back, &d, sizeof d), 0) << text;
    EXPECT_LE(digits(text), 17) << text;
  }
  for (const float f : floats) {
    const std::string text = NumberText(f);
    const float back = ReadBack<float>(text);
    EXPECT_EQ(std::memcmp(&back, &f, sizeof f), 0) << text;
    EXPECT_LE(digits(text), 9) << text;
  }
}

TEST(NumberText, NonFiniteValuesAreRefusedNamingWhatTheyAre) {
  std::string out = "x";
  for (const double v : {std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                         std::numeric_limits<double>::quiet_NaN()}) {
    try {
      AppendNumber(v, &out, "vertex 7");
      ADD_FAILURE() << "no error for " << v;
    } catch (const NonFiniteValue& e) {
      EXPECT_NE(std::string(e.what()).find("vertex 7 is "), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("not a finite number"), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(out, "x");  // nothing appended
  EXPECT_THROW(AppendNumber(std::numeric_limits<float>::infinity(), &out), NonFiniteValue);
}

// A writer meeting a non-finite value inside WriteFileAtomically: the error names the file and
// neither the file nor its temporary is left.
TEST(NumberText, AWriterMeetingANonFiniteValueLeavesNoFileAndNamesIt) {
  testing::TempDir dir;
  try {
    WriteFileAtomically(dir / "out.csv", [](std::ostream& out) {
      std::string text = "x\n";
      AppendNumber(1.5, &text, "row 2");
      AppendNumber(std::nan(""), &text, "row 3");
      out << text;
    });
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind((dir / "out.csv").string() + ": row 3 is nan", 0), 0u) << msg;
  }
  EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}

}  // namespace
}  // namespace contactlab
