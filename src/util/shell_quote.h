// Quoting for commands handed to /bin/sh (git in meta.json, generated Slurm scripts).
#pragma once

#include <string>

namespace contactlab {

// S single-quoted for a POSIX shell: 'it'\''s' for it's.
std::string ShellQuote(const std::string& s);

}  // namespace contactlab
