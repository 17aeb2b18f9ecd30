#include "view/page_encoding.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "util/error.h"

namespace contactlab {
namespace {

TEST(Base64, MatchesRfc4648Vectors) {
  EXPECT_EQ(Base64Encode(""), "");
  EXPECT_EQ(Base64Encode("f"), "Zg==");
  EXPECT_EQ(Base64Encode("fo"), "Zm8=");
  EXPECT_EQ(Base64Encode("foo"), "Zm9v");
  EXPECT_EQ(Base64Encode("foob"), "Zm9vYg==");
  EXPECT_EQ(Base64Encode("fooba"), "Zm9vYmE=");
  EXPECT_EQ(Base64Encode("foobar"), "Zm9vYmFy");
  EXPECT_EQ(Base64Encode(std::string("\xff\xfe\x00", 3)), "//4A");
}

TEST(Base64, RoundTripOfEveryByteAndLength) {
  std::mt19937 rng(17);
  for (int n = 0; n < 70; ++n) {
    std::string bytes(n, '\0');
    for (char& c : bytes) c = char(rng() & 255);
    const std::string text = Base64Encode(bytes);
    EXPECT_EQ(text.size() % 4, 0u);
    EXPECT_EQ(Base64Decode(text, "test"), bytes) << "length " << n;
  }
}

TEST(Base64, BadTextIsAnErrorNamingWhere) {
  for (const char* bad : {"Zg=", "Zm9v$A==", "Z===", "=m9v", "Zg==Zg=="}) {
    try {
      Base64Decode(bad, "page.json: slice.values");
      ADD_FAILURE() << bad << " was accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("page.json: slice.values"), std::string::npos) << e.what();
    }
  }
}

TEST(Base64, FloatArraysRoundTripBitForBit) {
  const std::vector<float> v = {1.0f / 3, -0.0f, 1e-38f, -7.25e12f, std::numeric_limits<float>::infinity(),
                                std::numeric_limits<float>::denorm_min()};
  const std::vector<float> back = DecodeArray<float>(EncodeArray(v), "test");
  ASSERT_EQ(back.size(), v.size());
  for (std::size_t i = 0; i < v.size(); ++i) {
    EXPECT_EQ(std::memcmp(&back[i], &v[i], sizeof(float)), 0) << i;
  }
  const std::vector<std::uint32_t> idx = {0, 1, 4294967295u, 123456789};
  EXPECT_EQ(DecodeArray<std::uint32_t>(EncodeArray(idx), "test"), idx);
  const std::vector<std::uint8_t> levels = {0, 1, 2, 11};
  EXPECT_EQ(DecodeArray<std::uint8_t>(EncodeArray(levels), "test"), levels);
}

TEST(Base64, ArrayOfTheWrongWidthIsAnError) {
  EXPECT_THROW(DecodeArray<float>(Base64Encode("abcde"), "test"), Error);
}

TEST(ScriptSafeJson, NoValueCanCloseTheScriptElement) {
  const nlohmann::json j = {{"title", "a</script><script>alert(1)</script>"}, {"x", {1, 2, "</"}}};
  const std::string text = ScriptSafeJson(j);
  EXPECT_EQ(text.find("</"), std::string::npos) << text;
  EXPECT_EQ(nlohmann::json::parse(text), j);
}

TEST(ScriptSafeJson, InvalidUtf8IsReplacedNotThrown) {
  const nlohmann::json j = {{"name", std::string("bad\xff")}};
  EXPECT_NO_THROW(ScriptSafeJson(j));
}

}  // namespace
}  // namespace contactlab
