#include "tests/shell/shell_harness.h"

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <sstream>

#include "apps/previewer/viewer_app.h"

namespace phonglab::test {

ShellRun run_shell(const TestFolder& folder, const std::string& scene, const std::string& script, int width, int height) {
  const std::string script_path = (folder.path() / "script.txt").string();
  std::ofstream(script_path) << script;
  setenv("XDG_STATE_HOME", (folder.path() / "state").c_str(), 1);  // nothing of the user's read or written
  ViewerOptions options;
  options.scene_arg = scene;
  options.scene_given = true;
  options.width = width;
  options.height = height;
  options.script_path = script_path;
  PlatformOptions platform_options;
  platform_options.width = width;
  platform_options.height = height;
  const std::unique_ptr<Platform> platform = Platform::create_headless(platform_options);
  ShellRun run;
  {
    Viewer viewer(*platform, options);
    if (!viewer.init().empty()) return run;
    run.exit_status = viewer.run();
  }
  return run;
}

std::map<std::string, std::string> read_state(const std::string& path) {
  std::map<std::string, std::string> values;
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);) {
    const std::size_t eq = line.find('=');
    if (eq != std::string::npos) values.emplace(line.substr(0, eq), line.substr(eq + 1));
  }
  return values;
}

std::array<double, 3> vec3_of(const std::string& text) {
  std::array<double, 3> v{};
  std::istringstream in(text);
  in >> v[0] >> v[1] >> v[2];
  return v;
}

bool rects_apart(const std::string& a, const std::string& b) {
  double ax = 0, ay = 0, aw = 0, ah = 0, bx = 0, by = 0, bw = 0, bh = 0;
  std::istringstream(a) >> ax >> ay >> aw >> ah;
  std::istringstream(b) >> bx >> by >> bw >> bh;
  return ax + aw <= bx || bx + bw <= ax || ay + ah <= by || by + bh <= ay;
}

std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace phonglab::test
