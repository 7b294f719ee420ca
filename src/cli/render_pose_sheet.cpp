// The pose benchmark's contact sheet (cli/pose_sheet.hpp): each cell drawn by the headless
// renderer, framed on the posed (left) joint, labelled with a small bitmap font of our own so
// that no image tool is needed. Built only with the renderer; registers itself at start-up.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli/pose_sheet.hpp"
#include "render/camera.hpp"
#include "render/headless_context.hpp"
#include "render/png_writer.hpp"
#include "spaces/body_scene.hpp"

namespace {

// 5 x 7 glyphs, '#' = ink: lower-case letters (upper case is drawn as lower case), digits and
// the punctuation the labels use.
struct Glyph {
  char c;
  const char* rows[7];
};

const Glyph kGlyphs[] = {
    {'a', {".....", ".....", ".###.", "....#", ".####", "#...#", ".####"}},
    {'b', {"#....", "#....", "#.##.", "##..#", "#...#", "#...#", "####."}},
    {'c', {".....", ".....", ".###.", "#....", "#....", "#...#", ".###."}},
    {'d', {"....#", "....#", ".##.#", "#..##", "#...#", "#...#", ".####"}},
    {'e', {".....", ".....", ".###.", "#...#", "#####", "#....", ".###."}},
    {'f', {"..##.", ".#..#", ".#...", "###..", ".#...", ".#...", ".#..."}},
    {'g', {".....", ".####", "#...#", "#...#", ".####", "....#", ".###."}},
    {'h', {"#....", "#....", "#.##.", "##..#", "#...#", "#...#", "#...#"}},
    {'i', {"..#..", ".....", ".##..", "..#..", "..#..", "..#..", ".###."}},
    {'j', {"...#.", ".....", "..##.", "...#.", "...#.", "#..#.", ".##.."}},
    {'k', {"#....", "#....", "#..#.", "#.#..", "##...", "#.#..", "#..#."}},
    {'l', {".##..", "..#..", "..#..", "..#..", "..#..", "..#..", ".###."}},
    {'m', {".....", ".....", "##.#.", "#.#.#", "#.#.#", "#...#", "#...#"}},
    {'n', {".....", ".....", "#.##.", "##..#", "#...#", "#...#", "#...#"}},
    {'o', {".....", ".....", ".###.", "#...#", "#...#", "#...#", ".###."}},
    {'p', {".....", "####.", "#...#", "#...#", "####.", "#....", "#...."}},
    {'q', {".....", ".####", "#...#", "#...#", ".####", "....#", "....#"}},
    {'r', {".....", ".....", "#.##.", "##..#", "#....", "#....", "#...."}},
    {'s', {".....", ".....", ".####", "#....", ".###.", "....#", "####."}},
    {'t', {".#...", ".#...", "###..", ".#...", ".#...", ".#..#", "..##."}},
    {'u', {".....", ".....", "#...#", "#...#", "#...#", "#..##", ".##.#"}},
    {'v', {".....", ".....", "#...#", "#...#", "#...#", ".#.#.", "..#.."}},
    {'w', {".....", ".....", "#...#", "#...#", "#.#.#", "#.#.#", ".#.#."}},
    {'x', {".....", ".....", "#...#", ".#.#.", "..#..", ".#.#.", "#...#"}},
    {'y', {".....", "#...#", "#...#", "#...#", ".####", "....#", ".###."}},
    {'z', {".....", ".....", "#####", "...#.", "..#..", ".#...", "#####"}},
    {'0', {".###.", "#...#", "#..##", "#.#.#", "##..#", "#...#", ".###."}},
    {'1', {"..#..", ".##..", "..#..", "..#..", "..#..", "..#..", ".###."}},
    {'2', {".###.", "#...#", "....#", "...#.", "..#..", ".#...", "#####"}},
    {'3', {"#####", "...#.", "..#..", "...#.", "....#", "#...#", ".###."}},
    {'4', {"...#.", "..##.", ".#.#.", "#..#.", "#####", "...#.", "...#."}},
    {'5', {"#####", "#....", "####.", "....#", "....#", "#...#", ".###."}},
    {'6', {"..##.", ".#...", "#....", "####.", "#...#", "#...#", ".###."}},
    {'7', {"#####", "....#", "...#.", "..#..", ".#...", ".#...", ".#..."}},
    {'8', {".###.", "#...#", "#...#", ".###.", "#...#", "#...#", ".###."}},
    {'9', {".###.", "#...#", "#...#", ".####", "....#", "...#.", ".##.."}},
    {' ', {".....", ".....", ".....", ".....", ".....", ".....", "....."}},
    {'-', {".....", ".....", ".....", "#####", ".....", ".....", "....."}},
    {'+', {".....", "..#..", "..#..", "#####", "..#..", "..#..", "....."}},
    {'.', {".....", ".....", ".....", ".....", ".....", ".##..", ".##.."}},
    {',', {".....", ".....", ".....", ".....", ".##..", "..#..", ".#..."}},
    {'%', {"##...", "##..#", "...#.", "..#..", ".#...", "#..##", "...##"}},
    {':', {".....", ".##..", ".##..", ".....", ".##..", ".##..", "....."}},
    {'(', {"...#.", "..#..", ".#...", ".#...", ".#...", "..#..", "...#."}},
    {')', {".#...", "..#..", "...#.", "...#.", "...#.", "..#..", ".#..."}},
    {'/', {".....", "....#", "...#.", "..#..", ".#...", "#....", "....."}},
    {'_', {".....", ".....", ".....", ".....", ".....", ".....", "#####"}},
    {'=', {".....", ".....", "#####", ".....", "#####", ".....", "....."}},
    {'?', {".###.", "#...#", "....#", "...#.", "..#..", ".....", "..#.."}},
};

const Glyph& glyph(char c) {
  if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  for (const Glyph& g : kGlyphs) {
    if (g.c == c) return g;
  }
  return kGlyphs[sizeof kGlyphs / sizeof kGlyphs[0] - 1];  // '?'
}

constexpr int kScale = 2;                // glyph pixels per font pixel
constexpr int kAdvance = 6 * kScale;     // 5 columns and a gap
constexpr int kLineHeight = 9 * kScale;  // 7 rows and a gap

// An RGBA8 image, top row first.
struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> px;
  Image(int w, int h) : width(w), height(h), px(std::size_t(w) * h * 4, 255) {}
  void set(int x, int y, std::uint8_t v) {
    if (x < 0 || y < 0 || x >= width || y >= height) return;
    std::uint8_t* p = &px[(std::size_t(y) * width + x) * 4];
    p[0] = p[1] = p[2] = v;
    p[3] = 255;
  }
};

// Draws `text` with its top-left corner at (x, y), clipped to `max_width` pixels.
void draw_text(Image& img, int x, int y, const std::string& text, int max_width) {
  for (std::size_t i = 0; i < text.size(); ++i) {
    const int gx = x + static_cast<int>(i) * kAdvance;
    if (gx + 5 * kScale > x + max_width) break;
    const Glyph& g = glyph(text[i]);
    for (int r = 0; r < 7; ++r) {
      for (int c = 0; c < 5; ++c) {
        if (g.rows[r][c] != '#') continue;
        for (int dy = 0; dy < kScale; ++dy) {
          for (int dx = 0; dx < kScale; ++dx)
            img.set(gx + c * kScale + dx, y + r * kScale + dy, 20);
        }
      }
    }
  }
}

// Where a cell looks: at the middle of two posed joints (the measured joint and the next one
// along the limb), from a direction and distance that show the bend: front for the abductions
// and the head, from the front-left for flexions, close for the hand.
struct Framing {
  const char* pose;
  const char* joint_a;
  const char* joint_b;
  float yaw, pitch, distance;
};

const Framing kFramings[] = {
    {"shoulder-abduct-80", "left_shoulder", "left_elbow", 15.0f, 5.0f, 1.5f},
    {"shoulder-abduct-170", "left_shoulder", "left_elbow", 15.0f, 5.0f, 1.5f},
    {"shoulder-abduct-80-from-t", "left_shoulder", "left_elbow", 15.0f, 5.0f, 1.5f},
    {"shoulder-abduct-170-from-t", "left_shoulder", "left_elbow", 15.0f, 5.0f, 1.5f},
    {"shoulder-flex-90", "left_shoulder", "left_elbow", 55.0f, 10.0f, 1.5f},
    {"elbow-130", "left_elbow", "left_elbow", 60.0f, 5.0f, 1.1f},
    {"forearm-twist-90", "left_elbow", "left_wrist", 35.0f, 5.0f, 1.1f},
    {"wrist-flex-60", "left_wrist", "left_wrist", 50.0f, 5.0f, 0.7f},
    {"hip-flex-90", "left_hip", "left_knee", 65.0f, 10.0f, 1.7f},
    {"knee-130", "left_knee", "left_knee", 80.0f, 5.0f, 1.5f},
    {"head-turn-60", "head", "head", 0.0f, 5.0f, 0.9f},
    {"fist", "left_wrist", "left_middle1", 50.0f, 15.0f, 0.45f},
};

int find_joint(const body::Model& model, const std::string& name) {
  for (std::size_t j = 0; j < model.joint_names.size(); ++j) {
    if (model.joint_names[j] == name) return static_cast<int>(j);
  }
  return -1;
}

render::Camera framing(const body::Model& model, const cli::PoseSheetCell& cell) {
  render::Camera camera;
  camera.set_preset(render::ViewPreset::kThreeQuarter);
  for (const Framing& f : kFramings) {
    if (cell.pose != f.pose) continue;
    const int a = find_joint(model, f.joint_a), b = find_joint(model, f.joint_b);
    if (a < 0 || b < 0 || cell.mesh.joints.rows() <= std::max(a, b)) break;
    const Eigen::Vector3f t = 0.5f * (cell.mesh.joints.row(a) + cell.mesh.joints.row(b));
    camera.target = glm::vec3(t.x(), t.y(), t.z());
    camera.yaw_degrees = f.yaw;
    camera.pitch_degrees = f.pitch;
    camera.distance = f.distance;
  }
  return camera;
}

void write_sheet(const std::filesystem::path& path, const std::vector<cli::PoseSheetBlock>& blocks,
                 int cell_px) {
  constexpr int kColumns = 4, kGap = 4, kLabelLines = 2;
  const int label_h = kLabelLines * kLineHeight + 6;
  const int title_h = kLineHeight + 10;
  const int cell_h = cell_px + label_h;
  int height = kGap;
  for (const auto& b : blocks) {
    const int rows = (static_cast<int>(b.cells.size()) + kColumns - 1) / kColumns;
    height += title_h + rows * (cell_h + kGap);
  }
  const int width = kGap + kColumns * (cell_px + kGap);
  Image sheet(width, height);
  render::HeadlessContext context;
  int y0 = kGap;
  for (const auto& block : blocks) {
    draw_text(sheet, kGap + 2, y0 + 4, block.title, width - 2 * kGap);
    y0 += title_h;
    for (std::size_t i = 0; i < block.cells.size(); ++i) {
      const cli::PoseSheetCell& cell = block.cells[i];
      const int x = kGap + static_cast<int>(i % kColumns) * (cell_px + kGap);
      const int y = y0 + static_cast<int>(i / kColumns) * (cell_h + kGap);
      if (cell.available) {
        const std::vector<std::uint8_t> pixels = spaces::render_body_image(
            *block.model, cell.mesh, framing(*block.model, cell), cell_px, cell_px, 4);
        // The framebuffer's rows come bottom first.
        for (int r = 0; r < cell_px; ++r) {
          std::memcpy(&sheet.px[(std::size_t(y + r) * width + x) * 4],
                      &pixels[std::size_t(cell_px - 1 - r) * cell_px * 4],
                      std::size_t(cell_px) * 4);
        }
      } else {
        for (int r = 0; r < cell_px; ++r) {
          for (int c = 0; c < cell_px; ++c) sheet.set(x + c, y + r, 200);
        }
      }
      for (std::size_t l = 0; l < cell.label.size() && l < kLabelLines; ++l) {
        draw_text(sheet, x + 2, y + cell_px + 4 + static_cast<int>(l) * kLineHeight, cell.label[l],
                  cell_px - 4);
      }
    }
    y0 += (static_cast<int>(block.cells.size()) + kColumns - 1) / kColumns * (cell_h + kGap);
  }
  render::write_png(path, width, height, sheet.px, false);
}

const bool registered = (cli::pose_sheet_writer() = &write_sheet, true);

}  // namespace
