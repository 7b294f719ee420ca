// Entry point: `sequential-gallery [command] [options]`. Without a command the GUI starts
// (the `gallery` command) when it is built in; otherwise the help is printed.
#include <algorithm>
#include <cstring>
#include <exception>
#include <iostream>
#include <new>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli/command_registry.hpp"

namespace {

void print_help(std::ostream& out) {
  auto commands = cli::command_registry();
  std::sort(commands.begin(), commands.end(),
            [](const cli::Command& a, const cli::Command& b) { return a.name < b.name; });
  out << "Sequential Gallery for body shapes\n\n"
         "usage: sequential-gallery [command] [options]\n"
         "       sequential-gallery <command> --help\n\n"
         "commands:\n";
  for (const auto& c : commands) {
    out << "  " << c.name << std::string(c.name.size() < 12 ? 12 - c.name.size() : 1, ' ')
        << c.summary << "\n";
  }
}

const cli::Command* find_command(const std::string& name) {
  const auto& commands = cli::command_registry();
  const auto it = std::find_if(commands.begin(), commands.end(),
                               [&](const cli::Command& c) { return c.name == name; });
  return it == commands.end() ? nullptr : &*it;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    if (argc >= 2 && (std::strcmp(argv[1], "--help") == 0 || std::strcmp(argv[1], "-h") == 0 ||
                      std::strcmp(argv[1], "help") == 0)) {
      print_help(std::cout);
      return 0;
    }
    // No command, or only options: the GUI, which takes the options itself.
    if (argc < 2 || argv[1][0] == '-') {
      if (const auto* gui = find_command("gallery")) {
        char name[] = "gallery";
        std::vector<char*> args{name};
        for (int i = 1; i < argc; ++i) args.push_back(argv[i]);
        return gui->run(static_cast<int>(args.size()), args.data());
      }
      print_help(std::cerr);
      return 2;
    }
    const auto* command = find_command(argv[1]);
    if (command == nullptr) {
      std::cerr << "sequential-gallery: unknown command '" << argv[1] << "'\n\n";
      print_help(std::cerr);
      return 2;
    }
    return command->run(argc - 1, argv + 1);
  } catch (const std::bad_alloc&) {
    std::cerr << "sequential-gallery: error: out of memory (is an input file absurdly large?)\n";
    return 1;
  } catch (const std::logic_error& e) {
    // length_error, out_of_range, ...: a library or programming error that escaped the checks
    // that should have caught it; still a message and an exit code, never an abort.
    std::cerr << "sequential-gallery: internal error: " << e.what()
              << " (this is a bug; please report it with the command line)\n";
    return 1;
  } catch (const std::exception& e) {
    const std::string what = e.what();
    if (what.rfind("[json.exception.", 0) == 0) {
      // nlohmann::json's own message: an input that the checks before it should have caught.
      std::cerr << "sequential-gallery: internal error: unexpected JSON library error: " << what
                << " (this is a bug; please report it with the command line)\n";
    } else {
      std::cerr << "sequential-gallery: error: " << what << "\n";
    }
    return 1;
  }
}
