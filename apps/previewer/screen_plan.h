// What the window shows under ImGui's draw data, in framebuffer pixels from the top-left: the
// clear colour, the panels' background, the view's image or the small multiples' cells. One rule
// for the window (Viewer::draw_gl, with GL) and the headless screen (ui::SoftwareScreen).
#pragma once

#include <vector>

#include <glm/glm.hpp>
#include <imgui.h>

#include "apps/previewer/shell_state.h"
#include "core/scene/display8.h"
#include "ui/software_screen.h"

namespace phonglab {

struct ScreenPlan {
  struct Image {
    int source = -1;  // -1: the view's image; 0 .. kTermCells - 1: a small multiple's term
    ui::PixelRect rect;
    bool nearest = false;  // coarse levels as crisp blocks; otherwise scaled linearly
  };
  bool clear = true;  // false: the image covers the whole window but the panels
  glm::vec3 clear_color{0.10f, 0.10f, 0.11f};  // the window where neither the image nor a panel is
  bool panel = false;
  ui::PixelRect panel_rect;
  glm::vec3 panel_color{0.0f};  // the panels' background as ImGui blends it over the clear colour
  std::vector<Image> images;
  DisplayBlocks view_blocks;  // the view's image is uploaded widened into these (block 1: as it is)
};

// The plan for a framebuffer of fb_width x fb_height at ImGui's framebuffer scale, with the
// panels' background colour (ImGui's WindowBg).
ScreenPlan plan_screen(const ShellState& s, int fb_width, int fb_height, ImVec2 scale, ImVec4 panel_background);

}  // namespace phonglab
