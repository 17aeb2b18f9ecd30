// Writing output files so that a failed or interrupted run never leaves a file that looks
// complete: everything goes to a temporary name beside the target and is renamed at the end.
#pragma once

#include <filesystem>
#include <functional>
#include <ostream>
#include <string_view>

namespace contactlab {

// A temporary file "PATH.tmp-<pid>-<n>" beside PATH that becomes PATH at Commit. Construction
// checks PATH (CheckOutputTarget: absent or a regular file, never a device, folder or pipe; and
// never a file the command read, util/input_files.h), creates the parent folder and registers
// the temporary for removal on a signal; the destructor removes it unless committed. Throws
// Error naming PATH.
class TemporaryOutput {
 public:
  explicit TemporaryOutput(std::filesystem::path path);
  ~TemporaryOutput();
  TemporaryOutput(const TemporaryOutput&) = delete;
  TemporaryOutput& operator=(const TemporaryOutput&) = delete;

  const std::filesystem::path& path() const { return path_; }
  const std::filesystem::path& temporary() const { return temporary_; }
  // Renames the temporary onto PATH, checking PATH again first.
  void Commit();

 private:
  std::filesystem::path path_;
  std::filesystem::path temporary_;
  int slot_ = -1;
  bool committed_ = false;
};

// Calls WRITE with a stream onto a TemporaryOutput for PATH, flushes, checks the stream, and
// renames the temporary file onto PATH. On any failure (including an exception thrown by WRITE)
// the temporary file is removed and Error is thrown naming PATH (a NonFiniteValue thrown by WRITE,
// util/number_text.h, becomes "PATH: what"). BINARY opens in binary mode.
void WriteFileAtomically(const std::filesystem::path& path,
                         const std::function<void(std::ostream&)>& write, bool binary = false);

// Convenience: writes BYTES atomically.
void WriteFileAtomically(const std::filesystem::path& path, std::string_view bytes);

// Reads a whole regular file and records it as an input of the command (util/input_files.h);
// throws Error naming PATH when it does not exist, is not a regular file (a folder, a named pipe,
// a device, a socket: refused without blocking), or cannot be read.
std::string ReadWholeFile(const std::filesystem::path& path);

// Throws Error naming PATH unless it exists and is a regular file (after symlinks); the message
// says what it is instead ("is a named pipe, not a file"). WHAT names the expected input
// ("mesh file"), used in "WHAT not found".
void CheckInputFile(const std::filesystem::path& path, std::string_view what = "file");

// What PATH is when it exists but is not a regular file ("a folder", "a named pipe", ...), or
// an empty string for a regular file or nothing at all.
std::string NonRegularFileKind(const std::filesystem::path& path);

}  // namespace contactlab
