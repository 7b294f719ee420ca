// `session-info FILE`: loads a session file exactly as the window does (the same parser and
// checks, then its design space with the session's dimensions) and prints what it holds,
// or why it is unusable. Never moves or changes the file.
#include <cstdio>
#include <iostream>
#include <optional>
#include <string>

#include "app/constraint_projector.hpp"
#include "app/session_store.hpp"
#include "cli/arg_parser.hpp"
#include "cli/command_registry.hpp"
#include "spaces/space_factory.hpp"

namespace {

const char* const kUsage =
    "usage: sequential-gallery session-info FILE\n\n"
    "Loads a session file as the window does and prints what it holds (model, components,\n"
    "grid, planes, clicks, holds, the current best and its measurements, file version).\n"
    "Exit code 0 if the window could resume it, 1 if not (the reason is printed). The file\n"
    "is only read.\n";

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
  // A session that names no kind is of the default kind, as the window opens it.
  const std::string kind = s.space.empty() ? spaces::catalogue().default_kind().name : s.space;
  std::cout << "file: " << path << "\n"
            << "version: 1\n"
            << "space: " << kind << "\n"
            << "model: " << (s.model_path.empty() ? "(built-in default)" : s.model_path) << "\n"
            << "components: " << s.components << "\n"
            << "grid: " << s.grid_size << "x" << s.grid_size << ", " << s.zoom_levels
            << " clicks per plane\n"
            << "planes: " << session->planes_done() << " finished\n"
            << "clicks on this plane: " << session->clicks_on_plane()
            << (session->submission_pending() ? " (waiting for the optimizer)" : "") << "\n"
            << "preference data: " << search.data().point_count() << " points, "
            << search.data().preference_count() << " preferences\n"
            << "seed: " << s.seed << "\n"
            << "redo: " << session->redo_depth() << " step"
            << (session->redo_depth() == 1 ? "" : "s")
            << (session->redo_problem().empty() ? ""
                                                : " (unusable: " + session->redo_problem() + ")")
            << "\n";
  // The window resumes a session only if its design space opens (the body model or the
  // photo) with the same number of dimensions.
  try {
    const auto space = spaces::open_space(app::SpaceSettings{kind, s.model_path, s.components});
    if (space->dimensions() != s.components) {
      throw std::runtime_error("the space now has " + std::to_string(space->dimensions()) +
                               " dimensions, the session " + std::to_string(s.components));
    }
    std::cout << "space check: " << space->description() << "\n";
    // The body (or photo edit) the search has reached, as the window shows it.
    const Eigen::VectorXd best = session->current_best();
    std::cout << "current best: x =";
    char value[32];
    for (Eigen::Index i = 0; i < best.size(); ++i) {
      std::snprintf(value, sizeof value, " %.4f", best[i]);
      std::cout << value;
    }
    std::cout << "\n";
    if (const auto prepared = space->prepare(best, true)) {
      const auto numbers = space->numbers(*prepared);
      if (!numbers.empty()) {
        std::cout << "current best measures:";
        for (const auto& [name, number] : numbers) {
          std::snprintf(value, sizeof value, " %s=%.4g", name.c_str(), number);
          std::cout << value;
        }
        std::cout << "\n";
      }
    }
    // The window holds a resumed session's holds again; one it would refuse (an unknown name,
    // a name given twice, a value no body in the range has) makes the session unusable as saved.
    if (!session->saved_holds().empty()) {
      const auto texts = app::hold_texts(session->saved_holds());
      std::string listed;
      for (const auto& t : texts) listed += (listed.empty() ? "" : ", ") + t;
      try {
        const auto projector =
            app::measurements_to(*space, "hold").hold_projector(texts, session->current_best());
        std::cout << "holds: " << (projector ? projector->description() : listed) << "\n";
      } catch (const std::invalid_argument& e) {
        std::cout << "usable: no: " << path << ": its holds (" << listed
                  << ") cannot be held: " << e.what() << "\n";
        return 1;
      }
    }
  } catch (const std::exception& e) {
    std::cout << "usable: no: " << path << ": cannot open its " << kind << " space: " << e.what()
              << "\n";
    return 1;
  }
  std::cout << "usable: yes\n";
  return 0;
}

const cli::CommandRegistration reg{"session-info",
                                   "print what a session file holds, or why it is unusable", &run};

}  // namespace
