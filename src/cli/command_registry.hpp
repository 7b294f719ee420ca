// Subcommands of the one executable register themselves here, so adding a command means
// adding one file under src/cli/ and nothing else.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace cli {

// argv[0] is the subcommand name; the function returns the process exit code.
using CommandFn = std::function<int(int argc, char** argv)>;

struct Command {
  std::string name;
  std::string summary;  // one line for the top-level --help
  CommandFn run;
};

std::vector<Command>& command_registry();

// A file-scope `static const cli::CommandRegistration reg{...};` adds a command at start-up.
struct CommandRegistration {
  CommandRegistration(std::string name, std::string summary, CommandFn run);
};

}  // namespace cli
