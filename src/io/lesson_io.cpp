// Lesson files, read in the scene loader's passes (src/io/scene/scene_load.h): prescan, syntax,
// position index, then the LessonReader over the DOM, which reads a step's changes by the scene
// file's own rules (SceneMembers).
#include "io/lesson_io.h"

#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>
#include <map>
#include <new>
#include <string_view>

#include <nlohmann/json.hpp>

#include "io/embedded_scenes.h"
#include "io/scene/scene_io.h"
#include "io/scene/scene_load.h"
#include "io/scene/scene_reader.h"

namespace phonglab {

using namespace scene_load;

std::string LessonLoad::error_text() const { return diagnostics_text(errors); }

namespace {

constexpr std::array<std::string_view, 3> kLessonKeys = {"title", "description", "steps"};
constexpr std::array<std::string_view, 8> kStepKeys = {"title",    "caption", "scene",  "changes",
                                                      "show",     "question", "answer", "exercise"};
constexpr std::array<std::string_view, 4> kExerciseKeys = {"slot", "task", "starter", "hints"};
constexpr std::size_t kMaxHints = 16;
constexpr std::array<std::string_view, 6> kChangeKeys = {"materials", "lights", "camera", "max_depth", "ambient", "background"};
constexpr std::array<std::string_view, 11> kShowKeys = {"term", "small_multiples", "probe", "ray_tree", "depth_cut",
                                                        "head_angle_deg", "light_markers", "compare", "ambient", "mute",
                                                        "solo"};
constexpr std::array<std::string_view, 9> kAnswerShowKeys = {"term", "small_multiples", "probe", "ray_tree", "depth_cut",
                                                             "head_angle_deg", "light_markers", "compare", "ambient"};
constexpr std::array<std::string_view, 4> kAmbientChoices = {"constant", "indirect", "beside", "difference"};
constexpr std::array<std::string_view, 2> kAnswerKeys = {"caption", "show"};
constexpr std::array<std::string_view, 4> kCompareKeys = {"against", "view", "wipe", "gain"};
constexpr std::array<std::string_view, 2> kCompareViews = {"difference", "wipe"};
constexpr std::array<std::string_view, 9> kTermNames = {"full", "ambient", "diffuse", "specular", "reflection", "refraction",
                                                        "indirect", "normal", "depth"};
constexpr int kMaxSteps = 200;

class LessonReader : private SceneMembers {
 public:
  LessonReader(std::string_view original, const PosIndex& index, const Json& root, const std::vector<Overflow>& overflows,
               Issues& issues, std::string base_dir)
      : SceneMembers(original, index, root, overflows, issues), base_dir_(std::move(base_dir)) {}

  Lesson run() {
    Lesson lesson;
    const Val root{&root_, 0, ""};
    if (!root_.is_object()) {
      report(root, "the lesson must be a JSON object (got " + shown(root) + ")");
      return lesson;
    }
    const Fields top = fields(root, kLessonKeys);
    if (!require(root, top, {"title", "steps"})) return lesson;
    set(lesson.title, read_string(*top.find("title")));
    if (const Val* v = top.find("description")) set(lesson.description, read_string(*v));
    const Val& steps = *top.find("steps");
    if (!expect_array(steps)) return lesson;
    const std::size_t count = element_count(steps);
    if (count == 0 || count > kMaxSteps) {
      report(steps, "must hold 1 to " + std::to_string(kMaxSteps) + " steps (got " + std::to_string(count) + ")");
      return lesson;
    }
    for (std::size_t i = 0; i < count && !issues_.full(); ++i) lesson.steps.push_back(step(element(steps, i), i));
    check_compare_targets(lesson);
    return lesson;
  }

 private:
  LessonStep step(const Val& v, std::size_t i) {
    LessonStep s;
    if (!expect_object(v)) return s;
    const Fields f = fields(v, kStepKeys);
    require(v, f, {"title", "caption"});
    if (const Val* x = f.find("title")) set(s.title, read_string(*x));
    if (const Val* x = f.find("caption")) set(s.caption, read_string(*x));
    const Val* named = f.find("scene");
    if (named != nullptr) {
      set(scene_arg_, read_string(*named));
    } else if (i == 0) {
      report(v, "missing key \"scene\" (the first step names its scene; later steps keep the one before)");
    }
    s.scene = scene_arg_;
    // A scene is first loaded where a step names it; later steps keeping it reuse that load.
    const std::optional<Scene> base = scene_arg_.empty() ? std::nullopt : load(scene_arg_, named);
    if (!base) return s;
    s.prepared_scene = *base;
    if (const Val* x = f.find("changes")) changes(*x, s.prepared_scene);
    if (const Val* x = f.find("show")) view(*x, s.prepared_scene, s.view, true, i);
    s.answer_view = s.view;
    if (const Val* x = f.find("question")) set(s.question, read_string(*x));
    if (const Val* x = f.find("answer")) {
      if (s.question.empty()) report(*x, "an answer needs a \"question\" in its step");
      answer(*x, s, i);
    } else if (!s.question.empty()) {
      report(v, "missing key \"answer\" (a question's answer is revealed on the next key press)");
    }
    if (const Val* x = f.find("exercise")) {
      if (!s.question.empty()) report(*x, "a step is a question or an exercise, not both");
      s.exercise = exercise(*x);
    }
    return s;
  }

  // A step of kind "exercise": {"slot", "task", "starter", "hints"}.
  LessonExercise exercise(const Val& v) {
    LessonExercise e;
    if (!expect_object(v)) return e;
    const Fields f = fields(v, kExerciseKeys);
    require(v, f, {"slot", "task"});
    if (const Val* x = f.find("slot")) {
      set(e.slot, read_string(*x));
      const std::vector<std::string_view> slots = {"ambient", "diffuse", "specular"};
      if (!e.slot.empty() && std::find(slots.begin(), slots.end(), e.slot) == slots.end()) {
        report(*x, "unknown slot \"" + e.slot + "\"" + suggestion_for(e.slot, slots, "expected one of"));
      }
    }
    if (const Val* x = f.find("task")) set(e.task, read_string(*x));
    if (const Val* x = f.find("starter")) set(e.starter, read_string(*x));
    if (const Val* x = f.find("hints")) {
      if (!expect_array(*x)) return e;
      const std::size_t count = element_count(*x);
      if (count > kMaxHints) {
        report(*x, "at most " + std::to_string(kMaxHints) + " hints (got " + std::to_string(count) + ")");
        return e;
      }
      for (std::size_t i = 0; i < count; ++i) {
        std::string hint;
        set(hint, read_string(element(*x, i)));
        e.hints.push_back(std::move(hint));
      }
    }
    return e;
  }

  // The scene a step names, loaded once per lesson; reported at `at` when it does not load.
  std::optional<Scene> load(const std::string& arg, const Val* at) {
    if (const auto it = scenes_.find(arg); it != scenes_.end()) return it->second;
    const bool embedded = find_embedded_scene(arg) != nullptr;
    const std::filesystem::path file(arg);
    const std::filesystem::path path = file.is_absolute() ? file : (base_dir_ / file).lexically_normal();
    LoadResult r = embedded ? load_scene_arg(arg) : load_scene_file(path.string());
    if (!r.ok()) {
      std::string why = r.errors.empty() ? "it does not load" : r.errors.front().to_string();
      if (r.errors.size() > 1) why += " (and " + std::to_string(r.errors.size() - 1) + " more)";
      if (!embedded) why += misspelt_scene(arg, path);
      if (at != nullptr) report(*at, "the scene does not load: " + why);
    }
    return scenes_[arg] = r.scene;
  }

  // What follows "cannot read file" for a scene `arg` (resolved to `path`) that is neither
  // embedded nor an existing file: a bare name, the nearest embedded scene's; a path, the file
  // of the nearest name in its folder (as the lesson would write it), else the nearest
  // embedded scene's name for its stem. Empty when the file exists (it does not load: its own
  // errors say why).
  static std::string misspelt_scene(const std::string& arg, const std::filesystem::path& path) {
    std::error_code ec;
    if (std::filesystem::exists(path, ec)) return "";
    std::vector<std::string_view> embedded;
    for (const EmbeddedScene& e : embedded_scenes()) embedded.push_back(e.name);
    if (arg.find_first_of("/.") == std::string::npos) return "; not an embedded scene either" + suggestion(arg, embedded, "embedded scenes");
    std::vector<std::string> files;
    for (std::filesystem::directory_iterator it(path.parent_path().empty() ? "." : path.parent_path(), ec), end; !ec && it != end;
         it.increment(ec)) {
      std::error_code type_ec;
      if (it->is_regular_file(type_ec)) files.push_back(it->path().filename().string());
      if (files.size() >= 10000) break;  // a huge folder: the first ten thousand names are enough to guess from
    }
    std::sort(files.begin(), files.end());  // the same suggestion whatever order the folder lists them in
    const std::vector<std::string_view> names(files.begin(), files.end());
    const std::string name = path.filename().string();
    if (const auto near = closest(name, names)) {
      const std::string parent = std::filesystem::path(arg).parent_path().string();
      const std::string written = parent.empty() ? std::string(*near) : (std::filesystem::path(parent) / std::string(*near)).string();
      return " (did you mean " + json_string(written) + "?)";
    }
    if (const auto near = closest(path.stem().string(), embedded)) {
      return "; nor the embedded scene's name (did you mean " + json_string(*near) + "?)";
    }
    return "";
  }

  void changes(const Val& v, Scene& s) {
    if (!expect_object(v)) return;
    const Fields f = fields(v, kChangeKeys);
    if (const Val* x = f.find("camera")) read_camera(*x, s.camera);
    if (const Val* x = f.find("max_depth")) set(s.max_depth, read_int(*x, 0, kMaxDepthLimit));
    if (const Val* x = f.find("ambient")) set(s.ambient, read_color(*x));
    if (const Val* x = f.find("background")) set(s.background, read_color(*x));
    if (const Val* x = f.find("lights")) {
      if (expect_array(*x)) {
        std::vector<Light> lights;
        bool ok = true;
        for (std::size_t i = 0; i < element_count(*x); ++i) {
          auto light = read_light(element(*x, i));
          ok = light.has_value() && ok;
          if (light) lights.push_back(*light);
        }
        if (ok) s.lights = std::move(lights);
      }
    }
    if (const Val* x = f.find("materials")) {
      if (!expect_object(*x)) return;
      std::vector<std::string_view> names;
      for (const Material& m : s.materials) names.push_back(m.name);
      for (auto& [name, m] : members(*x)) {
        const std::string wanted = name;  // (clang 14 does not capture structured bindings)
        const auto it = std::find_if(s.materials.begin(), s.materials.end(), [&](const Material& mat) { return mat.name == wanted; });
        if (it == s.materials.end()) {
          issues_.add({index_.key_begin(m.node), m.path, "unknown material " + json_string(name) + suggestion(name, names, "the scene's materials")});
          continue;
        }
        read_material_fields(m, *it);
      }
    }
  }

  // "show" (with_lights: a step's, which may mute and solo lights in `scene`; else an answer's).
  void view(const Val& v, Scene& scene, StepView& out, bool with_lights, std::size_t step) {
    if (!expect_object(v)) return;
    const Fields f = with_lights ? fields(v, kShowKeys) : fields(v, kAnswerShowKeys);
    if (const Val* x = f.find("term")) {
      if (auto name = read_choice(*x, kTermNames, "term")) out.term = *term_from_name(*name);
    }
    if (const Val* x = f.find("small_multiples")) set(out.small_multiples, read_bool(*x));
    if (const Val* x = f.find("probe")) {
      if (auto p = pixel(*x, scene)) out.probe = p;
    }
    if (const Val* x = f.find("ray_tree")) {
      set(out.ray_tree, read_bool(*x));
      if (out.ray_tree && !out.probe) report(*x, "the ray tree is a probed pixel's: add \"probe\": [x, y]");
    }
    if (const Val* x = f.find("depth_cut")) {
      if (auto d = read_int(*x, 0, kMaxDepthLimit)) out.depth_cut = d;
    }
    if (const Val* x = f.find("head_angle_deg")) {
      if (auto a = read_number(*x)) {
        if (*a < -90 || *a > 90) report(*x, "must be in -90..90 degrees (got " + shown(*x) + ")");
        else out.head_angle_deg = a;
      }
    }
    if (const Val* x = f.find("light_markers")) set(out.light_markers, read_bool(*x));
    if (const Val* x = f.find("compare")) compare(*x, out, step);
    if (const Val* x = f.find("ambient")) {
      if (auto name = read_choice(*x, kAmbientChoices, "ambient")) {
        // "beside" and "difference": the indirect light beside ka·Ia, or their signed gap.
        out.ambient = *name == "constant" ? Ambient::kConstant : Ambient::kIndirect;
        out.ambient_shown = *name == "beside"       ? AmbientShown::kBeside
                            : *name == "difference" ? AmbientShown::kDifference
                                                    : AmbientShown::kImage;
      }
    }
    if (const Val* x = f.find("mute")) mute(*x, scene);
    if (const Val* x = f.find("solo")) {
      if (auto i = light_index(*x, scene)) {
        for (std::size_t l = 0; l < scene.lights.size(); ++l) scene.lights[l].enabled = static_cast<int>(l) == *i;
      }
    }
  }

  std::optional<std::array<int, 2>> pixel(const Val& v, const Scene& scene) {
    if (!v.json->is_array() || element_count(v) != 2) {
      report(v, "must be [x, y], a pixel of the scene's " + std::to_string(scene.width) + "x" + std::to_string(scene.height) +
                    " image (got " + shown(v) + ")");
      return std::nullopt;
    }
    const auto x = read_int(element(v, 0), 0, scene.width - 1);
    const auto y = read_int(element(v, 1), 0, scene.height - 1);
    if (!x || !y) return std::nullopt;
    return std::array<int, 2>{*x, *y};
  }

  std::optional<int> light_index(const Val& v, const Scene& scene) {
    if (scene.lights.empty()) {
      report(v, "the scene has no lights (got " + shown(v) + ")");
      return std::nullopt;
    }
    return read_int(v, 0, static_cast<int>(scene.lights.size()) - 1);
  }

  void mute(const Val& v, Scene& scene) {
    if (!expect_array(v)) return;
    for (std::size_t i = 0; i < element_count(v); ++i) {
      if (auto l = light_index(element(v, i), scene)) scene.lights[static_cast<std::size_t>(*l)].enabled = false;
    }
  }

  void compare(const Val& v, StepView& out, std::size_t step) {
    // "none": no compare (an answer that drops its question's).
    if (v.json->is_string() && v.json->get<std::string>() == "none") {
      out.compare = CompareView::kNone;
      return;
    }
    if (!expect_object(v)) return;
    const Fields f = fields(v, kCompareKeys);
    if (!require(v, f, {"against"})) return;
    out.compare = CompareView::kDifference;
    if (const Val* x = f.find("view")) {
      if (auto name = read_choice(*x, kCompareViews, "compare view")) out.compare = *name == "wipe" ? CompareView::kWipe : CompareView::kDifference;
    }
    const Val& against = *f.find("against");
    if (against.json->is_string() && against.json->get<std::string>() == "head") {
      out.compare_against = -1;
    } else if (against.json->is_number()) {
      if (auto n = read_int(against, 1, kMaxSteps)) {
        out.compare_against = *n - 1;
        if (static_cast<std::size_t>(*n - 1) == step) report(against, "a step cannot be compared with itself (got " + shown(against) + ")");
        compare_refs_.emplace_back(against, *n);
      }
    } else {
      report(against, "must be a step number or \"head\" (this step with the head not moved) (got " + shown(against) + ")");
    }
    if (const Val* x = f.find("wipe")) {
      if (auto w = read_number(*x)) {
        if (*w < 0 || *w > 1) report(*x, "must be in 0..1 (got " + shown(*x) + ")");
        else out.wipe = *w;
      }
    }
    if (const Val* x = f.find("gain")) set(out.difference_gain, read_positive(*x));
    if (out.compare_against < 0 && !out.head_angle_deg) {
      report(against, "\"head\" compares with this step's head not moved: the view needs \"head_angle_deg\"");
    }
  }

  void answer(const Val& v, LessonStep& s, std::size_t step) {
    if (!expect_object(v)) return;
    const Fields f = fields(v, kAnswerKeys);
    require(v, f, {"caption"});
    if (const Val* x = f.find("caption")) set(s.answer, read_string(*x));
    if (const Val* x = f.find("show")) view(*x, s.prepared_scene, s.answer_view, false, step);
  }

  void check_compare_targets(const Lesson& lesson) {
    for (const auto& [at, n] : compare_refs_) {
      if (static_cast<std::size_t>(n) > lesson.steps.size()) {
        report(at, "there is no step " + std::to_string(n) + " (the lesson has " + std::to_string(lesson.steps.size()) + ")");
      }
    }
  }

  std::string base_dir_;
  std::string scene_arg_;  // the scene of the step being read (a step without "scene" keeps it)
  std::map<std::string, std::optional<Scene>> scenes_;
  std::vector<std::pair<Val, int>> compare_refs_;  // "against": N, checked once every step is known
};

// A problem inside a step says which step, as the previewer and the handouts number them (from 1):
// `steps[2].show.probe[0]: (step 3) must be ...`; the JSON path keeps the file's own index.
void number_steps(std::vector<Diagnostic>& errors) {
  for (Diagnostic& d : errors) {
    constexpr std::string_view kSteps = "steps[";
    if (d.path.compare(0, kSteps.size(), kSteps) != 0) continue;
    std::size_t i = kSteps.size(), index = 0;
    while (i < d.path.size() && d.path[i] >= '0' && d.path[i] <= '9' && index < 1000000) index = index * 10 + static_cast<std::size_t>(d.path[i++] - '0');
    if (i == kSteps.size() || i >= d.path.size() || d.path[i] != ']') continue;
    d.message = "(step " + std::to_string(index + 1) + ") " + d.message;
  }
}

LessonLoad load_text_checked(const std::string& text, const std::string& file_name, const std::string& base_dir) {
  Issues issues;
  LessonLoad r;
  ParsedText parsed;
  std::optional<Lesson> lesson;
  if (parse_text(text, "a lesson file", issues, parsed)) {
    LessonReader reader(text, *parsed.index, parsed.root, parsed.overflows, issues, base_dir);
    lesson = reader.run();
  }
  const bool truncated = issues.full();
  r.errors = to_diagnostics(text, std::move(issues.list()), truncated, file_name);
  number_steps(r.errors);
  if (r.errors.empty() && lesson) {
    lesson->name = std::filesystem::path(file_name).stem().string();
    r.lesson = std::move(lesson);
  }
  return r;
}

LessonLoad lesson_failure(const std::string& file, std::string message) {
  LessonLoad r;
  r.errors.push_back(line_diagnostic(file, 0, std::move(message)));
  return r;
}

}  // namespace

LessonLoad load_lesson_text(const std::string& text, const std::string& file_name, const std::string& base_dir) {
  try {
    return load_text_checked(text, file_name, base_dir);
  } catch (const std::bad_alloc&) {
    return lesson_failure(file_name, "out of memory while loading the lesson");
  } catch (const std::exception& e) {
    return lesson_failure(file_name, std::string("internal error while loading the lesson: ") + e.what());
  }
}

LessonLoad load_lesson_arg(const std::string& lesson_arg) {
  if (const EmbeddedLesson* l = find_embedded_lesson(lesson_arg)) {
    LessonLoad r = load_lesson_text(std::string(l->json), std::string(l->name), ".");
    return r;
  }
  std::string error;
  const std::optional<std::string> text = read_text_file(lesson_arg, kMaxFileBytes, error);
  if (!text) {
    std::string message = error;
    if (lesson_arg.find_first_of("/.") == std::string::npos) {
      std::vector<std::string_view> names;
      for (const EmbeddedLesson& e : embedded_lessons()) names.push_back(e.name);
      message += "; not an embedded lesson either" + suggestion(lesson_arg, names, "embedded lessons");
    }
    return lesson_failure(lesson_arg, message);
  }
  const std::string dir = std::filesystem::path(lesson_arg).parent_path().string();
  return load_lesson_text(*text, lesson_arg, dir.empty() ? "." : dir);
}

namespace {

// Looks for the key "steps" in the top-level object without building the document: a SAX pass
// that keeps nothing but its depth and stops at the answer, so a scene file of any size is told
// from a lesson in constant memory (the scene loader's memory budget then sees the file alone).
struct LessonKeyScan final : nlohmann::json_sax<nlohmann::json> {
  int depth = 0;
  bool object_at_top = false;
  bool found = false;
  bool null() override { return true; }
  bool boolean(bool) override { return true; }
  bool number_integer(number_integer_t) override { return true; }
  bool number_unsigned(number_unsigned_t) override { return true; }
  bool number_float(number_float_t, const string_t&) override { return true; }
  bool string(string_t&) override { return true; }
  bool binary(binary_t&) override { return true; }
  bool start_object(std::size_t) override {
    if (depth == 0) object_at_top = true;
    ++depth;
    return true;
  }
  bool end_object() override { return --depth > 0; }
  bool start_array(std::size_t) override { return ++depth > 1; }  // a top-level array is no lesson
  bool end_array() override { --depth; return true; }
  bool key(string_t& k) override {
    if (depth == 1 && k == "steps") {
      found = true;
      return false;  // the answer: stop reading
    }
    return true;
  }
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override { return false; }
};

}  // namespace

bool looks_like_lesson(const std::string& text) {
  LessonKeyScan scan;
  nlohmann::json::sax_parse(text, &scan, nlohmann::json::input_format_t::json, false);
  return scan.object_at_top && scan.found;
}

bool is_lesson_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  LessonKeyScan scan;
  nlohmann::json::sax_parse(in, &scan, nlohmann::json::input_format_t::json, false);
  return scan.object_at_top && scan.found;
}

}  // namespace phonglab
