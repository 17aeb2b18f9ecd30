// The `contactlab` command: subcommands registered by cli/*_commands.cc.
#include <exception>
#include <iostream>

#include "contact/register_contact_models.h"
#include "cli/command_registry.h"
#include "util/error.h"
#include "util/input_files.h"
#include "util/temporary_files.h"

namespace contactlab::cli {

std::vector<CommandAdder>& CommandRegistry() {
  static std::vector<CommandAdder> registry;
  return registry;
}

}  // namespace contactlab::cli

int main(int argc, char** argv) {
  // SIGINT, SIGTERM, SIGHUP or SIGQUIT while an output is being written removes its temporary.
  contactlab::InstallTemporaryFileCleanupOnSignals();
  // Every file the command reads is recorded, and no output of it may replace one.
  const contactlab::InputFileRecord inputs;
  contactlab::RegisterContactModels();
  CLI::App app{"ContactLab: a testbed for 6-DoF haptic contact (Barbič & James 2008 and baselines)"};
  app.set_version_flag("--version", std::string("contactlab ") + CONTACTLAB_VERSION);
  app.require_subcommand(1);
  for (const auto& add : contactlab::cli::CommandRegistry()) add(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const contactlab::Error& e) {
    std::cerr << "contactlab: error: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "contactlab: internal error: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
