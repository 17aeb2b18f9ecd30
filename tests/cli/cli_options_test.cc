// The `contactlab` command line as a whole: every floating-point option of every subcommand
// refuses NaN and infinities when the command line is parsed, before any command runs.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <string>
#include <vector>

#include "cli/command_registry.h"

namespace contactlab {
namespace {

// One floating-point option: its subcommand, its long name and how many values it takes.
struct FloatOption {
  std::string command, name;
  int values = 1;
};

// Every option of every subcommand whose values CLI11 reads as floating-point numbers.
std::vector<FloatOption> FloatOptions() {
  const auto app = cli::MakeCommandLineApp();
  std::vector<FloatOption> found;
  for (CLI::App* sub : app->get_subcommands({})) {
    for (const CLI::Option* option : sub->get_options()) {
      if (option->get_type_name().rfind("FLOAT", 0) != 0 || option->get_lnames().empty()) continue;
      found.push_back({sub->get_name(), "--" + option->get_lnames().front(), std::max(1, option->get_expected_min())});
    }
  }
  return found;
}

// Thrown once a subcommand's options are parsed and checked, in place of running the command.
struct ParsedWithoutRunning {};

// Parses `contactlab COMMAND NAME VALUE 1 1 ...` (VALUE first of the option's values; NAME=VALUE
// when VALUE starts with '-', which would otherwise read as an option) and stops before the command
// runs; returns the CLI11 error's kind and message ("" when none). The command's own action stays
// in place: it holds the variables its options write into, so replacing it would free them.
std::string ParseError(const FloatOption& option, const std::string& value, std::string* kind) {
  const auto app = cli::MakeCommandLineApp();
  for (CLI::App* sub : app->get_subcommands({})) sub->parse_complete_callback([] { throw ParsedWithoutRunning{}; });
  std::vector<std::string> args = {"contactlab", option.command};
  if (value[0] == '-') {
    args.push_back(option.name + "=" + value);
  } else {
    args.insert(args.end(), {option.name, value});
  }
  for (int k = 1; k < option.values; ++k) args.push_back("1");
  std::vector<const char*> argv;
  for (const std::string& a : args) argv.push_back(a.c_str());
  try {
    app->parse(int(argv.size()), argv.data());
  } catch (const CLI::ParseError& e) {
    *kind = e.get_name();
    return e.what();
  } catch (const ParsedWithoutRunning&) {
  }
  *kind = "";
  return "";
}

// CLI11 reads "nan" and "inf" as numbers and its range checks let NaN through (every comparison
// with NaN is false): `session --duration nan` ran forever and `--k-vc nan` or `--touch nan` fell
// back to the defaults without a word. Every floating-point option of every subcommand now refuses
// them, naming the option, as a validation error before any command runs.
TEST(CliOptions, NoFloatingPointOptionOfAnySubcommandAcceptsNanOrInfinity) {
  const std::vector<FloatOption> options = FloatOptions();
  // The walk sees the options of the report and the others of their kind (one of several values,
  // an optional one).
  std::set<std::string> seen;
  for (const FloatOption& o : options) seen.insert(o.command + " " + o.name);
  for (const char* expected : {"session --duration", "session --k-vc", "session --touch", "reduce --E", "reduce --nu",
                               "reduce --fix-box", "reduce-export --scale", "sdf --padding", "pointshell --offset",
                               "mesh-info --scale"}) {
    EXPECT_EQ(seen.count(expected), 1u) << expected << " was not found among the floating-point options";
  }
  for (const FloatOption& o : options) {
    for (const std::string bad : {"nan", "NaN", "-nan", "inf", "-inf", "infinity", "1e999", "-1e999"}) {
      if (bad[0] == '-' && o.values > 1) continue;  // NAME=VALUE gives one value only
      std::string kind;
      const std::string message = ParseError(o, bad, &kind);
      EXPECT_EQ(kind, "ValidationError") << o.command << " " << o.name << " " << bad << ": " << message;
      EXPECT_NE(message.find(o.name), std::string::npos) << message;
      EXPECT_NE(message.find("is not a finite number"), std::string::npos) << message;
    }
    // A finite value passes this check (it may still be refused by the option's own range).
    std::string kind;
    EXPECT_EQ(ParseError(o, "0.25", &kind).find("is not a finite number"), std::string::npos) << o.command << " " << o.name;
  }
}

}  // namespace
}  // namespace contactlab
