#include "apps/previewer/screen_plan.h"

#include <cmath>

namespace phonglab {

ScreenPlan plan_screen(const ShellState& s, int fb_width, int fb_height, ImVec2 scale, ImVec4 panel_background) {
  ScreenPlan plan;
  const auto px = [](float v, float k) { return static_cast<int>(std::lround(v * k)); };
  const ui::PixelRect view{px(s.viewport.x, scale.x), px(s.viewport.y, scale.y), px(s.viewport.width, scale.x),
                            px(s.viewport.height, scale.y)};
  // The sidebar, when shown, runs from the view's right edge to the window's (Sidebar::draw_sidebar).
  const int panel_x = px(s.viewport.width, scale.x);
  plan.panel = s.sidebar_visible && panel_x < fb_width;
  if (plan.panel) {
    const ImVec4& bg = panel_background;
    plan.panel_rect = {panel_x, 0, fb_width - panel_x, fb_height};
    plan.panel_color = glm::vec3(bg.x, bg.y, bg.z) * bg.w + plan.clear_color * (1 - bg.w);
  }
  const bool multiples = s.instruments.small_multiples;
  // A coarse level filling the view is widened into its blocks when uploaded: the copy is then plain.
  const int shown_w = s.shown.width, shown_h = s.shown.height;
  if (!multiples && s.shown.divisor > 1) {
    const DisplayBlocks blocks{s.shown.divisor, view.width, view.height};
    if (blocks.fit(shown_w, shown_h)) plan.view_blocks = blocks;
  }
  if (plan.view_blocks.block <= 1) plan.view_blocks = DisplayBlocks{1, shown_w, shown_h};
  if (multiples) {
    // 3 x 2 cells in reading order, the full image last (Cells).
    const int cell_w = view.width / kMultiplesColumns, cell_h = view.height / kMultiplesRows;
    for (int cell = 0; cell < kMultiplesColumns * kMultiplesRows; ++cell) {
      const ui::PixelRect rect{view.x + (cell % kMultiplesColumns) * cell_w, view.y + (cell / kMultiplesColumns) * cell_h,
                                cell_w, cell_h};
      plan.images.push_back({cell == kTermCells ? -1 : cell, rect, s.shown.divisor > 1});
    }
  } else {
    // Coarse levels as crisp blocks; a reduced-resolution final image is smoothed.
    plan.images.push_back({-1, view, s.shown.divisor > 1 || plan.view_blocks.width == view.width});
  }
  // The image over the whole view, up to the panel or the window's edge, leaves nothing to clear.
  plan.clear = multiples || view.x != 0 || view.y != 0 || view.height != fb_height ||
               view.width != (plan.panel ? panel_x : fb_width) || plan.view_blocks.width != view.width ||
               plan.view_blocks.height != view.height;
  return plan;
}

}  // namespace phonglab
