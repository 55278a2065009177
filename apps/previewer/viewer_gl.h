// The rendered image on screen: a float RGB texture drawn by a fullscreen triangle whose
// fragment shader applies exposure and the sRGB curve (display-time only). Needs a current
// GL 3.3 core context loaded by glad.
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

  // Compiles the shader and creates the textures. Returns an empty string or the GL error log.
  std::string init();
  // Uploads a linear RGB image (rows from the top) as GL_RGB32F: a new texture size
  // reallocates it, otherwise glTexSubImage2D updates it in place.
  void upload(int width, int height, const std::vector<glm::vec3>& pixels);
  // Draws the image into the framebuffer rectangle (x, y, width, height), origin at the
  // bottom-left as in glViewport. `nearest` shows coarse levels as crisp blocks.
  void draw(int x, int y, int width, int height, float exposure_ev, bool srgb, bool nearest);
  bool has_image() const { return texture_width_ > 0; }

 private:
  GLuint program_ = 0;
  GLuint vertex_array_ = 0;  // empty: the triangle's corners come from gl_VertexID
  GLuint texture_ = 0;       // the linear float image
  GLint exposure_location_ = -1;
  GLint srgb_location_ = -1;
  GLint image_location_ = -1;
  int texture_width_ = 0;
  int texture_height_ = 0;
  // The displayed 8-bit result, kept between frames: software GL (llvmpipe) needs ~10 ms to
  // shade 1280x720 pixels from a float texture, a blit of the cache about half that. Redrawn
  // only when the image, its size on screen, exposure, the sRGB toggle or the filter change.
  GLuint cache_framebuffer_ = 0;
  GLuint cache_texture_ = 0;
  int cache_width_ = 0;
  int cache_height_ = 0;
  bool cache_valid_ = false;
  float cached_exposure_ev_ = 0;
  bool cached_srgb_ = false;
  bool cached_nearest_ = false;
};

// Reads the back buffer as 8-bit RGB, rows from the top.
std::vector<unsigned char> read_framebuffer_rgb8(int width, int height);

}  // namespace phonglab
