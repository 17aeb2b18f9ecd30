// Numbers written into files that other programs read (meshes, point and pointshell CSVs, VTK):
// the shortest decimal text that reads back as exactly the same value (std::to_chars: at most
// 17 significant digits for a double, 9 for a float), and never a non-finite value. One helper
// for every writer, so no export rounds a coordinate or writes "inf" or "nan".
#pragma once

#include <span>
#include <string>
#include <string_view>

#include "util/error.h"

namespace contactlab {

// A non-finite value met while a file's text was being formatted. Thrown inside the writing
// callback of WriteFileAtomically (util/atomic_file.h), it becomes an Error naming the file and
// nothing is written.
class NonFiniteValue : public Error {
 public:
  using Error::Error;
};

// Appends the shortest text that reads back as exactly V. Throws NonFiniteValue ("WHAT is inf,
// not a finite number") when V is infinite or NaN.
void AppendNumber(double v, std::string* out, std::string_view what = "a value");
void AppendNumber(float v, std::string* out, std::string_view what = "a value");
// The same as a string.
std::string NumberText(double v, std::string_view what = "a value");
std::string NumberText(float v, std::string_view what = "a value");
// Appends VALUES separated by SEPARATOR.
void AppendNumbers(std::span<const double> values, char separator, std::string* out, std::string_view what = "a value");

// Throws NonFiniteValue naming WHAT unless V is finite.
void RequireFinite(double v, std::string_view what);

}  // namespace contactlab
