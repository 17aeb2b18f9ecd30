#include "util/output_target.h"

#include <string>

#include "util/error.h"

namespace contactlab {
namespace fs = std::filesystem;
namespace {

// What a non-regular file is, in a few words.
const char* KindOf(fs::file_type type) {
  switch (type) {
    case fs::file_type::directory: return "a folder";
    case fs::file_type::character:
    case fs::file_type::block: return "a device";
    case fs::file_type::fifo: return "a named pipe";
    case fs::file_type::socket: return "a socket";
    default: return "not a regular file";
  }
}

}  // namespace

void CheckOutputTarget(const fs::path& path, std::string_view what) {
  if (path.empty()) Fail(what, "the output path is empty");
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (status.type() == fs::file_type::not_found || status.type() == fs::file_type::regular) return;
  if (ec) Fail(path.string(), std::string(what) + ": cannot inspect the output: " + ec.message());
  Fail(path.string(), std::string(what) + " is " + KindOf(status.type()) + ", not a regular file; refusing to replace it");
}

void CheckOutputFolder(const fs::path& path, std::string_view what) {
  if (path.empty()) Fail(what, "the output folder is empty");
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (status.type() == fs::file_type::not_found || status.type() == fs::file_type::directory) return;
  if (ec) Fail(path.string(), std::string(what) + ": cannot inspect the output folder: " + ec.message());
  const std::string kind = status.type() == fs::file_type::regular ? "a file" : KindOf(status.type());
  Fail(path.string(), std::string(what) + " is " + kind + ", not a folder");
}

void CheckOutputIsNotInput(const fs::path& output, const fs::path& input, std::string_view what) {
  std::error_code ec;
  bool same = fs::exists(output, ec) && fs::exists(input, ec) && fs::equivalent(output, input, ec);
  if (!same) {
    const fs::path a = fs::weakly_canonical(fs::absolute(output, ec), ec);
    const fs::path b = fs::weakly_canonical(fs::absolute(input, ec), ec);
    same = !a.empty() && a == b;
  }
  if (same) Fail(output.string(), std::string(what) + " is the input " + input.string() + "; refusing to overwrite it");
}

}  // namespace contactlab
