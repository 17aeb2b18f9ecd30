// Subcommands of the `contactlab` program register themselves here: each cli/*_commands.cc
// defines a static CommandRegistration that adds its subcommands to the app.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <memory>
#include <vector>

namespace contactlab::cli {

using CommandAdder = std::function<void(CLI::App&)>;

std::vector<CommandAdder>& CommandRegistry();

struct CommandRegistration {
  explicit CommandRegistration(CommandAdder adder) { CommandRegistry().push_back(std::move(adder)); }
};

// The `contactlab` program's command line: every registered subcommand, with every
// floating-point option of every subcommand refusing NaN and infinities (util/finite_options.h).
std::unique_ptr<CLI::App> MakeCommandLineApp();

}  // namespace contactlab::cli
