#include "apps/previewer/viewer_gl.h"

#include <cmath>
#include <cstring>

#include "core/scene/display8.h"

namespace phonglab {

ImageView::~ImageView() {
  if (framebuffer_ != 0) glDeleteFramebuffers(1, &framebuffer_);
  if (texture_ != 0) glDeleteTextures(1, &texture_);
}

std::string ImageView::init() {
  glGenTextures(1, &texture_);
  glBindTexture(GL_TEXTURE_2D, texture_);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glBindTexture(GL_TEXTURE_2D, 0);
  glGenFramebuffers(1, &framebuffer_);
  if (texture_ == 0 || framebuffer_ == 0) return "cannot create the image's texture";
  return {};
}

void ImageView::upload(int width, int height, const std::vector<glm::vec3>& pixels, float exposure_ev, bool srgb) {
  const std::size_t n = static_cast<std::size_t>(width > 0 ? width : 0) * static_cast<std::size_t>(height > 0 ? height : 0);
  if (n == 0 || pixels.size() < n) return;
  staging_.resize(n * 4);
  const Display8Encoder& encoder = srgb ? Display8Encoder::srgb() : Display8Encoder::linear();
  const float scale = std::exp2(exposure_ev);
  const auto row = static_cast<std::size_t>(width);
  // GL's rows run from the bottom: the image's last row first, so the blit needs no flip.
  for (std::size_t y = 0; y < static_cast<std::size_t>(height); ++y) {
    encoder.encode_bgra(pixels.data() + y * row, row, scale, staging_.data() + (static_cast<std::size_t>(height) - 1 - y) * row * 4);
  }
  exposure_ev_ = exposure_ev;
  srgb_ = srgb;
  glBindTexture(GL_TEXTURE_2D, texture_);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);  // ImGui's backend also touches pixel-store state
  glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
  if (width != width_ || height != height_) {
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_BGRA, GL_UNSIGNED_INT_8_8_8_8_REV, staging_.data());
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, texture_, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    width_ = width;
    height_ = height;
  } else {
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, width, height, GL_BGRA, GL_UNSIGNED_INT_8_8_8_8_REV, staging_.data());
  }
  glBindTexture(GL_TEXTURE_2D, 0);
}

void ImageView::draw(int x, int y, int width, int height, bool nearest) {
  if (!has_image() || width <= 0 || height <= 0) return;
  glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer_);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  glDisable(GL_SCISSOR_TEST);
  glBlitFramebuffer(0, 0, width_, height_, x, y, x + width, y + height, GL_COLOR_BUFFER_BIT,
                    nearest ? GL_NEAREST : GL_LINEAR);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

std::vector<unsigned char> read_framebuffer_rgb8(int width, int height) {
  std::vector<unsigned char> bottom_up(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3);
  if (bottom_up.empty()) return bottom_up;
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadBuffer(GL_BACK);
  glReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, bottom_up.data());
  // GL reads from the bottom row up; images here run from the top.
  std::vector<unsigned char> top_down(bottom_up.size());
  const std::size_t row = static_cast<std::size_t>(width) * 3;
  for (int y = 0; y < height; ++y) {
    std::memcpy(top_down.data() + static_cast<std::size_t>(y) * row,
                bottom_up.data() + static_cast<std::size_t>(height - 1 - y) * row, row);
  }
  return top_down;
}

}  // namespace phonglab
