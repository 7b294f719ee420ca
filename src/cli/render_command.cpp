// `render`: one body to a PNG without any window (EGL surfaceless through Mesa), drawn exactly
// as a grid cell of the viewer draws it.
#include <cmath>
#include <iostream>
#include <stdexcept>
#include <string>

#include "body/mesh_normals.hpp"
#include "body/model_loader.hpp"
#include "body/pose_library.hpp"
#include "body/posing.hpp"
#include "cli/arg_parser.hpp"
#include "cli/body_cli_common.hpp"
#include "cli/command_registry.hpp"
#include "render/headless_context.hpp"
#include "render/png_writer.hpp"
#include "spaces/body_scene.hpp"

namespace {

const char* const kUsage =
    "usage: sequential-gallery render [--model female|male|neutral|FILE.npz] [--betas B1 B2 ...] "
    "-o OUT.png\n"
    "                                 [--size WxH] [--view front|side|three-quarter]\n"
    "                                 [--components K] [--samples N] [--rest-pose a|t]\n"
    "                                 [--target X Y Z] [--distance M] [--yaw DEG] [--pitch DEG]\n"
    "                                 [--pose NAME]\n"
    "Renders one body headless (EGL surfaceless, Mesa) exactly like a viewer grid cell.\n"
    "Without --model the built-in neutral body model is used; betas default to 0 (mean body).\n"
    "--rest-pose t shows the body in the T-pose that `export --rest-pose t` writes.\n"
    "--target (metres, feet on y = 0), --distance, --yaw and --pitch move the camera from the\n"
    "grid cell's framing, e.g. for close-ups of the head, a hand or a knee.\n"
    "--pose NAME poses the body in a test pose of the pose benchmark (bench-pose), by the\n"
    "model's own skinning; the -from-t poses start from the T-pose themselves. The poses:\n"
    "  ";

int run(int argc, char** argv_in) {
  std::vector<std::string> store;  // "-o" spelled "--output" so that --betas 1 -2 -o x.png works
  auto argv = cli::normalize_output_flag(argc, argv_in, store);
  cli::ArgParser args(argc, argv.data(), {"help"}, {"betas", "target"});
  if (args.has("help")) {
    std::cout << kUsage << body::pose_names() << "\n";
    return 0;
  }
  args.reject_unknown({"help", "model", "betas", "o", "output", "size", "view", "components",
                       "samples", "rest-pose", "target", "distance", "yaw", "pitch", "pose"});
  const auto out = args.get("o") ? *args.get("o") : args.get("output");
  if (!out) throw cli::ArgError("render: -o OUT.png is required\n" + std::string(kUsage));
  cli::require_output_file(*out);
  int width = 400, height = 400;
  if (const auto size = args.get("size")) {
    char x = 0;
    if (std::sscanf(size->c_str(), "%d%c%d", &width, &x, &height) != 3 || (x != 'x' && x != 'X') ||
        width < 16 || height < 16 || width > 8192 || height > 8192) {
      throw cli::ArgError("render: --size must look like 400x600 (16..8192), got '" + *size + "'");
    }
  }
  render::Camera camera;
  const std::string view_name = args.get_or("view", "front");
  const auto preset = render::parse_view_preset(view_name);
  if (!preset) {
    throw cli::ArgError("render: --view must be front, side or three-quarter, got '" + view_name +
                        "'");
  }
  camera.set_preset(*preset);
  if (args.has("target")) {
    const auto t = args.get_doubles("target");
    if (t.size() != 3) throw cli::ArgError("render: --target needs three numbers X Y Z (metres)");
    camera.target = glm::vec3(float(t[0]), float(t[1]), float(t[2]));
  }
  camera.distance = static_cast<float>(args.get_double("distance", camera.distance));
  if (!(camera.distance > 0.05f && camera.distance < 100.0f))
    throw cli::ArgError("render: --distance must be between 0.05 and 100 metres");
  camera.yaw_degrees = static_cast<float>(args.get_double("yaw", camera.yaw_degrees));
  camera.pitch_degrees = static_cast<float>(args.get_double("pitch", camera.pitch_degrees));
  if (!(std::abs(camera.pitch_degrees) <= 89.0f))
    throw cli::ArgError("render: --pitch must be within -89..89 degrees");

  const int components = args.get_int("components", 0);
  body::Model model = body::resolve_model(args.get_or("model", ""), components);
  cli::check_component_count(args, model);
  const std::string pose_name = args.get_or("pose", "");
  const body::PoseDefinition* test_pose = nullptr;
  if (!pose_name.empty()) {
    test_pose = body::find_pose(pose_name);
    if (!test_pose) {
      throw cli::ArgError("render: unknown --pose '" + pose_name + "'; the poses are " +
                          body::pose_names());
    }
    if (args.has("rest-pose")) {
      throw cli::ArgError(
          "render: --pose and --rest-pose do not go together: a pose starts "
          "from the rest its definition names (the -from-t poses from the T-pose)");
    }
  }
  if (args.get_or("rest-pose", "a") == "t" || test_pose) body::load_pose_correctives(model);
  Eigen::VectorXf betas = Eigen::VectorXf::Zero(model.component_count());
  const Eigen::VectorXf given = cli::read_betas(args, model);
  betas.head(given.size()) = given;

  render::HeadlessContext context;
  auto mesh = spaces::body_from_betas(model, betas);
  const std::string pose = args.get_or("rest-pose", "a");
  if (pose != "a" && pose != "t") {
    throw cli::ArgError("render: --rest-pose must be a or t, got '" + pose + "'");
  }
  if (pose == "t") mesh = body::t_posed(model, mesh);
  if (test_pose) {
    const body::PosedBody posed = body::pose_body(model, mesh, *test_pose);
    if (!posed.available) {
      throw std::runtime_error("render: the model '" + model.name + "' cannot make the pose " +
                               pose_name + ": " + posed.reason);
    }
    mesh.vertices = posed.posed_vertices;
    mesh.joints = posed.posed_joints;
    body::place_on_ground(mesh);
    body::compute_vertex_normals(mesh.vertices, model.faces, mesh.normals);
  }
  const auto pixels =
      spaces::render_body_image(model, mesh, camera, width, height, args.get_int("samples", 4));
  render::write_png(*out, width, height, pixels);
  std::cout << "wrote " << *out << " (" << width << "x" << height << ", " << model.name << ", "
            << (test_pose ? "pose " + pose_name + ", " : std::string())
            << render::view_preset_name(*preset) << " view, " << context.renderer() << ")\n";
  return 0;
}

const cli::CommandRegistration reg{"render", "render one body to a PNG headless (no window)", &run};

}  // namespace
