// The files a command has read, recorded where they are opened, so that no output of the command
// replaces one of them: whichever option names it, and however the path is spelled (a relative
// path, a symlink, a hard link). Recording is on while an InputFileRecord is alive (the program's
// main holds one for the whole command); without one nothing is recorded or refused, so that a
// long-lived process (the Python module, a test binary) may read a file and later rewrite it.
#pragma once

#include <filesystem>
#include <string_view>

namespace contactlab {

// Turns recording on for its lifetime (nested records share one list, cleared by the outermost).
class InputFileRecord {
 public:
  InputFileRecord();
  ~InputFileRecord();
  InputFileRecord(const InputFileRecord&) = delete;
  InputFileRecord& operator=(const InputFileRecord&) = delete;
};

// While alive, outputs written by this thread are not checked against the record: a cache entry
// (util/cached_or_built.h), which parallel jobs may each build and save while another has read
// it already, and whose name comes from its key, never from an option.
class CacheEntryWrite {
 public:
  CacheEntryWrite();
  ~CacheEntryWrite();
  CacheEntryWrite(const CacheEntryWrite&) = delete;
  CacheEntryWrite& operator=(const CacheEntryWrite&) = delete;
};

// Records PATH (an existing file just opened for reading) as an input of the command: its
// device and inode and its canonical path. Does nothing without a live InputFileRecord.
void RecordInputFile(const std::filesystem::path& path);

// Throws Error naming OUTPUT and the input when OUTPUT is a recorded input: the same file when
// it exists, or the same canonical path. WHAT names the option ("--log").
void CheckOutputIsNoRecordedInput(const std::filesystem::path& output, std::string_view what);

}  // namespace contactlab
