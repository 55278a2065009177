// The window's pixels drawn on the CPU, for the shell run without a window (the headless
// platform): its screenshots show what the window would, so the checks of what is on the screen
// (the compare and difference views, the small multiples, the overlays, a panel drawn over the
// view) run in a test without a display.
//
// It draws what the previewer's GL path draws, the same way: rectangles cleared to a colour, an
// image's 8-bit codes copied and scaled as glBlitFramebuffer copies them (nearest, or linear
// between the codes), and ImGui's draw data as ImGui's OpenGL 3 backend draws it (each command's
// triangles clipped to its rectangle, pixel centres sampled, the vertex colour times the font
// atlas's texel read linearly, blended over by alpha into 8 bits). Written here: ImGui 1.86 and
// Debian's packages ship GPU backends only; this is a few dozen lines of triangle setup.
#pragma once

#include <vector>

#include <glm/glm.hpp>
#include <imgui.h>

namespace phonglab::ui {

struct PixelRect {  // pixels from the window's top-left
  int x = 0, y = 0, width = 0, height = 0;
};

class SoftwareScreen {
 public:
  SoftwareScreen(int width, int height);  // black

  int width() const { return width_; }
  int height() const { return height_; }
  // RGB, 8 bits a channel, rows from the top: what glReadPixels reads of the window.
  const std::vector<unsigned char>& rgb() const { return rgb_; }

  // As glClear inside a scissor rectangle: the colour's channels rounded to 8 bits.
  void fill(PixelRect rect, glm::vec3 color);
  // An image's 8-bit codes (B, G, R, A a pixel, rows from the top: Display8Encoder's) into
  // `rect`, scaled as glBlitFramebuffer scales: nearest, or linear between the codes.
  void blit(const unsigned char* bgra, int width, int height, PixelRect rect, bool nearest);
  // ImGui's draw data over what is there, with the font atlas (RGBA, 8 bits a channel) as the
  // texture of every command.
  void draw(const ImDrawData& data, const unsigned char* atlas_rgba, int atlas_width, int atlas_height);

 private:
  void triangle(const ImDrawVert& a, const ImDrawVert& b, const ImDrawVert& c, const ImVec4& clip,
                const unsigned char* atlas, int atlas_width, int atlas_height);

  int width_ = 0;
  int height_ = 0;
  std::vector<unsigned char> rgb_;
};

}  // namespace phonglab::ui
