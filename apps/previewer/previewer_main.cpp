// phonglab [SCENE]: the interactive previewer (README).
#include <cstdlib>
#include <iostream>
#include <string>
#include <string_view>

#include "apps/previewer/viewer_app.h"

namespace {

constexpr std::string_view kUsage =
    "usage: phonglab [SCENE] [--lesson LESSON]\n"
    "\n"
    "Interactive previewer of the lecture's Phong illumination and Whitted recursion.\n"
    "SCENE is a scene file (JSON) or the name of an embedded scene (default:\n"
    "lecture; `phonglab-cli scenes` lists them).\n"
    "\n"
    "  left-drag orbit, right-drag or wheel dolly, middle- or shift+left-drag pan,\n"
    "  click an object to select it and its material, drag the selected object to\n"
    "  slide it over the floor (V held: up and down; X, Y or Z held: along that\n"
    "  axis), drag a light's marker to move it,\n"
    "  drop a .json on the window to open it or an .obj to add it as a mesh,\n"
    "  F frames the scene, R resets the camera, H hides the panels; 1 .. 6 show the\n"
    "  image or one term, M all five, I what the ambient term stands in for,\n"
    "  Shift+1 .. 9 solo a light; Ctrl+O opens, Ctrl+S saves, Ctrl+Shift+S saves\n"
    "  as, Ctrl+Z undoes; F1 lists the keys.\n"
    "\n"
    "options:\n"
    "  --lesson LESSON  present a lesson (an embedded lesson's name, e.g. shading,\n"
    "                   or a lesson file): arrows, Page Up/Down and space step\n"
    "                   through it, F11 is presenter mode (full screen, caption\n"
    "                   large)\n"
    "  --help           this text\n"
    "  --version        the version\n";

// Parses "1280x720".
bool parse_size(const std::string& text, int& width, int& height) {
  const std::size_t x = text.find('x');
  if (x == std::string::npos) return false;
  char* end = nullptr;
  const long w = std::strtol(text.c_str(), &end, 10);
  if (end != text.c_str() + x) return false;
  const long h = std::strtol(text.c_str() + x + 1, &end, 10);
  if (*end != '\0' || w < 1 || h < 1 || w > 16384 || h > 16384) return false;
  width = static_cast<int>(w);
  height = static_cast<int>(h);
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  phonglab::ViewerOptions options;
  bool have_scene = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    // Test hooks (not in --help): a command script, a timing log, the window size.
    const bool takes_value = arg == "--script" || arg == "--stats-log" || arg == "--size" || arg == "--lesson";
    if (takes_value && i + 1 >= argc) {
      std::cerr << "phonglab: " << arg << " needs a value\n" << kUsage;
      return 2;
    }
    if (arg == "--help" || arg == "-h") {
      std::cout << kUsage;
      return 0;
    } else if (arg == "--version") {
      std::cout << "phonglab " << PHONGLAB_VERSION << "\n";
      return 0;
    } else if (arg == "--script") {
      options.script_path = argv[++i];
    } else if (arg == "--lesson") {
      options.lesson_arg = argv[++i];
    } else if (arg == "--stats-log") {
      options.stats_log_path = argv[++i];
    } else if (arg == "--size") {
      if (!parse_size(argv[++i], options.width, options.height)) {
        std::cerr << "phonglab: --size wants WIDTHxHEIGHT, e.g. 1280x720\n";
        return 2;
      }
    } else if (!arg.empty() && arg[0] == '-') {
      std::cerr << "phonglab: unknown option " << arg << "\n" << kUsage;
      return 2;
    } else if (have_scene) {
      std::cerr << "phonglab: only one SCENE may be given\n" << kUsage;
      return 2;
    } else {
      options.scene_arg = arg;
      options.scene_given = have_scene = true;
    }
  }
  return phonglab::run_viewer(options);
}
