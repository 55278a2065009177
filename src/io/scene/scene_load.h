// The scene loader's parts shared between its files (src/io/scene/scene_*.cpp): the text helpers
// and the syntax pass (scene_text.cpp), the position index, the mesh files (scene_files.cpp) and
// the validation (scene_validate.cpp). Internal to phonglab_io: nothing outside src/io/
// includes it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "io/embedded_scenes.h"
#include "io/obj_io.h"
#include "io/scene/scene_io.h"

namespace phonglab::scene_load {

using Json = nlohmann::json;

inline constexpr int kMaxNesting = 64;            // deeper arrays/objects are rejected before parsing
inline constexpr double kMaxMagnitude = 1e100;    // keeps every product of two scene values finite
inline constexpr std::size_t kMaxShown = 60;      // bytes of an offending value quoted in a message
inline constexpr std::size_t kMaxIssues = 100;    // errors collected before validation stops
inline constexpr std::size_t kMaxFileBytes = std::size_t{256} << 20;  // /dev/zero must not hang us
inline constexpr std::size_t kMaxTextBytes = std::size_t{1} << 31;    // offsets fit PosNode's 32 bits
inline constexpr std::size_t kNoOffset = std::numeric_limits<std::size_t>::max();
inline constexpr int kMaxDepthLimit = 100;        // max_depth range is 0..kMaxDepthLimit
inline constexpr int kMaxImageSide = 16384;       // image width/height range is 1..kMaxImageSide
inline constexpr std::size_t kMaxMeshFileBytes = std::size_t{1} << 31;  // a 1.3M-triangle OBJ is ~100 MB

// The loader's types (defined below).
struct Overflow;
struct Prescan;
struct Issue;
struct PosNode;
class PosIndex;
struct SceneFiles;
struct MeshLoad;
class Issues;

bool is_digit(char c);
bool is_space(char c);
bool is_word_char(char c);
char to_lower(char c);
bool has_bom(std::string_view t);
std::string truncated(std::string s);
std::string json_string(std::string_view s);
std::string compact_source(std::string_view t, std::size_t begin, std::size_t end);
std::string describe_byte(unsigned char c);
std::string printable(std::string_view s);
std::size_t edit_distance(std::string_view a, std::string_view b);
std::optional<std::string_view> closest(std::string_view word,
                                        std::span<const std::string_view> candidates);
std::string suggestion(std::string_view word, std::span<const std::string_view> candidates,
                       std::string_view list_intro);
std::string member_path(const std::string& parent, std::string_view key);
std::string element_path(const std::string& parent, std::size_t i);
std::size_t number_length(std::string_view t, std::size_t i);
bool number_overflows(std::string_view tok);
Prescan prescan(std::string_view t);
std::size_t word_start(std::string_view t, std::size_t off);
std::size_t word_end(std::string_view t, std::size_t start);
std::size_t string_start(std::string_view t, std::size_t close);
std::string expectation(std::string_view context, std::string_view expected);
Issue syntax_issue(std::string_view t, const Json::parse_error& e, const Prescan& pre);

std::string os_reason(int err);
std::optional<std::string> read_text_file(const std::string& path, std::size_t limit, std::string& error);
glm::dmat3 rotation_of(const MeshTransform& t);
MeshLoad load_mesh(const SceneFiles& files, const std::string& file, const MeshTransform& transform,
                   NsMapping ns, int override_material, int material_base,
                   const std::unordered_map<std::string, int>& defined);

// Pass 4 and the whole load: diagnostics from issues, and one text to a LoadResult.
std::vector<Diagnostic> to_diagnostics(std::string_view t, std::vector<Issue> issues,
                                       bool truncated, const std::string& file);
LoadResult fail(const std::string& file, std::string message);
LoadResult load_text(const std::string& text, const std::string& file_name, const SceneFiles& files);

// Text helpers, suggestions and JSON paths; pass 1 (prescan) and pass 2 (syntax errors).
// A number token replaced before parsing because it overflows double.
struct Overflow {
  std::size_t offset;  // first byte of the token
  std::size_t length;  // bytes of the token
};

struct Prescan {
  std::size_t too_deep = kNoOffset;     // first bracket nested deeper than kMaxNesting
  std::size_t nul = kNoOffset;          // first NUL byte (nlohmann would stop reading there)
  std::size_t open_string = kNoOffset;  // opening quote of a string still open at the end
  std::vector<Overflow> overflows;      // in text order
};

// An error before line/column are known: a byte offset into the text.
struct Issue {
  std::size_t offset = kNoOffset;
  std::string path;
  std::string message;
};

// Where one JSON value sits in the text. 32-bit fields keep the index small for 10 MB inputs;
// load_text rejects texts of kMaxTextBytes or more, so every offset fits.
struct PosNode {
  std::uint32_t begin = 0;        // first byte of the value
  std::uint32_t end = 0;          // one past its last byte
  std::uint32_t key_begin = 0;    // opening quote of its key, for object members
  std::uint32_t child_begin = 0;  // first entry in PosIndex::children_
  std::uint32_t child_count = 0;  // members or elements, in file order
};

// Maps every value of a valid JSON text to its offsets, and every member to its key's offset:
// together with the DOM this is the map from JSON path to position. Built iteratively.
class PosIndex {
 public:
  explicit PosIndex(std::string_view text) : text_(text) { build(); }

  std::size_t begin(std::size_t id) const { return nodes_[id].begin; }
  std::size_t end(std::size_t id) const { return nodes_[id].end; }
  std::size_t key_begin(std::size_t id) const { return nodes_[id].key_begin; }

  std::span<const std::uint32_t> children(std::size_t id) const {
    const PosNode& n = nodes_[id];
    return std::span<const std::uint32_t>(children_).subspan(n.child_begin, n.child_count);
  }

  // The decoded key of an object member.
  std::string key(std::size_t id) const {
    const std::size_t b = nodes_[id].key_begin;
    const std::string_view raw = text_.substr(b, string_end(b) - b);
    if (raw.find('\\') == std::string_view::npos) return std::string(raw.substr(1, raw.size() - 2));
    return Json::parse(raw).get<std::string>();  // escapes decode exactly as the DOM's keys did
  }

 private:
  // A container still being read.
  struct Open {
    std::uint32_t node;
    bool is_object;
    bool expect_key;
    std::uint32_t key_begin;
    std::vector<std::uint32_t> kids;
  };

  std::size_t string_end(std::size_t i) const {
    ++i;
    while (i < text_.size() && text_[i] != '"') i += (text_[i] == '\\') ? 2 : 1;
    return std::min(i + 1, text_.size());
  }

  static std::uint32_t u32(std::size_t x) { return static_cast<std::uint32_t>(x); }

  std::uint32_t add(std::vector<Open>& stack, std::size_t begin, std::size_t end) {
    PosNode n;
    n.begin = u32(begin);
    n.end = u32(end);
    const std::uint32_t id = u32(nodes_.size());
    if (!stack.empty()) {
      Open& top = stack.back();
      if (top.is_object) n.key_begin = top.key_begin;
      top.kids.push_back(id);
    }
    nodes_.push_back(n);
    return id;
  }

  void build() {
    std::vector<Open> stack;
    std::size_t i = has_bom(text_) ? 3 : 0;
    bool root_done = false;
    while (i < text_.size() && !root_done) {
      const char c = text_[i];
      if (is_space(c) || c == ':') {
        ++i;
      } else if (c == ',') {
        if (!stack.empty() && stack.back().is_object) stack.back().expect_key = true;
        ++i;
      } else if (c == '"') {
        const std::size_t end = string_end(i);
        if (!stack.empty() && stack.back().is_object && stack.back().expect_key) {
          stack.back().expect_key = false;
          stack.back().key_begin = u32(i);
        } else {
          add(stack, i, end);
          root_done = stack.empty();
        }
        i = end;
      } else if (c == '{' || c == '[') {
        const std::uint32_t id = add(stack, i, i + 1);
        stack.push_back({id, c == '{', c == '{', 0, {}});
        ++i;
      } else if (c == '}' || c == ']') {
        if (stack.empty()) break;
        Open& top = stack.back();
        PosNode& n = nodes_[top.node];
        n.end = u32(i + 1);
        n.child_begin = u32(children_.size());
        n.child_count = u32(top.kids.size());
        children_.insert(children_.end(), top.kids.begin(), top.kids.end());
        stack.pop_back();
        root_done = stack.empty();
        ++i;
      } else {
        const std::size_t end = std::max(word_end(text_, i), i + 1);
        add(stack, i, end);
        root_done = stack.empty();
        i = end;
      }
    }
  }

  std::string_view text_;
  std::vector<PosNode> nodes_;            // node 0 is the root value
  std::vector<std::uint32_t> children_;   // each container's children, contiguous
};

// Passes 1 to 3 over one JSON text: the DOM, the number tokens patched because they overflow,
// and the position index.
struct ParsedText {
  std::string patched;             // the text with overflowing numbers replaced, when there were any
  Json root;
  std::vector<Overflow> overflows;
  std::optional<PosIndex> index;   // over the parsed text (`patched` or the original)
};
// Runs passes 1 to 3 over `text` into `out`; false (the problems in `issues`) when the text is
// not JSON. `kind` names what the file should be in messages ("a scene file").
bool parse_text(const std::string& text, std::string_view kind, Issues& issues, ParsedText& out);

// Mesh files and other files a scene names.
// Where a scene's mesh files come from: the disk, relative to the scene file's folder, or the
// files compiled in beside the embedded scenes.
struct SceneFiles {
  std::string base_dir = ".";
  bool embedded = false;
  const FileReader* reader = nullptr;  // set: every file comes from it (load_scene_text_with)

  // `relative` as written in the scene (or in an OBJ's mtllib, joined to the OBJ's folder).
  std::optional<std::string> read(const std::string& relative, std::string& error) const {
    namespace fs = std::filesystem;
    if (reader != nullptr) return (*reader)(relative, error);
    const fs::path p(relative);
    if (embedded && !p.is_absolute()) {  // an absolute path (a mesh added to an embedded scene) is on disk
      const std::string key = p.lexically_normal().generic_string();
      if (auto text = embedded_file(key)) return text;
      error = "no such embedded file";
      return std::nullopt;
    }
    const std::string path = resolve(relative);
    std::error_code ec;
    if (fs::exists(path, ec) && !fs::is_regular_file(path, ec)) {
      error = "not a regular file";  // a device such as /dev/zero would be read for ever
      return std::nullopt;
    }
    return read_text_file(path, kMaxMeshFileBytes, error);
  }

  // The absolute path `relative` names on disk; empty for embedded files.
  std::string resolve(const std::string& relative) const {
    namespace fs = std::filesystem;
    if (embedded && !fs::path(relative).is_absolute()) return "";
    const fs::path p(relative);
    std::error_code ec;
    const fs::path full = fs::absolute(p.is_absolute() ? p : fs::path(base_dir) / p, ec);
    return ec ? (fs::path(base_dir) / p).string() : full.lexically_normal().string();
  }
};

struct MeshLoad {
  std::shared_ptr<const MeshGeometry> geometry;
  std::vector<Material> materials;  // the MTL's, to append to the scene's (none with an override)
  std::vector<Diagnostic> errors;   // the OBJ's and MTL's, and those of placing the mesh
  std::vector<Diagnostic> warnings;
  std::vector<Emitter> emitters;    // centroids in world coordinates
};

}  // namespace phonglab::scene_load
