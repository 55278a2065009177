// The headless screen's drawing (ui::SoftwareScreen) against what GL's rules give, analytically:
// a clear rounds to 8 bits, a same-size blit copies the codes and a scaled one repeats or blends
// them, ImGui's opaque rectangle covers exactly the pixels whose centres are inside it, two
// translucent triangles sharing an edge blend each pixel once, a clip rectangle cuts, text is
// drawn from the font atlas.
#include <gtest/gtest.h>

#include <array>
#include <cstddef>
#include <vector>

#include <imgui.h>

#include "ui/software_screen.h"

namespace phonglab {
namespace {

using ui::SoftwareScreen;

std::array<int, 3> pixel(const SoftwareScreen& s, int x, int y) {
  const std::size_t i = (static_cast<std::size_t>(y) * static_cast<std::size_t>(s.width()) + static_cast<std::size_t>(x)) * 3;
  return {s.rgb()[i], s.rgb()[i + 1], s.rgb()[i + 2]};
}

TEST(SoftwareScreen, FillRoundsToEightBitsInsideItsRectangle) {
  SoftwareScreen s(4, 3);
  s.fill({1, 1, 2, 5}, {0.5f, 0.1f, 1.0f});
  EXPECT_EQ(pixel(s, 1, 1), (std::array<int, 3>{128, 26, 255}));
  EXPECT_EQ(pixel(s, 2, 2), (std::array<int, 3>{128, 26, 255}));
  EXPECT_EQ(pixel(s, 0, 1), (std::array<int, 3>{0, 0, 0}));
  EXPECT_EQ(pixel(s, 3, 1), (std::array<int, 3>{0, 0, 0}));
  EXPECT_EQ(pixel(s, 1, 0), (std::array<int, 3>{0, 0, 0}));
}

TEST(SoftwareScreen, BlitCopiesRepeatsOrBlendsTheCodes) {
  // Two pixels, B G R A each: red 200 then blue 100.
  const std::vector<unsigned char> bgra = {0, 0, 200, 255, 100, 0, 0, 255};
  SoftwareScreen copy(3, 1);
  copy.blit(bgra.data(), 2, 1, {1, 0, 2, 1}, false);
  EXPECT_EQ(pixel(copy, 0, 0), (std::array<int, 3>{0, 0, 0}));
  EXPECT_EQ(pixel(copy, 1, 0), (std::array<int, 3>{200, 0, 0}));
  EXPECT_EQ(pixel(copy, 2, 0), (std::array<int, 3>{0, 0, 100}));
  SoftwareScreen nearest(4, 2);
  nearest.blit(bgra.data(), 2, 1, {0, 0, 4, 2}, true);
  for (int y = 0; y < 2; ++y) {
    EXPECT_EQ(pixel(nearest, 1, y), (std::array<int, 3>{200, 0, 0}));
    EXPECT_EQ(pixel(nearest, 2, y), (std::array<int, 3>{0, 0, 100}));
  }
  // Linear, 2 -> 4: the centres fall at source x 0.25, 0.75, 1.25, 1.75 - 0.5, clamped at the edges.
  SoftwareScreen linear(4, 1);
  linear.blit(bgra.data(), 2, 1, {0, 0, 4, 1}, false);
  EXPECT_EQ(pixel(linear, 0, 0), (std::array<int, 3>{200, 0, 0}));
  EXPECT_EQ(pixel(linear, 1, 0), (std::array<int, 3>{150, 0, 25}));
  EXPECT_EQ(pixel(linear, 2, 0), (std::array<int, 3>{50, 0, 75}));
  EXPECT_EQ(pixel(linear, 3, 0), (std::array<int, 3>{0, 0, 100}));
}

// One ImGui frame at 64 x 48 whose foreground draw list `draw` fills.
template <typename Draw>
SoftwareScreen imgui_frame(Draw draw) {
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;
  io.DisplaySize = ImVec2(64, 48);
  ImGui::GetStyle().AntiAliasedFill = false;  // the triangles as given, no feathered edges
  unsigned char* atlas = nullptr;
  int w = 0, h = 0;
  io.Fonts->GetTexDataAsRGBA32(&atlas, &w, &h);
  ImGui::NewFrame();
  draw(*ImGui::GetForegroundDrawList());
  ImGui::Render();
  SoftwareScreen screen(64, 48);
  screen.draw(*ImGui::GetDrawData(), atlas, w, h);
  ImGui::DestroyContext();
  return screen;
}

int count(const SoftwareScreen& s, std::array<int, 3> code) {
  int n = 0;
  for (int y = 0; y < s.height(); ++y) {
    for (int x = 0; x < s.width(); ++x) n += pixel(s, x, y) == code ? 1 : 0;
  }
  return n;
}

TEST(SoftwareScreen, AnOpaqueRectangleCoversThePixelsWhoseCentresAreInside) {
  const SoftwareScreen s = imgui_frame([](ImDrawList& list) { list.AddRectFilled({10, 10}, {20, 30}, IM_COL32(255, 0, 0, 255)); });
  EXPECT_EQ(count(s, {255, 0, 0}), 10 * 20);
  EXPECT_EQ(pixel(s, 10, 10), (std::array<int, 3>{255, 0, 0}));
  EXPECT_EQ(pixel(s, 19, 29), (std::array<int, 3>{255, 0, 0}));
  EXPECT_EQ(pixel(s, 20, 29), (std::array<int, 3>{0, 0, 0}));
  EXPECT_EQ(pixel(s, 19, 30), (std::array<int, 3>{0, 0, 0}));
}

TEST(SoftwareScreen, TrianglesSharingAnEdgeBlendEachPixelOnce) {
  // A 32 x 32 square as two translucent triangles split on its diagonal, whose line passes through
  // 32 pixel centres: drawn twice there it would be brighter, drawn by neither black.
  const SoftwareScreen s = imgui_frame([](ImDrawList& list) {
    const ImU32 half_white = IM_COL32(255, 255, 255, 128);
    list.AddTriangleFilled({0, 0}, {32, 0}, {32, 32}, half_white);
    list.AddTriangleFilled({0, 0}, {32, 32}, {0, 32}, half_white);
  });
  EXPECT_EQ(count(s, {128, 128, 128}), 32 * 32);
  EXPECT_EQ(count(s, {0, 0, 0}), 64 * 48 - 32 * 32);
}

TEST(SoftwareScreen, AClipRectangleCutsAndTextIsDrawnFromTheAtlas) {
  const SoftwareScreen clipped = imgui_frame([](ImDrawList& list) {
    list.PushClipRect({4, 4}, {12, 8});
    list.AddRectFilled({0, 0}, {64, 48}, IM_COL32(0, 255, 0, 255));
    list.PopClipRect();
  });
  EXPECT_EQ(count(clipped, {0, 255, 0}), 8 * 4);
  EXPECT_EQ(pixel(clipped, 4, 4), (std::array<int, 3>{0, 255, 0}));
  const SoftwareScreen text = imgui_frame([](ImDrawList& list) { list.AddText({2, 2}, IM_COL32(255, 255, 255, 255), "Phong"); });
  int lit = 0, outside = 0;
  for (int y = 0; y < text.height(); ++y) {
    for (int x = 0; x < text.width(); ++x) {
      const bool on = pixel(text, x, y)[0] > 0;
      (x < 2 + 5 * 8 && y < 2 + 16 ? lit : outside) += on ? 1 : 0;
    }
  }
  EXPECT_GT(lit, 40) << "the glyphs' pixels";
  EXPECT_EQ(outside, 0) << "nothing beyond the text's box (13-pixel font, 7-pixel glyphs)";
  EXPECT_GT(count(text, {255, 255, 255}), 5) << "the glyphs' cores are opaque";
}

}  // namespace
}  // namespace phonglab
