// The second rehearsal's finds in the panels, the shell driven headless: ticking "cut recursion at
// depth" with a deep probe leaves the checkbox where it was, the probe names its pixel for
// phonglab-cli (whose total there is the previewer's), the specular factor's value stands apart
// from its label; a dropped file that is not taken is said in the error line, L hides the
// lights' markers, and Ctrl+Q with unsaved edits asks first and Discard quits.
#include <gtest/gtest.h>

#include <cstdio>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "tests/shell/shell_harness.h"
#include "tests/support/run_cli.h"

namespace phonglab {
namespace {

// The second word of a rectangle's text: its top.
std::string top_of(const std::string& rect) {
  std::istringstream in(rect);
  std::string x, y;
  in >> x >> y;
  return y;
}

TEST(PanelInput, TheProbesRowsAndTheDepthCutStayPutAndTheCliAgrees) {
  test::TestFolder folder("phonglab-shell-probe-text");
  const std::string d = folder.path().string() + "/";
  const test::ShellRun run = test::run_shell(folder, "lecture", R"(set render target_spp 1
wait_idle 120
probe 520 440
wait_frames 3
wait_idle 120
click_item panel.Rays
wait_frames 3
show_item rays.depth_cut
wait_frames 3
dump_state )" + d + R"(p1.txt
click_item rays.depth_cut
wait_frames 3
wait_idle 120
wait_frames 3
dump_state )" + d + R"(p2.txt
show_item probe.spec_factor
wait_frames 3
dump_state )" + d + R"(p3.txt
quit
)");
  ASSERT_EQ(run.exit_status, 0);
  auto p1 = test::read_state(d + "p1.txt");
  auto p2 = test::read_state(d + "p2.txt");
  auto p3 = test::read_state(d + "p3.txt");
  const std::string y1 = top_of(p1["item_rays.depth_cut"]);
  EXPECT_FALSE(y1.empty());
  EXPECT_EQ(top_of(p2["item_rays.depth_cut"]), y1) << "ticking the depth cut with a deep probe leaves the checkbox where it was";
  EXPECT_NE(p2["depth_cut"], "-1");
  const std::string command = p1["probe_cli"];
  ASSERT_EQ(command.rfind("phonglab-cli probe lecture --pixel 520,440 ", 0), 0U) << command;
  const test::RunResult cli = test::run_cli_stdout(command.substr(command.find(' ') + 1) + " --json");
  ASSERT_EQ(cli.exit_code, 0) << cli.out;
  const nlohmann::json report = nlohmann::json::parse(cli.out, nullptr, false);
  ASSERT_TRUE(report.is_object()) << cli.out;
  std::string total;
  for (const auto& v : report.at("total")) {
    char text[64];
    std::snprintf(text, sizeof text, "%g", v.get<double>());
    if (!total.empty()) total += ' ';
    total += text;
  }
  EXPECT_EQ(total, p1["probe_total"]) << "the CLI's total at the probe's pixel is the previewer's (" << command << ")";
  EXPECT_TRUE(test::rects_apart(p3["item_probe.spec_factor_label"], p3["item_probe.spec_factor"]))
      << "the specular factor's value stands apart from its label: " << p3["item_probe.spec_factor_label"] << " | "
      << p3["item_probe.spec_factor"];
}

TEST(PanelInput, ADropRefusedIsSaidWhereOneLooksAndCtrlQAsksFirst) {
  test::TestFolder folder("phonglab-shell-drops");
  const std::string d = folder.path().string() + "/";
  std::FILE* notes = std::fopen((d + "notes.txt").c_str(), "w");
  ASSERT_NE(notes, nullptr);
  std::fputs("notes, not a scene\n", notes);
  std::fclose(notes);
  const test::ShellRun run = test::run_shell(folder, "lecture", R"(set render target_spp 1
wait_idle 120
drop )" + d + R"(notes.txt
wait_frames 3
dump_state )" + d + R"(d1.txt
key L
wait_frames 3
dump_state )" + d + R"(d3.txt
set material matte kd 0.5 0.5 0.5
wait_frames 3
key Q ctrl
wait_frames 3
dump_state )" + d + R"(d4.txt
modal discard
wait_frames 300
fail Ctrl+Q and Discard did not quit
)");
  EXPECT_EQ(run.exit_status, 0) << "Discard quits";
  EXPECT_NE(test::read_state(d + "d1.txt")["error"].find("notes.txt"), std::string::npos)
      << "a .txt dropped is refused in the overlay's error line too";
  EXPECT_EQ(test::read_state(d + "d3.txt")["light_markers"], "0") << "L hides the lights' markers";
  EXPECT_EQ(test::read_state(d + "d4.txt")["modal"], "1") << "Ctrl+Q with unsaved edits asks first";
}

}  // namespace
}  // namespace phonglab
