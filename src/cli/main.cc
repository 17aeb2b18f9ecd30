// The `contactlab` command: subcommands registered by cli/*_commands.cc.
#include <exception>
#include <iostream>

#include "contact/register_contact_models.h"
#include "cli/command_registry.h"
#include "util/error.h"
#include "util/input_files.h"
#include "util/temporary_files.h"

int main(int argc, char** argv) {
  // SIGINT, SIGTERM, SIGHUP or SIGQUIT while an output is being written removes its temporary.
  contactlab::InstallTemporaryFileCleanupOnSignals();
  // Every file the command reads is recorded, and no output of it may replace one.
  const contactlab::InputFileRecord inputs;
  contactlab::RegisterContactModels();
  const std::unique_ptr<CLI::App> app = contactlab::cli::MakeCommandLineApp();
  try {
    app->parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app->exit(e);
  } catch (const contactlab::Error& e) {
    std::cerr << "contactlab: error: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "contactlab: internal error: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
