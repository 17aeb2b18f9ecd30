#include "util/atomic_file.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>

#include <filesystem>
#include <string>

#include "test_support.h"
#include "util/error.h"
#include "util/output_target.h"
#include "util/temporary_files.h"

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

// What ReadWholeFile says for TARGET (empty when it reads).
std::string ReadError(const std::filesystem::path& target) {
  try {
    ReadWholeFile(target);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(AtomicFile, ReadingANamedPipeIsRefusedWithoutBlocking) {
  testing::TempDir dir;
  const std::filesystem::path fifo = dir / "field.sdf";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  // No writer ever opens the pipe: a blocking open would hang the test.
  const std::string message = ReadError(fifo);
  EXPECT_NE(message.find("field.sdf"), std::string::npos) << message;
  EXPECT_NE(message.find("is a named pipe, not a file"), std::string::npos) << message;
}

TEST(AtomicFile, FoldersAndDevicesAreNotReportedAsMissing) {
  testing::TempDir dir;
  const std::string folder = ReadError(dir.path());
  EXPECT_NE(folder.find("is a folder, not a file"), std::string::npos) << folder;
  const std::string device = ReadError("/dev/zero");
  EXPECT_NE(device.find("/dev/zero: is a character device, not a file"), std::string::npos) << device;
  EXPECT_EQ(device.find("not found"), std::string::npos) << device;
  EXPECT_EQ(device.find("does not exist"), std::string::npos) << device;
}

int CountFiles(const std::filesystem::path& dir) {
  int files = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++files;
  return files;
}

// A named pipe (a special file anyone can make) stands for a device: the writer must refuse it
// and leave it in place, not rename a regular file over it.
TEST(AtomicFile, OutputOntoANamedPipeIsRefusedAndThePipeKept) {
  testing::TempDir dir;
  const auto pipe = dir / "pipe";
  ASSERT_EQ(::mkfifo(pipe.c_str(), 0600), 0);
  try {
    WriteFileAtomically(pipe, std::string_view("data\n"));
    FAIL() << "wrote over a named pipe";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(pipe.string()), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("named pipe"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(std::filesystem::is_fifo(pipe));
  EXPECT_EQ(CountFiles(dir.path()), 1);  // no temporary left beside it
}

TEST(AtomicFile, OutputOntoAFolderIsRefused) {
  testing::TempDir dir;
  std::filesystem::create_directory(dir / "sub");
  EXPECT_THROW(WriteFileAtomically(dir / "sub", std::string_view("data\n")), Error);
  EXPECT_TRUE(std::filesystem::is_directory(dir / "sub"));
  EXPECT_EQ(CountFiles(dir.path()), 1);
}

// Only checked, never written: a device is refused before anything is opened.
TEST(OutputTarget, OutputOntoADeviceIsRefused) {
  try {
    CheckOutputTarget("/dev/null", "--out");
    FAIL() << "/dev/null accepted as an output";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/dev/null"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("device"), std::string::npos) << e.what();
  }
  testing::TempDir dir;
  EXPECT_NO_THROW(CheckOutputTarget(dir / "absent.sdf", "--out"));
  WriteFileAtomically(dir / "regular.sdf", std::string_view("x"));
  EXPECT_NO_THROW(CheckOutputTarget(dir / "regular.sdf", "--out"));
  EXPECT_THROW(CheckOutputTarget(dir.path(), "--out"), Error);
}

TEST(OutputTarget, OutputFolderThatIsAFileIsRefused) {
  testing::TempDir dir;
  WriteFileAtomically(dir / "file", std::string_view("x"));
  EXPECT_THROW(CheckOutputFolder(dir / "file", "--out"), Error);
  EXPECT_NO_THROW(CheckOutputFolder(dir.path(), "--out"));
  EXPECT_NO_THROW(CheckOutputFolder(dir / "new", "--out"));
}

TEST(OutputTarget, OutputEqualToTheInputIsRefusedNamingBoth) {
  testing::TempDir dir;
  const auto input = dir / "joint.obj";
  WriteFileAtomically(input, std::string_view("v 0 0 0\n"));
  // The same file through another spelling and through a hard link.
  const auto other_spelling = dir / "." / "joint.obj";
  std::filesystem::create_hard_link(input, dir / "link.obj");
  for (const auto& out : {input, other_spelling, dir / "link.obj"}) {
    try {
      CheckOutputIsNotInput(out, input, "--out");
      FAIL() << out << " accepted as the output of " << input;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(out.string()), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(input.string()), std::string::npos) << e.what();
    }
  }
  EXPECT_NO_THROW(CheckOutputIsNotInput(dir / "joint.sdf", input, "--out"));
}

// SIGTERM in the middle of a write: the handler unlinks the temporary, then the process dies
// of the signal as before.
TEST(AtomicFileDeathTest, SignalDuringAWriteLeavesNoTemporary) {
  GTEST_FLAG_SET(death_test_style, "fast");
  testing::TempDir dir;
  const auto target = dir / "field.sdf";
  EXPECT_EXIT(
      {
        InstallTemporaryFileCleanupOnSignals();
        WriteFileAtomically(target, [](std::ostream& out) {
          out << "half a field";
          out.flush();
          ::raise(SIGTERM);
        });
      },
      ::testing::KilledBySignal(SIGTERM), "");
  EXPECT_FALSE(std::filesystem::exists(target));
  EXPECT_EQ(CountFiles(dir.path()), 0);
}

TEST(TemporaryOutput, UncommittedTemporaryIsRemoved) {
  testing::TempDir dir;
  {
    TemporaryOutput output(dir / "log.csv");
    WriteFileAtomically(output.temporary(), std::string_view("partial"));
    EXPECT_EQ(CountFiles(dir.path()), 1);
  }
  EXPECT_EQ(CountFiles(dir.path()), 0);
}

}  // namespace
}  // namespace contactlab
