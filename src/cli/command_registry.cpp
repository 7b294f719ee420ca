#include "cli/command_registry.hpp"

#include <utility>

namespace cli {

std::vector<Command>& command_registry() {
  // Function-local static: safe to use from other translation units' static initializers.
  static std::vector<Command> commands;
  return commands;
}

CommandRegistration::CommandRegistration(std::string name, std::string summary, CommandFn run) {
  command_registry().push_back({std::move(name), std::move(summary), std::move(run)});
}

}  // namespace cli
