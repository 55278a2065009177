#include "ui/software_screen.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace phonglab::ui {

namespace {

unsigned char to_code(float v) { return static_cast<unsigned char>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)); }

std::size_t at(int x, int y, int width) { return static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x); }

// GL_LINEAR at texture coordinates (u, v), clamped to the edge: RGBA in [0, 1].
glm::vec4 sample_linear(const unsigned char* rgba, int width, int height, float u, float v) {
  const float x = u * static_cast<float>(width) - 0.5f;
  const float y = v * static_cast<float>(height) - 0.5f;
  const float fx = std::floor(x), fy = std::floor(y);
  const int x0 = static_cast<int>(fx), y0 = static_cast<int>(fy);
  const float tx = x - fx, ty = y - fy;
  glm::vec4 sum(0.0f);
  for (int j = 0; j < 2; ++j) {
    for (int i = 0; i < 2; ++i) {
      const int sx = std::clamp(x0 + i, 0, width - 1), sy = std::clamp(y0 + j, 0, height - 1);
      const unsigned char* p = rgba + at(sx, sy, width) * 4;
      const float weight = (i == 0 ? 1 - tx : tx) * (j == 0 ? 1 - ty : ty);
      sum += weight * glm::vec4(p[0], p[1], p[2], p[3]) / 255.0f;
    }
  }
  return sum;
}

glm::vec4 rgba(ImU32 packed) {
  const ImVec4 c = ImGui::ColorConvertU32ToFloat4(packed);
  return {c.x, c.y, c.z, c.w};
}

// Twice the signed area of (a, b, p): positive when p is left of a -> b in y-down pixels.
double edge(const ImVec2& a, const ImVec2& b, double px, double py) {
  return (static_cast<double>(b.x) - a.x) * (py - a.y) - (static_cast<double>(b.y) - a.y) * (px - a.x);
}

// A pixel centre on an edge belongs to one of the two triangles sharing it, as in GL's
// rasterisation: the two walk the edge in opposite directions, and only one direction owns it.
bool owns_edge(const ImVec2& a, const ImVec2& b) { return b.y > a.y || (b.y == a.y && b.x < a.x); }

}  // namespace

SoftwareScreen::SoftwareScreen(int width, int height)
    : width_(std::max(width, 0)), height_(std::max(height, 0)),
      rgb_(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_) * 3, 0) {}

void SoftwareScreen::fill(PixelRect rect, glm::vec3 color) {
  const unsigned char code[3] = {to_code(color.r), to_code(color.g), to_code(color.b)};
  const int x0 = std::max(rect.x, 0), x1 = std::min(rect.x + rect.width, width_);
  const int y0 = std::max(rect.y, 0), y1 = std::min(rect.y + rect.height, height_);
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) std::copy(code, code + 3, rgb_.begin() + static_cast<std::ptrdiff_t>(at(x, y, width_) * 3));
  }
}

void SoftwareScreen::blit(const unsigned char* bgra, int width, int height, PixelRect rect, bool nearest) {
  if (bgra == nullptr || width <= 0 || height <= 0 || rect.width <= 0 || rect.height <= 0) return;
  const bool copy = width == rect.width && height == rect.height;
  const float sx = static_cast<float>(width) / static_cast<float>(rect.width);
  const float sy = static_cast<float>(height) / static_cast<float>(rect.height);
  for (int y = std::max(rect.y, 0); y < std::min(rect.y + rect.height, height_); ++y) {
    for (int x = std::max(rect.x, 0); x < std::min(rect.x + rect.width, width_); ++x) {
      // The destination pixel's centre in the source's pixels.
      const float u = (static_cast<float>(x - rect.x) + 0.5f) * sx, v = (static_cast<float>(y - rect.y) + 0.5f) * sy;
      unsigned char* out = &rgb_[at(x, y, width_) * 3];
      if (copy || nearest) {
        const int ix = std::min(static_cast<int>(u), width - 1), iy = std::min(static_cast<int>(v), height - 1);
        const unsigned char* p = bgra + at(ix, iy, width) * 4;
        out[0] = p[2], out[1] = p[1], out[2] = p[0];
      } else {
        const glm::vec4 s = sample_linear(bgra, width, height, u / static_cast<float>(width), v / static_cast<float>(height));
        out[0] = to_code(s.b), out[1] = to_code(s.g), out[2] = to_code(s.r);  // the source's bytes are B, G, R
      }
    }
  }
}

void SoftwareScreen::draw(const ImDrawData& data, const unsigned char* atlas_rgba, int atlas_width, int atlas_height) {
  if (atlas_rgba == nullptr || atlas_width <= 0 || atlas_height <= 0) return;
  const ImVec2 origin = data.DisplayPos, scale = data.FramebufferScale;
  const auto to_screen = [&](ImDrawVert v) {
    v.pos = ImVec2((v.pos.x - origin.x) * scale.x, (v.pos.y - origin.y) * scale.y);
    return v;
  };
  for (int n = 0; n < data.CmdListsCount; ++n) {
    const ImDrawList& list = *data.CmdLists[n];
    for (const ImDrawCmd& cmd : list.CmdBuffer) {
      if (cmd.UserCallback != nullptr) continue;  // none of the previewer's draws has one
      const ImVec4 clip((cmd.ClipRect.x - origin.x) * scale.x, (cmd.ClipRect.y - origin.y) * scale.y,
                        (cmd.ClipRect.z - origin.x) * scale.x, (cmd.ClipRect.w - origin.y) * scale.y);
      if (clip.z <= clip.x || clip.w <= clip.y) continue;
      for (unsigned int i = 0; i + 2 < cmd.ElemCount; i += 3) {
        const ImDrawIdx* idx = list.IdxBuffer.Data + cmd.IdxOffset + i;
        const ImDrawVert* vtx = list.VtxBuffer.Data + cmd.VtxOffset;
        triangle(to_screen(vtx[idx[0]]), to_screen(vtx[idx[1]]), to_screen(vtx[idx[2]]), clip, atlas_rgba, atlas_width,
                 atlas_height);
      }
    }
  }
}

void SoftwareScreen::triangle(const ImDrawVert& a, const ImDrawVert& b_in, const ImDrawVert& c_in, const ImVec4& clip,
                              const unsigned char* atlas, int atlas_width, int atlas_height) {
  const double area = edge(a.pos, b_in.pos, c_in.pos.x, c_in.pos.y);
  if (area == 0) return;
  // Wound so that the inside is left of every edge.
  const ImDrawVert& b = area > 0 ? b_in : c_in;
  const ImDrawVert& c = area > 0 ? c_in : b_in;
  const double total = std::abs(area);
  // The scissor rectangle as ImGui's backend sets it (integer pixels) and the triangle's bounds.
  const int x_min = std::max({static_cast<int>(clip.x), 0, static_cast<int>(std::floor(std::min({a.pos.x, b.pos.x, c.pos.x})))});
  const int x_max = std::min({static_cast<int>(clip.x) + static_cast<int>(clip.z - clip.x), width_,
                              static_cast<int>(std::ceil(std::max({a.pos.x, b.pos.x, c.pos.x}))) + 1});
  const int y_min = std::max({static_cast<int>(clip.y), 0, static_cast<int>(std::floor(std::min({a.pos.y, b.pos.y, c.pos.y})))});
  const int y_max = std::min({static_cast<int>(clip.y) + static_cast<int>(clip.w - clip.y), height_,
                              static_cast<int>(std::ceil(std::max({a.pos.y, b.pos.y, c.pos.y}))) + 1});
  const bool own_a = owns_edge(b.pos, c.pos), own_b = owns_edge(c.pos, a.pos), own_c = owns_edge(a.pos, b.pos);
  const glm::vec4 col_a = rgba(a.col), col_b = rgba(b.col), col_c = rgba(c.col);
  for (int y = y_min; y < y_max; ++y) {
    const double py = y + 0.5;
    for (int x = x_min; x < x_max; ++x) {
      const double px = x + 0.5;
      const double wa = edge(b.pos, c.pos, px, py), wb = edge(c.pos, a.pos, px, py), wc = edge(a.pos, b.pos, px, py);
      if (wa < 0 || wb < 0 || wc < 0) continue;
      if ((wa == 0 && !own_a) || (wb == 0 && !own_b) || (wc == 0 && !own_c)) continue;
      const auto la = static_cast<float>(wa / total), lb = static_cast<float>(wb / total), lc = static_cast<float>(wc / total);
      const glm::vec4 color = la * col_a + lb * col_b + lc * col_c;
      const float u = la * a.uv.x + lb * b.uv.x + lc * c.uv.x, v = la * a.uv.y + lb * b.uv.y + lc * c.uv.y;
      const glm::vec4 src = color * sample_linear(atlas, atlas_width, atlas_height, u, v);
      unsigned char* out = &rgb_[at(x, y, width_) * 3];
      for (int k = 0; k < 3; ++k) out[k] = to_code(src[k] * src.a + static_cast<float>(out[k]) / 255.0f * (1 - src.a));
    }
  }
}

}  // namespace phonglab::ui
