#include "util/atomic_file.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "test_support.h"
#include "util/atomic_folder.h"
#include "util/error.h"
#include "util/input_files.h"
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


// An output onto a file the command read, however it is named (the path, a symlink, a hard
// link), is refused and the file kept; outside a record of inputs nothing is refused.
TEST(InputFiles, OutputOntoAFileTheCommandReadIsRefusedUnderAnyName) {
  testing::TempDir dir;
  const auto input = dir / "scene.yaml";
  WriteFileAtomically(input, std::string_view("the input\n"));
  std::filesystem::create_symlink(input, dir / "link.yaml");
  std::filesystem::create_hard_link(input, dir / "hard.yaml");
  {
    const InputFileRecord record;
    EXPECT_EQ(ReadWholeFile(dir / "link.yaml"), "the input\n");
    for (const std::filesystem::path& out : {input, dir / "link.yaml", dir / "hard.yaml", dir / "." / "scene.yaml"}) {
      SCOPED_TRACE(out.string());
      try {
        WriteFileAtomically(out, std::string_view("the output\n"));
        ADD_FAILURE() << "the input was overwritten";
      } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("is the input"), std::string::npos) << e.what();
      }
      EXPECT_THROW(CheckOutputWritable(out, "--out"), Error);
    }
    EXPECT_EQ(ReadWholeFile(input), "the input\n");
    EXPECT_NO_THROW(WriteFileAtomically(dir / "other.yaml", std::string_view("x")));
    // An input read after the output was opened is caught at the commit.
    TemporaryOutput late(dir / "late.txt");
    WriteFileAtomically(late.temporary(), std::string_view("the output\n"));
    WriteFileAtomically(dir / "late.txt", std::string_view("read late\n"));
    ReadWholeFile(dir / "late.txt");
    EXPECT_THROW(late.Commit(), Error);
    EXPECT_EQ(ReadWholeFile(dir / "late.txt"), "read late\n");
  }
  EXPECT_NO_THROW(WriteFileAtomically(input, std::string_view("rewritten\n")));  // no record: allowed
}

// A results folder in which a failure strikes between two files: the old folder stays whole
// (every old file, none new), and no staging folder is left. A commit replaces every file it
// writes and every file KEEP does not keep, and keeps the others.
TEST(AtomicFolder, FailureBetweenFilesLeavesTheOldFolderWhole) {
  testing::TempDir dir;
  const auto out = dir / "results";
  std::filesystem::create_directories(out / "slurm");
  for (const char* name : {"cycles.csv", "summary.csv", "meta.json", "notes.txt"}) {
    WriteFileAtomically(out / name, std::string("old ") + name);
  }
  const auto keep = [](const std::string& name) { return name != "cycles.csv" && name != "summary.csv" && name != "meta.json"; };
  EXPECT_THROW(
      {
        TemporaryFolder folder(out, keep);
        folder.Write("cycles.csv", "new cycles");
        throw Error("the disk is full");
      },
      Error);
  EXPECT_EQ(CountFiles(dir.path()), 1);  // no staging folder beside it
  for (const char* name : {"cycles.csv", "summary.csv", "meta.json", "notes.txt"}) {
    EXPECT_EQ(ReadWholeFile(out / name), std::string("old ") + name);
  }
  {
    TemporaryFolder folder(out, keep);
    folder.Write("cycles.csv", "new cycles");
    folder.Write("meta.json", "new meta");
    folder.Commit();
  }
  EXPECT_EQ(CountFiles(dir.path()), 1);
  EXPECT_EQ(ReadWholeFile(out / "cycles.csv"), "new cycles");
  EXPECT_EQ(ReadWholeFile(out / "meta.json"), "new meta");
  EXPECT_FALSE(std::filesystem::exists(out / "summary.csv"));  // an old result file goes
  EXPECT_EQ(ReadWholeFile(out / "notes.txt"), "old notes.txt");
  EXPECT_TRUE(std::filesystem::is_directory(out / "slurm"));
  // A new folder where there was none.
  {
    TemporaryFolder folder(dir / "a" / "b", keep);
    folder.Write("meta.json", "first");
    folder.Commit();
  }
  EXPECT_EQ(ReadWholeFile(dir / "a" / "b" / "meta.json"), "first");
}

// An old result file that is an input of the command is never removed by the commit.
// `run --out LINK`, LINK a dangling symlink, replaced the link by a folder: it is refused naming
// the link and its target, before anything is staged, and the link stays; a link to a folder
// is followed, and the results land in the folder it names.
TEST(AtomicFolder, ADanglingSymlinkIsRefusedAndALinkToAFolderFollowed) {
  testing::TempDir dir;
  std::filesystem::create_symlink(dir / "missing", dir / "link");
  try {
    TemporaryFolder folder(dir / "link", nullptr);
    ADD_FAILURE() << "a dangling symlink was taken as the results folder";
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("link"), std::string::npos) << msg;
    EXPECT_NE(msg.find("missing, which does not exist"), std::string::npos) << msg;
  }
  EXPECT_TRUE(std::filesystem::is_symlink(std::filesystem::symlink_status(dir / "link")));
  EXPECT_EQ(CountFiles(dir.path()), 1);  // the link alone: nothing staged
  std::filesystem::create_directory(dir / "real");
  std::filesystem::create_symlink(dir / "real", dir / "good");
  {
    TemporaryFolder folder(dir / "good", nullptr);
    folder.Write("meta.json", "new meta");
    folder.Commit();
  }
  EXPECT_TRUE(std::filesystem::is_symlink(std::filesystem::symlink_status(dir / "good")));
  EXPECT_EQ(ReadWholeFile(dir / "real" / "meta.json"), "new meta");
}

TEST(AtomicFolder, ReplacingAFileTheCommandReadIsRefused) {
  testing::TempDir dir;
  const auto out = dir / "results";
  WriteFileAtomically(out / "summary.csv", std::string_view("read as the config"));
  const InputFileRecord record;
  ReadWholeFile(out / "summary.csv");
  TemporaryFolder folder(out, [](const std::string&) { return false; });
  folder.Write("cycles.csv", "new");
  EXPECT_THROW(folder.Commit(), Error);
  EXPECT_EQ(ReadWholeFile(out / "summary.csv"), "read as the config");
  EXPECT_FALSE(std::filesystem::exists(out / "cycles.csv"));
}

// SIGHUP while a results folder is being written: the staging folder and its files are removed
// before the process dies of the signal, and the old folder is as it was.
TEST(AtomicFolderDeathTest, SignalWhileWritingAFolderLeavesNoStagingFolder) {
  GTEST_FLAG_SET(death_test_style, "fast");
  testing::TempDir dir;
  WriteFileAtomically(dir / "results" / "meta.json", std::string_view("old"));
  EXPECT_EXIT(
      {
        InstallTemporaryFileCleanupOnSignals();
        TemporaryFolder folder(dir / "results", [](const std::string&) { return true; });
        folder.Write("cycles.csv", "new");
        folder.Write("meta.json", "new");
        ::raise(SIGHUP);
      },
      ::testing::KilledBySignal(SIGHUP), "");
  EXPECT_EQ(CountFiles(dir.path()), 1);
  EXPECT_EQ(ReadWholeFile(dir / "results" / "meta.json"), "old");
}

// Before the work: an output whose folder cannot be written (here a regular file where its
// folder should be) is refused naming the option.
TEST(OutputTarget, UnwritableOutputFolderIsRefusedBeforeTheWork) {
  testing::TempDir dir;
  WriteFileAtomically(dir / "file", std::string_view("x"));
  EXPECT_THROW(CheckOutputWritable(dir / "file" / "out.csv", "--out"), Error);
  EXPECT_THROW(CheckOutputFolderWritable(dir / "file" / "results", "--out"), Error);
  EXPECT_NO_THROW(CheckOutputWritable(dir / "new" / "out.csv", "--out"));
  EXPECT_NO_THROW(CheckOutputFolderWritable(dir / "new" / "results", "--out"));
  EXPECT_FALSE(std::filesystem::exists(dir / "new"));  // the check makes no folder
  EXPECT_EQ(CountFiles(dir.path()), 1);                // and leaves no probe
  if (::geteuid() == 0) return;  // root writes through mode bits; the CLI test uses a read-only mount
  std::filesystem::create_directory(dir / "locked");
  std::filesystem::permissions(dir / "locked", std::filesystem::perms::owner_read | std::filesystem::perms::owner_exec);
  EXPECT_THROW(CheckOutputWritable(dir / "locked" / "out.csv", "--out"), Error);
  std::filesystem::permissions(dir / "locked", std::filesystem::perms::owner_all);
}

}  // namespace
}  // namespace contactlab
