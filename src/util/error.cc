#include "util/error.h"

namespace contactlab {

void Fail(std::string_view where, std::string_view what) {
  std::string message(where);
  message += ": ";
  message += what;
  throw Error(message);
}

void FailAtLine(std::string_view file, long line, std::string_view what) {
  Fail(std::string(file) + ":" + std::to_string(line), what);
}

}  // namespace contactlab
