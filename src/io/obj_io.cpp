#include "io/obj_io.h"
#include "core/scene/chars.h"
#include "core/base/threads.h"
#include "io/memory_budget.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <istream>
#include <map>
#include <sstream>
#include <streambuf>
#include <string_view>
#include <thread>

#include <tiny_obj_loader.h>  // double precision: the target defines TINYOBJLOADER_USE_DOUBLE

namespace phonglab {

Material default_mesh_material() {
  Material m;
  m.name = "default";
  m.ka = Color(0.1);
  m.kd = Color(0.7);
  m.ks = Color(0.2);
  m.n = 32;
  return m;
}

namespace {

bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r'; }

// What tinyobjloader does not check: the line of every face (so index errors can name it) and
// vertex coordinates that are not finite numbers (it would read "nan" as 0).
// The largest positive index of one kind met in the faces, as written, and where.
struct LargestIndex {
  long value = 0;
  int line = 0;
  std::string token;   // the face vertex it is part of
  std::string digits;  // the index as the file wrote it
};

struct Prescan {
  std::vector<int> face_lines;  // line of each face with 3 or more vertices, in file order
  std::vector<double> vertices;  // x, y, z of each `v`, correctly rounded (std::from_chars)
  std::size_t max_triangles = 0;  // of the fans of those faces
  std::vector<Diagnostic> errors;
  LargestIndex largest[3];  // vertices, texture coordinates, normals
};

// Checks one face vertex ("v", "v/t", "v//n", "v/t/n") where tinyobjloader would stop at the
// first bad one without a line: indices must be integers other than 0, and relative (negative)
// ones must not reach before the first element read so far (`read`: vertices, texture
// coordinates, normals). Returns the problem, or "".
std::string check_face_vertex(std::string_view token, const long read[3], LargestIndex largest[3], int line) {
  static const char* const kKinds[3] = {"vertex", "texture", "normal"};
  std::size_t start = 0;
  for (int kind = 0; kind < 3 && start <= token.size(); ++kind) {
    std::size_t slash = token.find('/', start);
    if (slash == std::string_view::npos) slash = token.size();
    const std::string_view digits = token.substr(start, slash - start);
    start = slash + 1;
    if (digits.empty() && kind > 0) continue;  // "v//n" has no texture index
    // std::from_chars where it reads the whole part (plain decimal, in range: what files hold), and
    // strtol's verdict on anything else, which it alone decides ("+5", overflow): the same answers
    // as strtol throughout, without a string made for every index of a 1.3M-face file.
    long index = 0;
    const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), index);
    if (digits.empty() || ec != std::errc() || end != digits.data() + digits.size()) {
      const std::string part(digits);
      char* after = nullptr;
      index = std::strtol(part.c_str(), &after, 10);
      if (part.empty() || *after != '\0') {
        return "face vertex '" + std::string(token) + "' is not made of integer indices";
      }
    }
    if (index == 0) {
      return "face vertex '" + std::string(token) + "': index 0 (OBJ indices start at 1; negative ones count back)";
    }
    if (index < 0 && index < -read[kind]) {  // (not -index: the most negative long has no negation)
      return "relative " + std::string(kKinds[kind]) + " index " + std::string(digits) +
             " reaches before the first " + kKinds[kind] + " (" + std::to_string(read[kind]) + " read so far)";
    }
    if (index > largest[kind].value) largest[kind] = {index, line, std::string(token), std::string(digits)};
  }
  return "";
}

Prescan prescan(std::string_view text, const std::string& name) {
  Prescan out;
  constexpr std::size_t kMaxErrors = 20;
  int line = 0;
  long read[3] = {0, 0, 0};  // vertices, texture coordinates, normals so far
  std::size_t pos = 0;
  while (pos < text.size() && out.errors.size() < kMaxErrors) {
    ++line;
    std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    std::string_view l = text.substr(pos, end - pos);
    pos = end + 1;
    std::size_t i = 0;
    while (i < l.size() && is_blank(l[i])) ++i;
    if (i + 2 < l.size() && l[i] == 'v' && (l[i + 1] == 't' || l[i + 1] == 'n') && is_blank(l[i + 2])) {
      ++read[l[i + 1] == 't' ? 1 : 2];
      continue;
    }
    if (i + 1 >= l.size() || !is_blank(l[i + 1])) continue;
    if (l[i] == 'f') {
      int vertices = 0;
      std::string problem;
      for (std::size_t j = i + 1; j < l.size();) {
        while (j < l.size() && is_blank(l[j])) ++j;
        if (j >= l.size() || l[j] == '#') break;
        ++vertices;
        const std::size_t begin = j;
        while (j < l.size() && !is_blank(l[j])) ++j;
        if (problem.empty()) problem = check_face_vertex(l.substr(begin, j - begin), read, out.largest, line);
      }
      if (!problem.empty()) out.errors.push_back(line_diagnostic(name, line, problem));
      if (vertices >= 3) {
        out.face_lines.push_back(line);
        out.max_triangles += static_cast<std::size_t>(vertices - 2);
      }
    } else if (l[i] == 'v') {
      ++read[0];
      // Three coordinates (std::from_chars: correctly rounded, and several times faster than strtod).
      const char* p = l.data() + i + 1;
      const char* const stop = l.data() + l.size();
      for (int k = 0; k < 3; ++k) {
        while (p < stop && is_blank(*p)) ++p;
        const char* token_end = p;
        while (token_end < stop && !is_blank(*token_end)) ++token_end;
        double x = 0;
        const char* number = p < token_end && *p == '+' ? p + 1 : p;
        const auto [after, ec] = double_from_chars(number, token_end, x);
        if (ec != std::errc() || after != token_end || !std::isfinite(x)) {
          const std::string token(p, token_end);
          out.errors.push_back(line_diagnostic(name, line,
                                "vertex coordinate " + std::to_string(k + 1) +
                                    " must be a finite number (got " + (token.empty() ? "nothing" : "'" + token + "'") +
                                    ")"));
          break;
        }
        out.vertices.push_back(x);
        p = token_end;
      }
    }
  }
  // A positive index may name an element further down, so the largest of each kind is checked
  // against the whole file's count here, in the file's own digits (tinyobjloader keeps indices
  // in an int, where 99999999999 would wrap).
  static const char* const kWhat[3][2] = {{"vertex", "vertices"}, {"texture", "texture coordinates"}, {"normal", "normals"}};
  for (const int kind : {0, 2}) {  // texture coordinates are not used: their indices are not checked
    const LargestIndex& big = out.largest[kind];
    if (big.value <= read[kind] || out.errors.size() >= kMaxErrors) continue;
    out.errors.push_back(line_diagnostic(name, big.line,
                                         std::string(kWhat[kind][0]) + " index " + big.digits + " is out of range (the file has " +
                                             std::to_string(read[kind]) + " " +
                                             (read[kind] == 1 ? kWhat[kind][0] : kWhat[kind][1]) + ")"));
  }
  std::sort(out.errors.begin(), out.errors.end(), [](const Diagnostic& a, const Diagnostic& b) { return a.line < b.line; });
  return out;
}

// The numbers of an MTL's colour and scalar statements that tinyobjloader would replace without
// a word (it reads "nan" as 0) or that the mapping replaces (negative, out of range): a warning
// for each, with the number as the file wrote it and what is used instead.
std::vector<Diagnostic> mtl_value_warnings(std::string_view text, const std::string& file) {
  struct Rule {
    std::string_view key;
    double lo, hi;               // the range kept
    std::string_view instead;    // what a value outside it becomes
  };
  static constexpr Rule kRules[] = {
      {"Ka", 0, 1e300, "0"}, {"Kd", 0, 1e300, "0"}, {"Ks", 0, 1e300, "0"}, {"Ke", 0, 1e300, "0"}, {"Tf", 0, 1e300, "0"},
      {"Ns", 0, 1e300, "0"}, {"Ni", 1e-300, 1e300, "1.5"}, {"d", 0, 1, "the nearest of 0 and 1"},
      {"Tr", 0, 1, "the nearest of 0 and 1"}};
  constexpr std::size_t kMaxWarnings = 50;
  std::vector<Diagnostic> out;
  std::string material = "(before any newmtl)";
  int line = 0;
  for (std::size_t pos = 0; pos < text.size() && out.size() < kMaxWarnings;) {
    ++line;
    std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view l = text.substr(pos, end - pos);
    pos = end + 1;
    std::vector<std::string_view> words;
    for (std::size_t i = 0; i < l.size();) {
      while (i < l.size() && is_blank(l[i])) ++i;
      const std::size_t b = i;
      while (i < l.size() && !is_blank(l[i])) ++i;
      if (i > b) words.push_back(l.substr(b, i - b));
    }
    if (words.empty() || words[0][0] == '#') continue;
    if (words[0] == "newmtl" && words.size() > 1) {
      material = std::string(words[1]);
      continue;
    }
    const Rule* rule = nullptr;
    for (const Rule& r : kRules) {
      if (r.key == words[0]) rule = &r;
    }
    if (rule == nullptr) continue;
    for (std::size_t w = 1; w < words.size() && w <= 3; ++w) {
      const std::string_view word = words[w];
      if (word == "spectral" || word == "xyz") break;  // other notations: not numbers to check
      double x = 0;
      const char* first = word.data() + (word[0] == '+' ? 1 : 0);
      const auto [after, ec] = double_from_chars(first, word.data() + word.size(), x);
      std::string why;
      if (ec != std::errc() || after != word.data() + word.size() || !std::isfinite(x)) {
        why = "is not a finite number";
      } else if (x < rule->lo || x > rule->hi) {
        why = rule->lo > 0 ? "must be > 0" : rule->hi <= 1 ? "must be in 0..1" : "must be >= 0";
      }
      if (why.empty()) continue;
      out.push_back(line_diagnostic(file, line,
                                    "material '" + material + "': " + std::string(rule->key) + " " + std::string(word) + " " +
                                        why + "; using " + std::string(rule->instead),
                                    Diagnostic::Severity::kWarning));
    }
  }
  return out;
}

// What a mesh will hold, counted before it is parsed (for the memory estimate): `v` and `vn`
// lines, and the triangles of the fans of `f` lines (vertices - 2 each).
struct ObjCounts {
  std::size_t vertices = 0, normals = 0, triangles = 0;
};
ObjCounts count_obj(std::string_view text) {
  ObjCounts c;
  for (std::size_t pos = 0; pos < text.size();) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    std::size_t i = pos;
    while (i < end && is_blank(text[i])) ++i;
    if (i + 1 < end && text[i] == 'v' && is_blank(text[i + 1])) {
      ++c.vertices;
    } else if (i + 2 < end && text[i] == 'v' && text[i + 1] == 'n' && is_blank(text[i + 2])) {
      ++c.normals;
    } else if (i + 1 < end && text[i] == 'f' && is_blank(text[i + 1])) {
      std::size_t corners = 0;
      for (std::size_t j = i + 1; j < end && text[j] != '#';) {
        while (j < end && is_blank(text[j])) ++j;
        if (j < end && text[j] != '#') ++corners;
        while (j < end && !is_blank(text[j])) ++j;
      }
      if (corners >= 3) c.triangles += corners - 2;
    }
    pos = end + 1;
  }
  return c;
}

// The OBJ text as a stream for tinyobjloader, read in place (std::istringstream would copy it:
// 55 MB for a 1.3M-triangle mesh). Only the get area is used, so the text is never written.
class TextStreamBuf final : public std::streambuf {
 public:
  explicit TextStreamBuf(const std::string& text) {
    char* begin = const_cast<char*>(text.data());
    setg(begin, begin, begin + text.size());
  }
};

// tinyobjloader's messages end in "(line N.)", "line N.)" or "line: N"; split them into our
// problems, with N as their line.
void add_messages(const std::string& text, const std::string& file, std::vector<Diagnostic>& to) {
  std::istringstream in(text);
  std::string msg;
  while (std::getline(in, msg)) {
    while (!msg.empty() && (msg.back() == '\r' || msg.back() == ' ')) msg.pop_back();
    if (msg.empty() || msg == ".") continue;
    int line = 0;
    if (const std::size_t at = msg.rfind("line"); at != std::string::npos) {
      std::size_t j = at + 4;
      while (j < msg.size() && (msg[j] == ' ' || msg[j] == ':')) ++j;
      long n = 0;
      std::size_t digits = 0;
      while (j < msg.size() && msg[j] >= '0' && msg[j] <= '9' && digits < 9) {
        n = 10 * n + (msg[j++] - '0');
        ++digits;
      }
      if (digits > 0) line = static_cast<int>(n);
    }
    to.push_back(line_diagnostic(file, line, msg));
  }
}

// Reads the MTL files an OBJ names through the caller's FileReader, and remembers which
// could not be read (a warning each, then the default material).
class MtlReader final : public tinyobj::MaterialReader {
 public:
  MtlReader(const FileReader& read, std::vector<Diagnostic>& warnings, const std::string& obj_name)
      : read_(read), warnings_(warnings), obj_name_(obj_name) {}

  bool operator()(const std::string& mat_id, std::vector<tinyobj::material_t>* materials,
                  std::map<std::string, int>* mat_map, std::string* warn, std::string* err) override {
    std::string error;
    const std::optional<std::string> text = read_ ? read_(mat_id, error) : std::nullopt;
    if (!text) {
      warnings_.push_back(line_diagnostic(obj_name_, 0, "cannot read material library '" + mat_id + "'" +
                                             (error.empty() ? "" : ": " + error) +
                                             "; its faces get the default material"));
      return false;
    }
    for (Diagnostic& w : mtl_value_warnings(*text, mat_id)) warnings_.push_back(std::move(w));
    std::istringstream stream(*text);
    std::string mtl_warn;
    tinyobj::LoadMtl(mat_map, materials, &stream, &mtl_warn, err);
    add_messages(mtl_warn, mat_id, warnings_);
    if (warn) warn->clear();
    return true;
  }

 private:
  const FileReader& read_;
  std::vector<Diagnostic>& warnings_;
  const std::string& obj_name_;
};

// A coefficient from the MTL: finite and >= 0, else 0 (mtl_value_warnings said so, at its line).
double coefficient(double x) { return std::isfinite(x) && x >= 0 ? x : 0; }

Color mtl_color(const double c[3]) { return Color(coefficient(c[0]), coefficient(c[1]), coefficient(c[2])); }

// The MTL mapping (docs/scene-format.md has it as a table).
Material map_material(const tinyobj::material_t& m, NsMapping ns) {
  Material out;
  out.name = m.name;
  out.ka = mtl_color(m.ambient);
  out.kd = mtl_color(m.diffuse);
  out.ks = mtl_color(m.specular);
  const double shininess = coefficient(m.shininess);
  out.n = ns == NsMapping::kBlinnToPhong ? shininess / 4 : shininess;
  out.ior = std::isfinite(m.ior) && m.ior > 0 ? m.ior : 1.5;
  const int illum = m.illum;
  // illum 3..7 trace a mirror ray weighted by Ks; 4, 6 and 7 also refract; 5 and 7 weight
  // both by Fresnel.
  const bool reflective = illum >= 3 && illum <= 7;
  const bool refractive = illum == 4 || illum == 6 || illum == 7;
  if (reflective) out.kr = out.ks;
  // Tf as 3ds Max writes it and as the Cornell boxes' author reads it (G3D's ParseMTL): 1 - the
  // transmitted fraction, so Tf 1 (or none) is opaque; the Wavefront spec calls it the transmitted
  // fraction itself, but the files met in practice follow Max. d is the opaque fraction (coverage):
  // light passes where neither blocks it, kt = 1 - d*Tf, for glass illums and for d below 1.
  const Color tf = mtl_color(m.transmittance);
  const double dissolve = std::isfinite(m.dissolve) ? std::clamp(m.dissolve, 0.0, 1.0) : 1.0;
  const Color blocked = is_zero(tf) ? Color(1) : glm::min(tf, Color(1));  // tinyobjloader's 0 0 0: no Tf
  if (dissolve < 1 || refractive) out.kt = Color(1) - dissolve * blocked;
  // Ks is also the mirror weight, but a surface cannot send on more light than it receives: kr is
  // kept to at most 1 - kt per channel. Without it an MTL glass of Ks 0.3 and Tf 0.1 gains 20 % at
  // every total internal reflection (kr' + kt' = kr + kt = 1.2), and deep paths grow without bound.
  out.kr = glm::min(out.kr, glm::max(Color(1) - out.kt, Color(0)));
  out.fresnel = illum == 5 || illum == 7;
  return out;
}

// An index-bound check as one message. Positive indices may refer to elements further down the
// file, so they are checked against the file's count; relative ones the prescan checked.
std::string index_error(const char* what, const char* plural, int index, std::size_t count) {
  if (index < 0) return std::string("a relative ") + what + " index reaches before the first " + what;
  return std::string(what) + " index " + std::to_string(index + 1) + " is out of range (the file has " +
         std::to_string(count) + " " + (count == 1 ? what : plural) + ")";
}

// tinyobjloader's parse and the prescan of the same text, on two threads at once.
struct Parsed {
  Prescan pre;
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> mtl;
  std::string warn, err;
  bool ok = false;
};

// A file the prescan rejects is parsed for nothing, but it is then reported as before, with
// the prescan's errors only. MTL warnings go to `mtl_warnings`.
Parsed parse_obj(const std::string& obj_text, const std::string& obj_name, const FileReader& read_mtl,
                 const TriangleCountHook& on_prescan, std::vector<Diagnostic>& mtl_warnings) {
  Parsed p;
  in_parallel(
      [&] {
        p.pre = prescan(obj_text, obj_name);
        if (p.pre.errors.empty() && on_prescan) on_prescan(p.pre.max_triangles);
      },
      [&] {
        TextStreamBuf buffer(obj_text);
        std::istream stream(&buffer);
        MtlReader reader(read_mtl, mtl_warnings, obj_name);
        p.ok = tinyobj::LoadObj(&p.attrib, &p.shapes, &p.mtl, &p.warn, &p.err, &stream, &reader,
                                /*triangulate=*/false, /*default_vcols_fallback=*/false);
      });
  return p;
}

// tinyobjloader's own warnings (a `usemtl` naming no material of the MTL, faces of fewer than 3
// vertices), once each; index bounds are errors below and unreadable MTLs have one warning
// already. Then the warnings of mapping the MTL's materials.
void add_parse_warnings(const Parsed& p, const std::string& obj_name, NsMapping ns, ObjIndexedMesh& out) {
  for (Diagnostic& w : out.warnings) {
    if (w.file.empty()) w.file = obj_name;
  }
  std::vector<Diagnostic> parse_warnings;
  add_messages(p.warn, obj_name, parse_warnings);
  for (Diagnostic& w : parse_warnings) {
    if (w.message.find("out of bounds") != std::string::npos ||
        w.message.starts_with("Failed to load material file")) {
      continue;
    }
    const bool seen = std::any_of(out.warnings.begin(), out.warnings.end(),
                                  [&](const Diagnostic& o) { return o.message == w.message; });
    if (!seen) out.warnings.push_back(std::move(w));
  }
  for (const tinyobj::material_t& m : p.mtl) out.materials.push_back(map_material(m, ns));
}

// Per material: the area, area-weighted centroid and face count of its faces (for emitters).
struct EmitterSums {
  std::vector<double> area;
  std::vector<Vec3> sum;
  std::vector<int> faces;
  explicit EmitterSums(std::size_t n) : area(n, 0.0), sum(n, Vec3(0)), faces(n, 0) {}
  void add_material() {
    area.push_back(0);
    sum.emplace_back(0);
    faces.push_back(0);
  }
};

// A fan from the first vertex of the face at `offset` (n corners): exact for the convex quads
// and polygons real files hold.
void add_fan(const std::vector<tinyobj::index_t>& indices, std::size_t offset, std::size_t n, bool smooth,
             int material, int face, ObjIndexedMesh& out, EmitterSums& emitters) {
  const tinyobj::index_t i0 = indices[offset];
  for (std::size_t k = 1; k + 1 < n; ++k) {
    const tinyobj::index_t i1 = indices[offset + k];
    const tinyobj::index_t i2 = indices[offset + k + 1];
    ObjIndexedTriangle tri;
    tri.v = {static_cast<std::uint32_t>(i0.vertex_index), static_cast<std::uint32_t>(i1.vertex_index),
             static_cast<std::uint32_t>(i2.vertex_index)};
    tri.n = smooth ? std::array<std::int32_t, 3>{i0.normal_index, i1.normal_index, i2.normal_index}
                   : std::array<std::int32_t, 3>{-1, -1, -1};
    tri.material = material;
    tri.face = face;
    const Vec3& v0 = out.vertices[tri.v[0]];
    const Vec3& v1 = out.vertices[tri.v[1]];
    const Vec3& v2 = out.vertices[tri.v[2]];
    const Vec3 cross = glm::cross(v1 - v0, v2 - v0);
    const double area2 = glm::length(cross);
    if (!(area2 > 0) || !std::isfinite(area2)) {
      ++out.skipped_degenerate;
      continue;
    }
    const auto m = static_cast<std::size_t>(material);
    emitters.area[m] += area2;
    emitters.sum[m] += area2 * (v0 + v1 + v2) / 3.0;
    out.triangles.push_back(tri);
  }
}

// The faces of every shape as fans of triangles, zero-area ones left out. Returns false when
// enough errors were found to stop.
bool add_faces(const Parsed& p, const std::string& obj_name, ObjIndexedMesh& out, EmitterSums& emitters) {
  const std::size_t vertex_count = out.vertices.size();
  const std::size_t normal_count = out.normals.size();
  std::size_t total_faces = 0;
  std::size_t triangle_count = 0;
  for (const tinyobj::shape_t& s : p.shapes) {
    total_faces += s.mesh.num_face_vertices.size();
    for (const unsigned char n : s.mesh.num_face_vertices) triangle_count += n >= 3 ? n - 2u : 0u;
  }
  // Our count of face lines matches tinyobjloader's faces unless the file uses a syntax we
  // do not scan (line continuations): then errors name the face number instead of a line.
  const bool lines_known = total_faces == p.pre.face_lines.size();
  out.triangles.reserve(triangle_count);
  int default_material = -1;
  int face = 0;
  for (const tinyobj::shape_t& s : p.shapes) {
    std::size_t offset = 0;
    for (std::size_t f = 0; f < s.mesh.num_face_vertices.size(); ++f, ++face) {
      const std::size_t n = s.mesh.num_face_vertices[f];
      const int line = lines_known ? p.pre.face_lines[static_cast<std::size_t>(face)] : 0;
      const auto fail = [&](const std::string& message) {
        out.errors.push_back(line_diagnostic(obj_name, line, lines_known ? message : "face " + std::to_string(face + 1) + ": " + message));
      };
      bool face_ok = true;
      bool smooth = true;
      for (std::size_t k = 0; k < n; ++k) {
        const tinyobj::index_t idx = s.mesh.indices[offset + k];
        if (idx.vertex_index < 0 || static_cast<std::size_t>(idx.vertex_index) >= vertex_count) {
          fail(index_error("vertex", "vertices", idx.vertex_index, vertex_count));
          face_ok = false;
          break;
        }
        if (idx.normal_index >= 0 && static_cast<std::size_t>(idx.normal_index) >= normal_count) {
          fail(index_error("normal", "normals", idx.normal_index, normal_count));
          face_ok = false;
          break;
        }
        if (idx.normal_index < 0) smooth = false;
      }
      if (out.errors.size() >= 20) return false;  // enough to go on
      if (!face_ok) {
        offset += n;
        continue;
      }
      int material = f < s.mesh.material_ids.size() ? s.mesh.material_ids[f] : -1;
      if (material < 0 || static_cast<std::size_t>(material) >= out.materials.size()) {
        if (default_material < 0) {
          default_material = static_cast<int>(out.materials.size());
          out.materials.push_back(default_mesh_material());
          emitters.add_material();
        }
        material = default_material;
      }
      add_fan(s.mesh.indices, offset, n, smooth, material, face, out, emitters);
      ++emitters.faces[static_cast<std::size_t>(material)];
      offset += n;
    }
  }
  return true;
}

}  // namespace

ObjIndexedMesh load_obj_indexed(const std::string& obj_text, const std::string& obj_name, const FileReader& read_mtl,
                                NsMapping ns, const TriangleCountHook& on_prescan) {
  ObjIndexedMesh out;
  const auto finish = [&out]() -> ObjIndexedMesh {
    set_severity(out.warnings, Diagnostic::Severity::kWarning);
    return std::move(out);
  };
  // Refused before anything is allocated when it would not fit (the kernel would kill us instead).
  const ObjCounts counts = count_obj(obj_text);
  const std::string refusal = refuse_if_too_large(
      mesh_bytes_needed(counts.vertices, counts.normals, counts.triangles), "the mesh",
      counted(counts.triangles, "triangle") + ", " + counted(counts.vertices, "vertex", "vertices"));
  if (!refusal.empty()) {
    out.errors.push_back(line_diagnostic(obj_name, 0, refusal));
    return finish();
  }
  Parsed p = parse_obj(obj_text, obj_name, read_mtl, on_prescan, out.warnings);
  if (!p.pre.errors.empty()) {
    out.warnings.clear();  // the MTL's: only the errors of a file the prescan rejects
    out.errors = std::move(p.pre.errors);
    return finish();
  }
  if (!p.ok) {
    add_messages(p.err.empty() ? "cannot parse the file" : p.err, obj_name, out.errors);
    return finish();
  }
  // tinyobjloader's own number parser is off by up to a few ulps for about half of all decimal
  // coordinates ("-1.9159" reads as -1.9158999999999997); the prescan's from_chars values are the
  // doubles nearest to what the file says.
  if (p.pre.vertices.size() == p.attrib.vertices.size()) p.attrib.vertices = std::move(p.pre.vertices);
  add_parse_warnings(p, obj_name, ns, out);
  const std::vector<double>& xyz = p.attrib.vertices;
  out.vertices.resize(xyz.size() / 3);
  for (std::size_t i = 0; i < out.vertices.size(); ++i) out.vertices[i] = Vec3(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
  const std::vector<double>& nxyz = p.attrib.normals;
  out.normals.resize(nxyz.size() / 3);
  for (std::size_t i = 0; i < out.normals.size(); ++i) out.normals[i] = Vec3(nxyz[3 * i], nxyz[3 * i + 1], nxyz[3 * i + 2]);
  p.attrib = {};
  EmitterSums emitters(out.materials.size());
  if (!add_faces(p, obj_name, out, emitters)) return finish();
  if (out.skipped_degenerate > 0) {
    out.warnings.push_back(line_diagnostic(obj_name, 0, std::to_string(out.skipped_degenerate) +
                                             " zero-area triangles left out"));
  }
  for (std::size_t i = 0; i < p.mtl.size(); ++i) {
    const Color ke(p.mtl[i].emission[0], p.mtl[i].emission[1], p.mtl[i].emission[2]);
    if (!(max_channel(ke) > 0) || !(emitters.area[i] > 0)) continue;
    Emitter e;
    e.material = p.mtl[i].name;
    e.ke = ke;
    e.centroid = emitters.sum[i] / emitters.area[i];
    e.faces = emitters.faces[i];
    out.emitters.push_back(e);
  }
  return finish();
}

Triangle ObjIndexedMesh::triangle(std::size_t i) const {
  const ObjIndexedTriangle& t = triangles[i];
  Triangle tri;
  tri.v0 = vertices[t.v[0]];
  tri.v1 = vertices[t.v[1]];
  tri.v2 = vertices[t.v[2]];
  tri.material = t.material;
  if (t.n[0] >= 0) {
    tri.has_vertex_normals = true;
    tri.n0 = normals[static_cast<std::size_t>(t.n[0])];
    tri.n1 = normals[static_cast<std::size_t>(t.n[1])];
    tri.n2 = normals[static_cast<std::size_t>(t.n[2])];
  }
  return tri;
}

}  // namespace phonglab
