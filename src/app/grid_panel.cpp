#include "app/grid_panel.hpp"

#include <epoxy/gl.h>
#include <imgui.h>

#include <iostream>

namespace app {

namespace {

void disable_blending(const ImDrawList* /*list*/, const ImDrawCmd* /*cmd*/) {
  glDisable(GL_BLEND);
}

}  // namespace

std::string cell_label(int index, int n) {
  if (n == 3) return std::to_string(index + 1);
  if (index >= 0 && index < 26) return std::string(1, static_cast<char>('A' + index));
  return std::to_string(index + 1);
}

bool GridPanel::draw(PanelContext& ctx, const GalleryLayout& layout,
                     const std::vector<CellView>& cells, const PreparedCell* best,
                     render::Camera& camera, long frame, bool report_layout) {
  GalleryController& c = ctx.c;
  const int n = c.session().settings().grid_size;
  const float shown = layout.cell;
  const float gap = layout.gap;
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const ImVec2 origin(layout.grid.x, layout.grid.y);
  const ImGuiIO& io = ImGui::GetIO();
  hovered_ = -1;
  bool orbited = false;
  const bool busy = c.busy();
  // The second press of a double-click is never a zoom step of its own.
  if (io.MouseClicked[0]) second_of_double_ = io.MouseDoubleClicked[0];
  dragging_ = false;
  for (int row = 0; row < n; ++row) {
    for (int col = 0; col < n; ++col) {
      const int index = row * n + col;
      const ImVec2 p0(origin.x + static_cast<float>(col) * (shown + gap),
                      origin.y + static_cast<float>(row) * (shown + gap));
      const ImVec2 p1(p0.x + shown, p0.y + shown);
      ImGui::SetCursorScreenPos(p0);
      ImGui::PushID(index);
      const bool pressed = ImGui::InvisibleButton("cell", ImVec2(shown, shown));
      const bool hovered = ImGui::IsItemHovered();
      const bool dragging = ImGui::IsItemActive() && ImGui::IsMouseDragging(ImGuiMouseButton_Left);
      ImGui::PopID();
      if (dragging) dragging_ = true;
      if (dragging && c.space().uses_camera() &&
          (io.MouseDelta.x != 0.0f || io.MouseDelta.y != 0.0f)) {
        camera.orbit(io.MouseDelta.x, io.MouseDelta.y);
        orbited = true;
      }
      const float drag_threshold = io.MouseDragThreshold * io.MouseDragThreshold;
      if (pressed && io.MouseDragMaxDistanceSqr[0] < drag_threshold) {
        if (second_of_double_) {
          second_of_double_ = false;
        } else {
          c.queue(intent::ClickCell{col, row});
        }
      }
      if (report_layout && frame == 3) {
        std::cout << "[layout] cell " << index + 1 << " " << p0.x << " " << p0.y << " " << shown
                  << std::endl;
      }
      const CellView* view = static_cast<std::size_t>(index) < cells.size()
                                 ? &cells[static_cast<std::size_t>(index)]
                                 : nullptr;
      if (view != nullptr && view->fbo.texture() != 0) {
        const auto uv = view->uv();
        // Cells are opaque: drawing them without blending saves a software rasterizer
        // reading back every cell's pixels every frame.
        dl->AddCallback(&disable_blending, nullptr);
        dl->AddImage(texture_id(view->fbo.texture()), p0, p1, ImVec2(uv[0], uv[1]),
                     ImVec2(uv[2], uv[3]));
        dl->AddCallback(ImDrawCallback_ResetRenderState, nullptr);
      }
      if (hovered && !busy) {
        hovered_ = index;
        dl->AddRectFilled(p0, p1, IM_COL32(255, 255, 255, 22));
        dl->AddRect(p0, p1, IM_COL32(255, 190, 60, 255), 0.0f, 0, 4.0f);
      } else {
        dl->AddRect(p0, p1, IM_COL32(40, 40, 48, 255), 0.0f, 0, 1.0f);
      }
      const std::string label = cell_label(index, n);
      const ImVec2 ls = ImGui::CalcTextSize(label.c_str());
      dl->AddRectFilled(ImVec2(p0.x + 4, p0.y + 4), ImVec2(p0.x + 12 + ls.x, p0.y + 6 + ls.y),
                        IM_COL32(20, 22, 28, 150), 3.0f);
      dl->AddText(ImVec2(p0.x + 8, p0.y + 5), IM_COL32(240, 240, 245, 255), label.c_str());
      if (view != nullptr && view->current && shown >= 90.0f) {
        const char* current = "current best";
        const ImVec2 cs = ImGui::CalcTextSize(current);
        dl->AddRectFilled(ImVec2(p1.x - 12 - cs.x, p0.y + 4), ImVec2(p1.x - 4, p0.y + 6 + cs.y),
                          IM_COL32(20, 22, 28, 150), 3.0f);
        dl->AddText(ImVec2(p1.x - 8 - cs.x, p0.y + 5), IM_COL32(120, 200, 255, 255), current);
      }
      if (view != nullptr && view->clamped && shown >= 90.0f) {
        const char* edge = "edge of the range";
        const ImVec2 es = ImGui::CalcTextSize(edge);
        dl->AddRectFilled(ImVec2(p0.x + 4, p1.y - 8 - es.y), ImVec2(p0.x + 12 + es.x, p1.y - 4),
                          IM_COL32(20, 22, 28, 150), 3.0f);
        dl->AddText(ImVec2(p0.x + 8, p1.y - 6 - es.y), IM_COL32(255, 180, 90, 255), edge);
      }
    }
  }
  const float total = static_cast<float>(n) * shown + static_cast<float>(n - 1) * gap;
  ImGui::SetCursorScreenPos(origin);
  ImGui::Dummy(ImVec2(total, total));
  if (busy) {
    const ImVec2 m(origin.x + total * 0.5f, origin.y + total * 0.5f);
    dl->AddRectFilled(ImVec2(m.x - 170, m.y - 46), ImVec2(m.x + 170, m.y + 46),
                      IM_COL32(20, 22, 28, 200), 8.0f);
    const float t = static_cast<float>(ImGui::GetTime()) * 6.0f;
    dl->PathArcTo(ImVec2(m.x - 130, m.y), 18.0f, t, t + 4.2f, 32);
    dl->PathStroke(IM_COL32(80, 160, 255, 255), 0, 4.5f);
    dl->AddText(ImVec2(m.x - 100, m.y - 8), IM_COL32(235, 235, 240, 255),
                "Computing the next plane...");
  }
  if (hovered_ >= 0 && !c.animating() && !busy && best != nullptr) {
    const int col = hovered_ % n, row = hovered_ / n;
    const ImVec2 cell_min(origin.x + static_cast<float>(col) * (shown + gap),
                          origin.y + static_cast<float>(row) * (shown + gap));
    draw_hover_details(ctx, LayoutRect{cell_min.x, cell_min.y, shown, shown}, *best,
                       origin.x + total * 0.5f, origin.y + total * 0.5f);
  }
  return orbited;
}

void GridPanel::draw_hover_details(PanelContext& ctx, const LayoutRect& cell,
                                   const PreparedCell& best, float centre_x, float centre_y) {
  const GalleryController& c = ctx.c;
  const ImVec2 cell_min(cell.x, cell.y), cell_max(cell.x + cell.w, cell.y + cell.h);
  const auto& points = c.displayed_cells();
  if (hovered_ >= static_cast<int>(points.size())) return;
  const Eigen::VectorXd& x = points[static_cast<std::size_t>(hovered_)].x;
  if (!details_ || details_->x.size() != x.size() ||
      (details_->x - x).cwiseAbs().maxCoeff() > 1e-12) {
    details_ = c.space().prepare(x, true);
  }
  // A tooltip over the grid covered the very cells being compared; the measurements table's
  // "hovered" column has the numbers. Inside the cell, one line says what differs most.
  if (!ImGui::GetIO().KeyShift) {
    std::string summary = c.space().cell_summary(*details_, best);
    if (summary.empty()) return;
    ImDrawList* dl = ImGui::GetWindowDrawList();
    const float width = cell_max.x - cell_min.x - 8.0f;
    ImVec2 size = ImGui::CalcTextSize(summary.c_str(), nullptr, false, width);
    // A small cell (a 5x5 photo grid) keeps most of its picture: the first item only, and
    // nothing when even that would cover a third of it.
    if (size.y > 0.3f * cell.h) {
      summary = summary.substr(0, summary.find(", "));
      size = ImGui::CalcTextSize(summary.c_str(), nullptr, false, width);
      if (size.y > 0.3f * cell.h) return;
    }
    // Above the cell's "edge of the range" label when it has one.
    const float lift = points[static_cast<std::size_t>(hovered_)].clamped ? size.y + 8.0f : 0.0f;
    const ImVec2 p(cell_min.x + 4.0f, cell_max.y - 6.0f - size.y - lift);
    dl->AddRectFilled(ImVec2(p.x, p.y - 2.0f), ImVec2(p.x + size.x + 8.0f, p.y + size.y + 2.0f),
                      IM_COL32(20, 22, 28, 190), 3.0f);
    dl->AddText(nullptr, 0.0f, ImVec2(p.x + 4.0f, p.y), IM_COL32(255, 220, 150, 255),
                summary.c_str(), nullptr, width);
    return;
  }
  const ImVec2 mouse = ImGui::GetIO().MousePos;
  const ImVec2 pivot(mouse.x > centre_x ? 1.0f : 0.0f, mouse.y > centre_y ? 1.0f : 0.0f);
  const float offset = 18.0f;
  ImGui::SetNextWindowPos(ImVec2(mouse.x + (pivot.x > 0 ? -offset : offset),
                                 mouse.y + (pivot.y > 0 ? -offset : offset)),
                          ImGuiCond_Always, pivot);
  ImGui::BeginTooltip();
  ImGui::Text("Cell %s", cell_label(hovered_, c.session().settings().grid_size).c_str());
  c.space().draw_inspector(*details_, "this cell", &best, "current best");
  if (points[static_cast<std::size_t>(hovered_)].clamped) {
    ImGui::TextDisabled("Some values of this cell are at the edge of their range.");
  }
  ImGui::EndTooltip();
}

}  // namespace app
