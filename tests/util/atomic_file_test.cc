#include "util/atomic_file.h"

#include <gtest/gtest.h>

#include "test_support.h"
#include "util/error.h"

namespace contactlab {
namespace {

TEST(AtomicFile, FailedWriteLeavesNeitherTargetNorTemporary) {
  testing::TempDir dir;
  const auto target = dir / "out.csv";
  EXPECT_THROW(WriteFileAtomically(target,
                                   [](std::ostream& out) {
                                     out << "partial,row\n";
                                     throw Error("interrupted");
                                   }),
               Error);
  EXPECT_FALSE(std::filesystem::exists(target));
  int files = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir.path())) ++files;
  EXPECT_EQ(files, 0);
}

TEST(AtomicFile, FailedRewriteKeepsThePreviousFile) {
  testing::TempDir dir;
  const auto target = dir / "out.txt";
  WriteFileAtomically(target, std::string_view("complete\n"));
  EXPECT_THROW(WriteFileAtomically(target, [](std::ostream&) { throw Error("boom"); }), Error);
  EXPECT_EQ(ReadWholeFile(target), "complete\n");
}

TEST(AtomicFile, ReadingAMissingFileNamesIt) {
  try {
    ReadWholeFile("/nonexistent/contactlab/file.bin");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/contactlab/file.bin"), std::string::npos);
  }
}

}  // namespace
}  // namespace contactlab
