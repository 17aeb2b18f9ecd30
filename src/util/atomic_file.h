// Writing output files so that a failed or interrupted run never leaves a file that looks
// complete: everything goes to a temporary name beside the target and is renamed at the end.
#pragma once

#include <filesystem>
#include <functional>
#include <ostream>
#include <string_view>

namespace contactlab {

// Calls WRITE with a stream onto "PATH.tmp-<pid>-<n>", flushes, checks the stream, and renames
// the temporary file onto PATH. On any failure (including an exception thrown by WRITE) the
// temporary file is removed and Error is thrown naming PATH. BINARY opens in binary mode.
void WriteFileAtomically(const std::filesystem::path& path,
                         const std::function<void(std::ostream&)>& write, bool binary = false);

// Convenience: writes BYTES atomically.
void WriteFileAtomically(const std::filesystem::path& path, std::string_view bytes);

// Reads a whole file; throws Error naming PATH when it cannot be opened or read.
std::string ReadWholeFile(const std::filesystem::path& path);

}  // namespace contactlab
