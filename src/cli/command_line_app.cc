// The `contactlab` command line: the registered subcommands, none of whose floating-point
// options takes a non-finite value (util/finite_options.h).
#include <string>

#include "cli/command_registry.h"
#include "util/finite_options.h"

namespace contactlab::cli {

std::vector<CommandAdder>& CommandRegistry() {
  static std::vector<CommandAdder> registry;
  return registry;
}

std::unique_ptr<CLI::App> MakeCommandLineApp() {
  auto app = std::make_unique<CLI::App>("ContactLab: a testbed for 6-DoF haptic contact (Barbič & James 2008 and baselines)");
  app->set_version_flag("--version", std::string("contactlab ") + CONTACTLAB_VERSION);
  app->require_subcommand(1);
  for (const auto& add : CommandRegistry()) add(*app);
  RequireFiniteNumbers(*app);
  return app;
}

}  // namespace contactlab::cli
