// The rendered image on screen. Its linear float pixels are encoded on the CPU into the 8-bit
// codes the CLI's PNG files hold (Display8Encoder: exposure, then the sRGB curve or none),
// uploaded into an 8-bit texture and copied into the window by a framebuffer blit. No shader:
// software GL (llvmpipe) took about 15 ms of both cores to shade 1280x720 pixels from a float
// texture, the encoder takes a few ms of one, and the screen shows exactly the PNG's codes.
//
// The copy is made cheap for software GL, whose drawing shares the UI thread with everything
// else: the texture keeps the window's own byte order (B, G, R, A, from an unsized RGBA format
// and BGRA uploads), a coarse level is widened into its blocks on the CPU so the blit is never
// scaled, and where GL_MESA_framebuffer_flip_y exists the texture's framebuffer runs from the
// top like the window's. Then Mesa copies rows instead of shading every pixel: about 10 ms a
// 1280x720 frame on one core of the reference machine becomes about 1 ms
// (docs/previewer.md, "The image's copy to the window").
// Needs a current GL 3.3 core context loaded by glad.
#pragma once

#include <string>
#include <vector>

#include <glad/gl.h>
#include <glm/glm.hpp>

#include "core/scene/display8.h"

namespace phonglab {

class ImageView {
 public:
  ImageView() = default;
  // Deletes the GL objects; the context must still be current.
  ~ImageView();
  ImageView(const ImageView&) = delete;
  ImageView& operator=(const ImageView&) = delete;

  // Creates the texture and its framebuffer; `load` finds GL functions beyond 3.3 core (the
  // flip-y extension's). Returns an empty string or what failed.
  std::string init(GLADloadfunc load);
  // Encodes a linear RGB image (rows from the top) at this exposure (EV) with the sRGB curve
  // or without, widened into `blocks`, and uploads it: a new size reallocates the texture,
  // else it is updated in place.
  void upload(int width, int height, const std::vector<glm::vec3>& pixels, float exposure_ev, bool srgb,
              DisplayBlocks blocks = {});
  // Whether the image on the texture was encoded with these display settings.
  bool shows(float exposure_ev, bool srgb) const { return exposure_ev == exposure_ev_ && srgb == srgb_; }
  // Draws the image into the framebuffer rectangle (x, y, width, height), origin at the
  // bottom-left as in glViewport. `nearest` shows coarse levels as crisp blocks; otherwise a
  // scaled image is filtered linearly (between the 8-bit codes).
  void draw(int x, int y, int width, int height, bool nearest);
  bool has_image() const { return width_ > 0; }
  // The texture's size: the view's when the last image was uploaded into its blocks.
  int width() const { return width_; }
  int height() const { return height_; }
  // Whether the texture's framebuffer runs from the top like the window's (flip-y).
  bool rows_from_top() const { return top_down_; }

 private:
  GLuint texture_ = 0;      // the 8-bit codes, B, G, R, A in memory
  GLuint framebuffer_ = 0;  // reads the texture for the blit
  int width_ = 0;
  int height_ = 0;
  float exposure_ev_ = 0;
  bool srgb_ = true;
  bool top_down_ = false;   // the framebuffer runs from the top (flip-y): rows go up in image order
  std::vector<unsigned char> staging_;  // the encoded rows, kept to avoid an allocation per image
};

// Reads the back buffer as 8-bit RGB, rows from the top.
std::vector<unsigned char> read_framebuffer_rgb8(int width, int height);

}  // namespace phonglab
