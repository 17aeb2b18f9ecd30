// Pointshell files (Barbič & James 2008, sec. 2.4: the precomputed nested pointshell): a
// versioned, checksummed binary container (util/binary_io.h, magic "CLPS", version 1), and the
// structural validation applied to every loaded pointshell.
#pragma once

#include <filesystem>
#include <string>

#include "pointshell/pointshell.h"

namespace contactlab {

// Throws Error("WHERE: ...") naming the first broken invariant: array lengths, finite
// positions, unit normals (|n| within 1e-3 of 1), strictly increasing level point counts
// ending at #P, level node ranges matching them, node points in range and each point once
// per level, parents on the previous level (-1 on level 0) whose child range holds the node,
// child ranges increasing and inside the next level, finite non-negative radii, 0 at leaves.
void ValidatePointshell(const Pointshell& shell, const std::string& where);

// Writes SHELL atomically (temporary name, then rename). Throws Error naming PATH on failure.
void SavePointshell(const Pointshell& shell, const std::filesystem::path& path);

// Reads and validates a pointshell file. Throws Error naming PATH for a missing, truncated
// or corrupt file (magic, version, length or checksum) or a structurally invalid pointshell.
Pointshell LoadPointshell(const std::filesystem::path& path);

}  // namespace contactlab
