// Reading gzip-compressed files (RFC 1952) through zlib: the shipped meshes are stored as
// .obj.gz / .off.gz / .ply.gz / .stl.gz and decompressed into memory before parsing.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

namespace contactlab {

// True when PATH's name ends in ".gz" (case-insensitive).
bool IsGzipName(const std::filesystem::path& path);

// PATH without a trailing ".gz" ("dragon.obj.gz" -> "dragon.obj"); PATH itself otherwise.
std::filesystem::path WithoutGzipSuffix(const std::filesystem::path& path);

// Decompresses BYTES, one or more concatenated gzip members, read from FILE (named in errors).
// Throws Error naming FILE when the data is not gzip, is corrupt (bad header, bad deflate data,
// CRC or length mismatch) or ends before the stream does.
std::string GunzipBytes(std::string_view bytes, std::string_view file);

// Reads and decompresses PATH; throws Error naming PATH as ReadWholeFile and GunzipBytes do.
std::string ReadGzipFile(const std::filesystem::path& path);

}  // namespace contactlab
