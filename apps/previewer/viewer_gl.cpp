#include "apps/previewer/viewer_gl.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace phonglab {

ImageView::~ImageView() {
  if (framebuffer_ != 0) glDeleteFramebuffers(1, &framebuffer_);
  if (texture_ != 0) glDeleteTextures(1, &texture_);
}

namespace {

constexpr GLenum kFramebufferFlipYMesa = 0x8BBB;  // GL_MESA_framebuffer_flip_y

bool has_extension(const char* name) {
  GLint count = 0;
  glGetIntegerv(GL_NUM_EXTENSIONS, &count);
  for (GLint i = 0; i < count; ++i) {
    const auto* extension = reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, static_cast<GLuint>(i)));
    if (extension != nullptr && std::strcmp(extension, name) == 0) return true;
  }
  return false;
}

}  // namespace

std::string ImageView::init(GLADloadfunc load) {
  glGenTextures(1, &texture_);
  glBindTexture(GL_TEXTURE_2D, texture_);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glBindTexture(GL_TEXTURE_2D, 0);
  glGenFramebuffers(1, &framebuffer_);
  if (texture_ == 0 || framebuffer_ == 0) return "cannot create the image's texture";
  // A framebuffer that runs from the top, as the window's does in Mesa: the blit then copies
  // rows as they are instead of flipping them through a shader.
  using FramebufferParameteri = void (*)(GLenum, GLenum, GLint);  // GL 4.3's, not in glad's 3.3
  FramebufferParameteri set_parameter = nullptr;
  if (load != nullptr && has_extension("GL_MESA_framebuffer_flip_y")) {
    set_parameter = reinterpret_cast<FramebufferParameteri>(load("glFramebufferParameteri"));
  }
  if (set_parameter != nullptr) {
    while (glGetError() != GL_NO_ERROR) continue;  // earlier errors are not this call's
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
    set_parameter(GL_FRAMEBUFFER, kFramebufferFlipYMesa, GL_TRUE);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    top_down_ = glGetError() == GL_NO_ERROR;
  }
  return {};
}

void ImageView::upload(int width, int height, const std::vector<glm::vec3>& pixels, float exposure_ev, bool srgb,
                       DisplayBlocks blocks) {
  const std::size_t n = static_cast<std::size_t>(width > 0 ? width : 0) * static_cast<std::size_t>(height > 0 ? height : 0);
  if (n == 0 || pixels.size() < n) return;
  if (blocks.block <= 1 || !blocks.fit(width, height)) {
    blocks = DisplayBlocks{1, width, height};  // the image as it is (also a coarse one of another view)
  }
  staging_.resize(static_cast<std::size_t>(blocks.width) * static_cast<std::size_t>(blocks.height) * 4);
  const Display8Encoder& encoder = srgb ? Display8Encoder::srgb() : Display8Encoder::linear();
  // Rows go up in GL's order (from the bottom) unless the framebuffer runs from the top.
  encoder.encode_bgra_blocks(pixels.data(), width, height, std::exp2(exposure_ev), blocks, !top_down_, staging_.data());
  exposure_ev_ = exposure_ev;
  srgb_ = srgb;
  glBindTexture(GL_TEXTURE_2D, texture_);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);  // ImGui's backend also touches pixel-store state
  glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
  if (blocks.width != width_ || blocks.height != height_) {
    // Unsized RGBA with BGRA data: the driver may keep the bytes as they come, the window's order.
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, blocks.width, blocks.height, 0, GL_BGRA, GL_UNSIGNED_INT_8_8_8_8_REV, staging_.data());
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, texture_, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    width_ = blocks.width;
    height_ = blocks.height;
  } else {
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, blocks.width, blocks.height, GL_BGRA, GL_UNSIGNED_INT_8_8_8_8_REV, staging_.data());
  }
  glBindTexture(GL_TEXTURE_2D, 0);
}

void ImageView::draw(int x, int y, int width, int height, bool nearest) {
  if (!has_image() || width <= 0 || height <= 0) return;
  glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer_);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  glDisable(GL_SCISSOR_TEST);
  // Same size: a copy (nearest is exact and lets the driver copy rows).
  const bool copy = width == width_ && height == height_;
  glBlitFramebuffer(0, 0, width_, height_, x, y, x + width, y + height, GL_COLOR_BUFFER_BIT,
                    copy || nearest ? GL_NEAREST : GL_LINEAR);
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
