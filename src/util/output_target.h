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

// Checks before the work that PATH can be written as an output: CheckOutputTarget, never a file
// the command read (util/input_files.h), and a probe file created and removed in PATH's folder,
// or in the nearest existing folder above it (where PATH's folders will be made), so that a
// read-only file system or a folder without write permission is reported now, not after the
// work. Throws Error naming PATH and WHAT (the option, "--out").
void CheckOutputWritable(const std::filesystem::path& path, std::string_view what);

// The same for a results folder written as one commit (util/atomic_folder.h): CheckOutputFolder,
// and the probe in the folder that holds FOLDER (where its staging folder goes) and in FOLDER
// itself when it exists (the entries it keeps move out of it).
void CheckOutputFolderWritable(const std::filesystem::path& folder, std::string_view what);

// Throws Error naming both files when OUTPUT is the same file as INPUT (the same inode when both
// exist, else the same absolute path), so that a command never overwrites what it reads.
void CheckOutputIsNotInput(const std::filesystem::path& output, const std::filesystem::path& input,
                           std::string_view what);

}  // namespace contactlab
