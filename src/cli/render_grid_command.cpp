// `render-grid`: the first plane's grid of a new search, headless (EGL surfaceless), drawn by
// the same cell code as the window (app::CellView and the design space's cell content).
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>

#include "app/cell_view.hpp"
#include "app/session.hpp"
#include "app/session_perception.hpp"
#include "cli/arg_parser.hpp"
#include "cli/command_registry.hpp"
#include "cli/gallery_display_options.hpp"
#include "render/headless_context.hpp"
#include "render/png_writer.hpp"
#include "spaces/space_factory.hpp"
#include "util/atomic_file.hpp"

namespace {

const char* const kUsage =
    "usage: sequential-gallery render-grid [--space body|photo] [--model FILE.npz|--image FILE]\n"
    "                                      [--grid 3|5] [--seed S] [--components K]\n"
    "                                      [--cell PX] [--samples N]\n"
    "                                      [--framing close-ups|whole-body]\n"
    "                                      [--target NAME=VALUE ...] [--hold NAME[=VALUE] ...]\n"
    "                                      [--cells-dir DIR] [--cells-csv FILE] -o GRID.png\n"
    "Renders the grid of the first plane of a new search (seed S) as the window draws it.\n"
    "Bodies: --target (e.g. height=1.80 mass=85) starts the search at the nearest body that\n"
    "meets it (the first plane is then the one proposed from there); --hold keeps a\n"
    "measurement fixed in every cell (a bare name holds the start body's value).\n"
    "--framing: bodies framed on where the grid's cells differ (close-ups, the window's\n"
    "default) or whole.\n"
    "--cells-dir also writes each cell as DIR/cell_<row>_<col>.png; --cells-csv writes each\n"
    "cell's x (and, for bodies, its measurements in metres) and how far it looks from the\n"
    "nearest other cell (nearest_cell: the window's look-alike measure, mm for bodies).\n";

int run(int argc, char** argv) {
  cli::ArgParser args(argc, argv, {"help"});
  if (args.has("help")) {
    std::cout << kUsage;
    return 0;
  }
  args.reject_unknown({"help", "space", "model", "image", "grid", "seed", "components", "cell",
                       "samples", "cells-dir", "cells-csv", "o", "output", "target", "hold",
                       "framing"});
  const std::string framing = args.get_or("framing", "close-ups");
  if (framing != "close-ups" && framing != "whole-body") {
    throw cli::ArgError("render-grid: --framing is close-ups or whole-body, not '" + framing + "'");
  }
  const auto out = args.get("o") ? args.get("o") : args.get("output");
  if (!out) throw cli::ArgError("render-grid: -o GRID.png is required\n" + std::string(kUsage));
  for (const char* option : {"o", "output", "cells-dir", "cells-csv"}) {
    if (const auto value = args.get(option); value && value->empty()) {
      const std::string name = option;
      throw cli::ArgError("render-grid: " + std::string(name.size() == 1 ? "-" : "--") + name +
                          " is empty; give a " + (name == "cells-dir" ? "folder" : "file") +
                          " name");
    }
  }
  std::optional<std::string> source;
  const app::SpaceKind& kind = [&]() -> const app::SpaceKind& {
    try {
      return cli::read_space_kind(args, source);
    } catch (const cli::ArgError& e) {
      throw cli::ArgError("render-grid: " + std::string(e.what()));
    }
  }();
  app::SpaceSettings space_settings = spaces::catalogue().default_settings(kind.name);
  space_settings.source = source.value_or("");
  if (!kind.dimensions_fixed) {
    space_settings.dimensions = args.get_int("components", kind.dimensions);
  }
  const int cell = args.get_int("cell", 256);
  if (cell < 32 || cell > 2048) throw cli::ArgError("render-grid: --cell must be 32..2048");
  const int samples = args.get_int("samples", 4);
  if (samples < 0 || samples > 16) throw cli::ArgError("render-grid: --samples must be 0..16");

  render::HeadlessContext context;
  auto space = spaces::open_space(space_settings);
  space->set_close_ups(framing == "close-ups");
  app::SessionSettings settings;
  settings.space = space_settings.kind;
  settings.model_path = space_settings.source;
  settings.components = space->dimensions();
  settings.grid_size = args.get_int("grid", kind.grid_size);
  if (settings.grid_size != 3 && settings.grid_size != 5) {
    throw cli::ArgError("render-grid: --grid must be 3 or 5");
  }
  settings.seed = static_cast<std::uint64_t>(args.get_int("seed", 1));
  app::Session session(settings);
  // As the window does for a new search with cells `cell` pixels high.
  if (const app::SpacePerception* perception = space->perception(); perception != nullptr) {
    app::install_perception(session, *perception, cell, /*perceptual_zoom=*/true);
  }
  if (const auto targets = args.get_all("target"); !targets.empty()) {
    app::TargetSolve solved;
    try {
      solved = app::measurements_to(*space, "aim for")
                   .solve_targets(targets, session.current_best(), args.get_all("hold"));
    } catch (const std::invalid_argument& e) {
      throw cli::ArgError(std::string("render-grid: --target: ") + e.what());
    }
    if (!solved.reached) throw std::runtime_error("render-grid: --target: " + solved.message);
    std::cerr << "target: " << solved.message << "\n";
    // As the window's "Go": the solved body is preferred over the start, and the search
    // continues from it.
    sps::PlaneSearch search = session.search();
    search.submit(solved.x, {}, {}, /*set_directly=*/true);
    session.adopt_point(solved.x, std::move(search));
  }
  if (const auto holds = args.get_all("hold"); !holds.empty()) {
    try {
      session.set_constraint_projector(
          app::measurements_to(*space, "hold").hold_projector(holds, session.current_best()));
    } catch (const std::invalid_argument& e) {
      throw cli::ArgError(std::string("render-grid: --hold: ") + e.what());
    }
    std::cerr << "hold: " << session.constraint_projector()->description() << "\n";
  }
  const auto points = session.cells();
  const int n = settings.grid_size;

  // The window's look: cells on its dark background with its 6-pixel gaps.
  const int gap = 6;
  const int size = n * cell + (n - 1) * gap;
  std::vector<std::uint8_t> grid(static_cast<std::size_t>(size) * size * 4);
  for (std::size_t i = 0; i < grid.size(); i += 4) {
    grid[i] = 15, grid[i + 1] = 15, grid[i + 2] = 15, grid[i + 3] = 255;
  }
  // Front view, as the window starts, framed as the window frames the grid.
  std::vector<Eigen::VectorXd> xs;
  for (const auto& p : points) xs.push_back(p.x);
  const app::SpacePerception* perception = space->perception();
  const app::GridFrame frame =
      perception != nullptr ? perception->grid_frame(xs) : app::GridFrame{};
  const render::Camera camera = render::Camera{}.scaled_about_height(
      static_cast<float>(frame.scale), static_cast<float>(frame.pivot_m));
  app::CellLook look;
  look.camera = space->uses_camera() ? &camera : nullptr;
  // The CSV is built in memory and written with the PNGs, through the atomic writer: a full
  // disk is an error naming the file, never a "wrote" over an empty file.
  const auto csv_path = args.get("cells-csv");
  std::ostringstream csv;
  const bool want_csv = csv_path.has_value();
  // How far each cell looks from its nearest neighbour, as the window's look-alike test
  // measures it (empty for a space without a perceptual distance).
  Eigen::VectorXd nearest_cell;
  if (want_csv) {
    csv << "row,col";
    for (int d = 0; d < space->dimensions(); ++d) csv << ",x" << d + 1;
    if (perception != nullptr) {
      Eigen::MatrixXd apart = perception->perceptual_distance()(xs);
      apart.diagonal().setConstant(std::numeric_limits<double>::infinity());
      nearest_cell = apart.rowwise().minCoeff();
    }
  }
  const auto cells_dir = args.get("cells-dir");
  if (cells_dir) {
    std::error_code ec;
    std::filesystem::create_directories(*cells_dir, ec);
    if (ec || !std::filesystem::is_directory(*cells_dir, ec)) {
      throw std::runtime_error(
          "render-grid: --cells-dir " + *cells_dir + ": cannot create that folder" +
          (ec ? " (" + ec.message() + ")" : std::string(" (a file is there)")));
    }
  }
  for (int row = 0; row < n; ++row) {
    for (int col = 0; col < n; ++col) {
      const auto& point = points[static_cast<std::size_t>(row * n + col)];
      app::CellView view;
      view.set_point(*space, point.x, want_csv);
      view.draw(look, 0, cell, cell, samples);
      const auto pixels = view.fbo.read_pixels();  // bottom row first
      for (int y = 0; y < cell; ++y) {
        const auto* src = &pixels[static_cast<std::size_t>(cell - 1 - y) * cell * 4];
        auto* dst = &grid[(static_cast<std::size_t>(row * (cell + gap) + y) * size +
                           static_cast<std::size_t>(col * (cell + gap))) *
                          4];
        std::copy(src, src + static_cast<std::size_t>(cell) * 4, dst);
      }
      if (cells_dir) {
        render::write_png(std::filesystem::path(*cells_dir) /
                              ("cell_" + std::to_string(row) + "_" + std::to_string(col) + ".png"),
                          cell, cell, pixels);
      }
      if (want_csv) {
        const auto numbers = space->numbers(*view.prepared);
        if (row == 0 && col == 0) {
          for (const auto& [name, value] : numbers) csv << "," << name;
          if (nearest_cell.size() > 0) csv << ",nearest_cell";
          csv << "\n";
        }
        csv << row << "," << col << std::setprecision(9);
        for (int d = 0; d < point.x.size(); ++d) csv << "," << point.x[d];
        for (const auto& [name, value] : numbers) csv << "," << value;
        if (nearest_cell.size() > 0) csv << "," << nearest_cell(row * n + col);
        csv << "\n";
      }
    }
  }
  if (want_csv) util::write_file_atomically(*csv_path, csv.str());
  render::write_png(*out, size, size, grid, false);
  std::cout << "wrote " << *out << " (" << n << "x" << n << " cells of " << cell << " px, "
            << space->description() << ", seed " << settings.seed << ", " << context.renderer()
            << ")\n";
  return 0;
}

const cli::CommandRegistration reg{
    "render-grid", "render the first plane's grid to a PNG headless (no window)", &run};

}  // namespace
