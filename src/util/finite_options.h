// No command-line option of a ContactLab program takes a non-finite number: CLI11 reads "nan",
// "inf" and "1e999" as numbers, and its range checks (PositiveNumber, Range) let NaN through,
// since every comparison with NaN is false (`session --duration nan` ran for ever, `--k-vc nan`
// fell back to the default without a word). RequireFiniteNumbers is the one place that holds
// the rule for every floating-point option of a program and of all its subcommands, so an option
// added later cannot miss it. Header-only (CLI11 is header-only too): the `contactlab` command
// and the tools include it; the util library itself does not depend on CLI11.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "util/error.h"
#include "util/parse_number.h"

namespace contactlab {

// A CLI11 check: the value is a finite number ("'nan' is not a finite number").
inline const CLI::Validator& FiniteNumber() {
  static const CLI::Validator check(
      [](std::string& text) -> std::string {
        if (ParseDouble(text)) return {};
        return "'" + QuoteToken(text) + "' is not a finite number";
      },
      "FINITE", "FiniteNumber");
  return check;
}

// Puts FiniteNumber first among the checks of every option of APP and its subcommands whose
// values are floating-point numbers (CLI11 type FLOAT, also for std::vector and std::optional of
// them). Call once every option was added, before parsing.
inline void RequireFiniteNumbers(CLI::App& app) {
  for (CLI::Option* option : app.get_options()) {
    if (option->get_type_name().rfind("FLOAT", 0) == 0) option->transform(FiniteNumber());
  }
  for (CLI::App* sub : app.get_subcommands({})) RequireFiniteNumbers(*sub);
}

}  // namespace contactlab
