#include "util/binary_io.h"

#include <gtest/gtest.h>

#include <fstream>

#include "test_support.h"
#include "util/atomic_file.h"
#include "util/error.h"

namespace contactlab {
namespace {

using testing::TempDir;

std::filesystem::path WriteSample(const TempDir& dir) {
  BinaryWriter w;
  w.Put<double>(1.0 / 3.0);
  w.PutArray(std::vector<float>{1.5f, -2.0f, 3.25f});
  w.PutString("hello");
  const auto path = dir / "sample.bin";
  w.Save(path, "CLTEST", 2);
  return path;
}

TEST(BinaryIo, RoundTripPreservesValues) {
  TempDir dir;
  const auto path = WriteSample(dir);
  BinaryReader r(path, "CLTEST", 2);
  EXPECT_EQ(r.version(), 2u);
  EXPECT_EQ(r.Get<double>("third"), 1.0 / 3.0);
  EXPECT_EQ(r.GetArray<float>("floats"), (std::vector<float>{1.5f, -2.0f, 3.25f}));
  EXPECT_EQ(r.GetString("text"), "hello");
  EXPECT_NO_THROW(r.ExpectEnd());
}

TEST(BinaryIo, TruncatedFileIsRejectedNamingTheFile) {
  TempDir dir;
  const auto path = WriteSample(dir);
  std::string bytes = ReadWholeFile(path);
  WriteFileAtomically(path, std::string_view(bytes).substr(0, bytes.size() - 7));
  try {
    BinaryReader r(path, "CLTEST", 2);
    FAIL() << "a truncated file was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("truncated"), std::string::npos) << e.what();
  }
}

TEST(BinaryIo, FlippedPayloadByteFailsTheChecksum) {
  TempDir dir;
  const auto path = WriteSample(dir);
  std::string bytes = ReadWholeFile(path);
  bytes[24] ^= 0x10;
  WriteFileAtomically(path, bytes);
  EXPECT_THROW(BinaryReader(path, "CLTEST", 2), Error);
}

TEST(BinaryIo, WrongMagicAndNewerVersionAreRejected) {
  TempDir dir;
  const auto path = WriteSample(dir);
  EXPECT_THROW(BinaryReader(path, "OTHER", 2), Error);
  EXPECT_THROW(BinaryReader(path, "CLTEST", 1), Error);
}

TEST(BinaryIo, ReadingPastThePayloadThrows) {
  TempDir dir;
  const auto path = WriteSample(dir);
  BinaryReader r(path, "CLTEST", 2);
  r.Get<double>("a");
  r.GetArray<float>("b");
  r.GetString("c");
  EXPECT_THROW(r.Get<int>("past the end"), Error);
}

}  // namespace
}  // namespace contactlab
