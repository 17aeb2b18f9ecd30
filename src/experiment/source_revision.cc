// ConfigRevision runs git in the config file's folder; BuildRevision is the commit written
// into build_commit.h at build time (cmake/build_commit.cmake).
#include "experiment/source_revision.h"

#include <cstdio>

#include "build_commit.h"
#include "util/data_path.h"
#include "util/shell_quote.h"

namespace contactlab {
namespace {

// Standard output of COMMAND (run by /bin/sh), trailing newlines removed; empty on failure.
std::string CommandOutput(const std::string& command) {
  std::string out;
  if (FILE* p = ::popen(command.c_str(), "r")) {
    char buf[512];
    while (std::fgets(buf, sizeof buf, p)) out += buf;
    if (::pclose(p) != 0) out.clear();
  }
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  return out;
}

}  // namespace

std::string ConfigRevision(const std::filesystem::path& config_file) {
  const std::string git = "git -C " + ShellQuote(FolderOf(config_file).string());
  std::string commit = CommandOutput(git + " rev-parse HEAD 2>/dev/null");
  if (commit.empty()) return "unknown";
  if (!CommandOutput(git + " status --porcelain --untracked-files=no 2>/dev/null").empty()) {
    commit += " (with uncommitted changes)";
  }
  return commit;
}

std::string BuildRevision() { return CONTACTLAB_BUILD_COMMIT; }

}  // namespace contactlab
