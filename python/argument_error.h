// The error of a Python call's argument that is not what the call takes (a shape, a value that
// is not finite, a pose that is no rigid transform): a contactlab::Error, raised in Python as
// contactlab.ArgumentError, which is both a contactlab.Error and a ValueError (module.cc).
#pragma once

#include <string>
#include <string_view>

#include "util/error.h"

namespace contactlab::python {

class ArgumentError : public Error {
 public:
  using Error::Error;
};

// Throws ArgumentError("WHERE: WHAT"), WHERE naming the argument.
[[noreturn]] inline void FailArgument(std::string_view where, std::string_view what) {
  throw ArgumentError(std::string(where) + ": " + std::string(what));
}

}  // namespace contactlab::python
