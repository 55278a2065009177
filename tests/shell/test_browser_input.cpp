// The file browser driven through the shell's keys and its named widgets, headless: Ctrl+O opens
// it, a folder typed into its field is listed, a click on a file and Open open it, Ctrl+Shift+S
// with a typed name saves there, the recent files list both newest first and are kept in the
// state folder for the next session, Esc closes it.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "tests/shell/shell_harness.h"

namespace phonglab {
namespace {

TEST(BrowserInput, OpenAndSaveAsThroughTheBrowserAndTheRecentFiles) {
  test::TestFolder folder("phonglab-shell-browser");
  const std::string d = folder.path().string() + "/";
  const std::string sub = d + "scenes/sub";
  std::filesystem::create_directories(sub);
  std::filesystem::copy_file(PHONGLAB_SOURCE_DIR "/assets/scenes/glass.json", sub + "/glass.json");
  const test::ShellRun run = test::run_shell(folder, "lecture", R"(set render target_spp 1
set render resolution_scale 0.25
wait_idle 120
key O ctrl
wait_frames 5
dump_state )" + d + R"(f1.txt
type_item browser.name )" + sub + R"(
wait_frames 3
dump_state )" + d + R"(f2.txt
click_item browser.entry.glass.json
wait_frames 2
click_item browser.accept
wait_idle 120
dump_state )" + d + R"(f3.txt
key S ctrl shift
wait_frames 5
type_item browser.name copy.json
wait_idle 120
dump_state )" + d + R"(f4.txt
key O ctrl
wait_frames 5
key ESCAPE
wait_frames 3
dump_state )" + d + R"(f5.txt
quit
)");
  ASSERT_EQ(run.exit_status, 0);
  EXPECT_EQ(test::read_state(d + "f1.txt")["file_browser"], "open") << "Ctrl+O opens the browser";
  auto f2 = test::read_state(d + "f2.txt");
  EXPECT_EQ(f2["file_browser_folder"], sub) << "a folder typed into its field is listed";
  EXPECT_EQ(f2["file_browser"], "open");
  auto f3 = test::read_state(d + "f3.txt");
  EXPECT_EQ(f3["source"], sub + "/glass.json") << "a click on a file and Open open it";
  EXPECT_EQ(f3["file_browser"], "");
  auto f4 = test::read_state(d + "f4.txt");
  EXPECT_EQ(f4["source"], sub + "/copy.json") << "Ctrl+Shift+S with a typed name saves there";
  EXPECT_TRUE(std::filesystem::is_regular_file(sub + "/copy.json"));
  EXPECT_EQ(f4["recent0"], sub + "/copy.json") << "the recent files list both, newest first";
  EXPECT_EQ(f4["recent1"], sub + "/glass.json");
  std::ifstream recent(d + "state/phonglab/recent");
  std::string first;
  std::getline(recent, first);
  EXPECT_EQ(first, sub + "/copy.json") << "and are kept for the next session";
  EXPECT_EQ(test::read_state(d + "f5.txt")["file_browser"], "") << "Esc closes the browser";
}

}  // namespace
}  // namespace phonglab
