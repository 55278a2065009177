// The rendered image on screen. Its linear float pixels are encoded on the CPU into the 8-bit
// codes the CLI's PNG files hold (Display8Encoder: exposure, then the sRGB curve or none),
// uploaded into an 8-bit texture and copied into the window by a framebuffer blit. No shader:
// software GL (llvmpipe) took about 15 ms of both cores to shade 1280x720 pixels from a float
// texture, the encoder takes a few ms of one, and the screen shows exactly the PNG's codes.
// Needs a current GL 3.3 core context loaded by glad.
#pragma once

#include <string>
#include <vector>

#include <glad/gl.h>
#include <glm/glm.hpp>

namespace phonglab {

class ImageView {
 public:
  ImageView() = default;
  // Deletes the GL objects; the context must still be current.
  ~ImageView();
  ImageView(const ImageView&) = delete;
  ImageView& operator=(const ImageView&) = delete;

  // Creates the texture and its framebuffer. Returns an empty string or what failed.
  std::string init();
  // Encodes a linear RGB image (rows from the top) at this exposure (EV) with the sRGB curve
  // or without, and uploads it: a new size reallocates the texture, else it is updated in place.
  void upload(int width, int height, const std::vector<glm::vec3>& pixels, float exposure_ev, bool srgb);
  // Whether the image on the texture was encoded with these display settings.
  bool shows(float exposure_ev, bool srgb) const { return exposure_ev == exposure_ev_ && srgb == srgb_; }
  // Draws the image into the framebuffer rectangle (x, y, width, height), origin at the
  // bottom-left as in glViewport. `nearest` shows coarse levels as crisp blocks; otherwise a
  // scaled image is filtered linearly (between the 8-bit codes).
  void draw(int x, int y, int width, int height, bool nearest);
  bool has_image() const { return width_ > 0; }

 private:
  GLuint texture_ = 0;      // the 8-bit codes, B, G, R, A in memory
  GLuint framebuffer_ = 0;  // reads the texture for the blit
  int width_ = 0;
  int height_ = 0;
  float exposure_ev_ = 0;
  bool srgb_ = true;
  std::vector<unsigned char> staging_;  // the encoded rows, kept to avoid an allocation per image
};

// Reads the back buffer as 8-bit RGB, rows from the top.
std::vector<unsigned char> read_framebuffer_rgb8(int width, int height);

}  // namespace phonglab
