// `session-info FILE`: loads a session file exactly as the window does (the same parser and
// checks, then its body model with the session's component count) and prints what it holds,
// or why it is unusable. Never moves or changes the file.
#include <iostream>
#include <string>

#include "app/session_store.hpp"
#include "body/model_loader.hpp"
#include "cli/arg_parser.hpp"
#include "cli/command_registry.hpp"

namespace {

const char* const kUsage =
    "usage: sequential-gallery session-info FILE\n\n"
    "Loads a session file as the window does and prints what it holds (model, components,\n"
    "grid, planes, clicks, file version). Exit code 0 if the window could resume it, 1 if not\n"
    "(the reason is printed). The file is only read.\n";

int run(int argc, char** argv) {
  const cli::ArgParser args(argc, argv, {});
  if (args.has("help")) {
    std::cout << kUsage;
    return 0;
  }
  args.reject_unknown({});
  if (args.positional().size() != 1) {
    throw cli::ArgError("session-info needs exactly one session file\n" + std::string(kUsage));
  }
  const std::string path = args.positional().front();
  std::optional<app::Session> session;
  try {
    session = app::read_session_file(path);
  } catch (const std::exception& e) {
    std::cout << "file: " << path << "\nusable: no: " << e.what() << "\n";
    return 1;
  }
  const auto& s = session->settings();
  const auto& search = session->search();
  std::cout << "file: " << path << "\n"
            << "version: 1\n"
            << "model: " << (s.model_path.empty() ? "(embedded default model)" : s.model_path)
            << "\n"
            << "components: " << s.components << "\n"
            << "grid: " << s.grid_size << "x" << s.grid_size << ", " << s.zoom_levels
            << " clicks per plane\n"
            << "planes: " << session->planes_done() << " finished\n"
            << "clicks on this plane: " << session->clicks_on_plane()
            << (session->submission_pending() ? " (waiting for the optimizer)" : "") << "\n"
            << "preference data: " << search.data().point_count() << " points, "
            << search.data().preference_count() << " preferences\n"
            << "seed: " << s.seed << "\n";
  // The window resumes a session only with its model at the same component count.
  try {
    const body::Model model = s.model_path.empty() ? body::load_default_model(s.components)
                                                   : body::load_model(s.model_path, s.components);
    if (model.component_count() != s.components) {
      throw std::runtime_error("the model has " + std::to_string(model.component_count()) +
                               " components, the session " + std::to_string(s.components));
    }
    std::cout << "model check: " << model.name << ", " << model.total_components
              << " components in the file\n";
  } catch (const std::exception& e) {
    std::cout << "usable: no: " << path << ": cannot load its body model: " << e.what() << "\n";
    return 1;
  }
  std::cout << "usable: yes\n";
  return 0;
}

const cli::CommandRegistration reg{"session-info",
                                   "print what a session file holds, or why it is unusable", &run};

}  // namespace
