#include "apps/previewer/viewer_gl.h"

#include <cmath>
#include <cstring>

namespace phonglab {

namespace {

// Corners (-1,-1), (3,-1), (-1,3) cover the viewport with one triangle. The image's first row
// is its top, while GL's texture origin is the bottom-left: v is flipped here.
constexpr const char* kVertexShader = R"(#version 330 core
out vec2 uv;
void main() {
  vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
  uv = vec2(p.x, 1.0 - p.y);
  gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
)";

// Exposure and the sRGB transfer curve (IEC 61966-2-1) are applied here only, so changing
// them never restarts rendering. The framebuffer is not sRGB: encoding is explicit.
constexpr const char* kFragmentShader = R"(#version 330 core
in vec2 uv;
out vec4 color;
uniform sampler2D image;
uniform float exposure_scale;
uniform bool srgb;
vec3 encode_srgb(vec3 c) {
  vec3 low = 12.92 * c;
  vec3 high = 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055;
  return mix(low, high, step(vec3(0.0031308), c));
}
void main() {
  vec3 c = clamp(texture(image, uv).rgb * exposure_scale, 0.0, 1.0);
  color = vec4(srgb ? encode_srgb(c) : c, 1.0);
}
)";

std::string shader_log(GLuint shader) {
  GLint length = 0;
  glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
  std::string log(static_cast<std::size_t>(length > 0 ? length : 1), '\0');
  glGetShaderInfoLog(shader, length, nullptr, log.data());
  return log;
}

GLuint compile(GLenum type, const char* source, std::string& error) {
  const GLuint shader = glCreateShader(type);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    error = "shader compilation failed: " + shader_log(shader);
    glDeleteShader(shader);
    return 0;
  }
  return shader;
}

}  // namespace

ImageView::~ImageView() {
  if (cache_framebuffer_ != 0) glDeleteFramebuffers(1, &cache_framebuffer_);
  if (cache_texture_ != 0) glDeleteTextures(1, &cache_texture_);
  if (texture_ != 0) glDeleteTextures(1, &texture_);
  if (vertex_array_ != 0) glDeleteVertexArrays(1, &vertex_array_);
  if (program_ != 0) glDeleteProgram(program_);
}

std::string ImageView::init() {
  std::string error;
  const GLuint vs = compile(GL_VERTEX_SHADER, kVertexShader, error);
  if (vs == 0) return error;
  const GLuint fs = compile(GL_FRAGMENT_SHADER, kFragmentShader, error);
  if (fs == 0) {
    glDeleteShader(vs);
    return error;
  }
  program_ = glCreateProgram();
  glAttachShader(program_, vs);
  glAttachShader(program_, fs);
  glLinkProgram(program_);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = GL_FALSE;
  glGetProgramiv(program_, GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) {
    GLint length = 0;
    glGetProgramiv(program_, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<std::size_t>(length > 0 ? length : 1), '\0');
    glGetProgramInfoLog(program_, length, nullptr, log.data());
    return "shader link failed: " + log;
  }
  exposure_location_ = glGetUniformLocation(program_, "exposure_scale");
  srgb_location_ = glGetUniformLocation(program_, "srgb");
  image_location_ = glGetUniformLocation(program_, "image");
  glGenVertexArrays(1, &vertex_array_);  // core profiles draw nothing without a bound VAO
  glGenTextures(1, &texture_);
  glBindTexture(GL_TEXTURE_2D, texture_);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glGenTextures(1, &cache_texture_);
  glBindTexture(GL_TEXTURE_2D, cache_texture_);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glBindTexture(GL_TEXTURE_2D, 0);
  glGenFramebuffers(1, &cache_framebuffer_);
  return {};
}

void ImageView::upload(int width, int height, const std::vector<glm::vec3>& pixels) {
  if (width <= 0 || height <= 0 || pixels.size() < static_cast<std::size_t>(width) * static_cast<std::size_t>(height)) {
    return;
  }
  glBindTexture(GL_TEXTURE_2D, texture_);
  // Rows of 12-byte texels are 4-byte aligned whatever the width; be explicit anyway, as
  // ImGui's backend also touches pixel-store state.
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
  if (width != texture_width_ || height != texture_height_) {
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB32F, width, height, 0, GL_RGB, GL_FLOAT, pixels.data());
    texture_width_ = width;
    texture_height_ = height;
  } else {
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, width, height, GL_RGB, GL_FLOAT, pixels.data());
  }
  glBindTexture(GL_TEXTURE_2D, 0);
  cache_valid_ = false;
}

void ImageView::draw(int x, int y, int width, int height, float exposure_ev, bool srgb, bool nearest) {
  if (!has_image() || width <= 0 || height <= 0) return;
  // With nearest filtering the shader may run at the image's own size and the blit scale its
  // result up: the same pixels, and a 1/8-level image costs 1/64 of the shading.
  const int cache_w = nearest ? texture_width_ : width;
  const int cache_h = nearest ? texture_height_ : height;
  if (cache_w != cache_width_ || cache_h != cache_height_) {
    glBindTexture(GL_TEXTURE_2D, cache_texture_);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, cache_w, cache_h, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
    glBindTexture(GL_TEXTURE_2D, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, cache_framebuffer_);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, cache_texture_, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    cache_width_ = cache_w;
    cache_height_ = cache_h;
    cache_valid_ = false;
  }
  const bool same = cache_valid_ && exposure_ev == cached_exposure_ev_ && srgb == cached_srgb_ && nearest == cached_nearest_;
  if (!same) {
    glBindFramebuffer(GL_FRAMEBUFFER, cache_framebuffer_);
    glViewport(0, 0, cache_w, cache_h);
    glDisable(GL_BLEND);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glUseProgram(program_);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, texture_);
    const GLint filter = nearest ? GL_NEAREST : GL_LINEAR;
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, filter);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, filter);
    glUniform1i(image_location_, 0);
    glUniform1f(exposure_location_, std::exp2(exposure_ev));
    glUniform1i(srgb_location_, srgb ? 1 : 0);
    glBindVertexArray(vertex_array_);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    glBindTexture(GL_TEXTURE_2D, 0);
    glUseProgram(0);
    cache_valid_ = true;
    cached_exposure_ev_ = exposure_ev;
    cached_srgb_ = srgb;
    cached_nearest_ = nearest;
  }
  glBindFramebuffer(GL_READ_FRAMEBUFFER, cache_framebuffer_);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  glDisable(GL_SCISSOR_TEST);
  glBlitFramebuffer(0, 0, cache_w, cache_h, x, y, x + width, y + height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
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
