// Checks on an output path made before any work starts, so that a long computation never ends
// in "cannot write" and an output never replaces a device, a folder or the command's own input.
#pragma once

#include <filesystem>
#include <string_view>

namespace contactlab {

// Throws Error naming PATH unless PATH is absent or a regular file (a symlink is judged by
// what it points to): a folder, a device, a named pipe or a socket is never replaced. WHAT
// names the option in the message ("--out").
void CheckOutputTarget(const std::filesystem::path& path, std::string_view what);

// Throws Error naming PATH unless PATH is absent or a folder. WHAT names the option.
void CheckOutputFolder(const std::filesystem::path& path, std::string_view what);

// Throws Error naming both files when OUTPUT is the same file as INPUT (the same inode when both
// exist, else the same absolute path), so that a command never overwrites what it reads.
void CheckOutputIsNotInput(const std::filesystem::path& output, const std::filesystem::path& input,
                           std::string_view what);

}  // namespace contactlab
