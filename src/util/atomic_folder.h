// Writing a folder of outputs (a run's results) as one commit: its files go into a staging
// folder beside it, which then takes its place in one step, so that a reader sees the old folder
// or the new one, never new files beside old ones, and a failed run (a full disk between two
// files, an exception, a signal) leaves the old folder as it was.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace contactlab {

// A staging folder "PATH.tmp-<pid>-<n>" beside PATH that becomes PATH at Commit. Construction
// checks PATH (absent or a folder; a symlink to a folder is followed: the folder it names is
// replaced, the link kept), creates PATH's parent folders and the staging folder, and registers
// it for removal on a signal; the destructor removes it and its files unless committed.
//
// PATH's old entries: those the new folder does not hold and KEEP accepts by name are moved
// into the new folder at Commit (a run keeps its Slurm scripts and job folders); every other
// one goes with the old folder. None of those that go may be a file the command read
// (util/input_files.h). Throws Error naming PATH.
class TemporaryFolder {
 public:
  TemporaryFolder(std::filesystem::path path, std::function<bool(const std::string&)> keep);
  ~TemporaryFolder();
  TemporaryFolder(const TemporaryFolder&) = delete;
  TemporaryFolder& operator=(const TemporaryFolder&) = delete;

  const std::filesystem::path& path() const { return path_; }
  const std::filesystem::path& temporary() const { return temporary_; }
  // Writes BYTES as the file NAME of the new folder. Throws Error naming PATH/NAME when the
  // write fails (a full disk, an I/O error).
  void Write(const std::string& name, std::string_view bytes);
  // Puts the new folder in PATH's place: renamed there when PATH is absent, else exchanged
  // with the old folder in one step (Linux renameat2 RENAME_EXCHANGE), which is then removed.
  void Commit();

 private:
  void MoveKeptEntries();
  void MoveKeptEntriesBack();

  std::filesystem::path path_;
  std::filesystem::path temporary_;
  std::function<bool(const std::string&)> keep_;
  std::vector<std::string> written_;
  std::vector<std::string> moved_;  // old entries moved into the staging folder at Commit
  int slot_ = -1;
  bool committed_ = false;
};

}  // namespace contactlab
