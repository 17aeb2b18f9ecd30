// Subcommands of the `contactlab` program register themselves here: each cli/*_commands.cc
// defines a static CommandRegistration that adds its subcommands to the app.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <vector>

namespace contactlab::cli {

using CommandAdder = std::function<void(CLI::App&)>;

std::vector<CommandAdder>& CommandRegistry();

struct CommandRegistration {
  explicit CommandRegistration(CommandAdder adder) { CommandRegistry().push_back(std::move(adder)); }
};

}  // namespace contactlab::cli
