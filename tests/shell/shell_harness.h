// The previewer's shell run headless in a test: no window and no GL (Platform::create_headless),
// the same components, panels and script commands as under a window, ImGui's frames at the size
// given; what a script's dump_state writes read back as key=value pairs.
#pragma once

#include <array>
#include <map>
#include <string>

#include "tests/support/test_folder.h"

namespace phonglab::test {

struct ShellRun {
  int exit_status = -1;  // the previewer's: 0, or 3 when a script command failed
};

// Runs `script` (the previewer's script commands, docs/previewer.md) on `scene` in a window of
// `width` x `height`, with the state folder (recovery, recent files) inside `folder`.
ShellRun run_shell(const TestFolder& folder, const std::string& scene, const std::string& script, int width = 1280,
                   int height = 720);

// A dump_state file's values by key.
std::map<std::string, std::string> read_state(const std::string& path);

// A dump_state vector ("x y z") as three numbers.
std::array<double, 3> vec3_of(const std::string& text);
// Whether two dump_state rectangles ("x y w h") do not overlap.
bool rects_apart(const std::string& a, const std::string& b);
// A file's bytes (empty when it cannot be read).
std::string file_bytes(const std::string& path);

}  // namespace phonglab::test
