// Recovery files' names and their .source text (the previewer writes them; GUI session 10
// kills it and restores them).
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "interaction/recovery.h"

namespace phonglab::ui {
namespace {

TEST(Recovery, KeysNameTheSourceStably) {
  EXPECT_EQ(recovery_key("lecture", true), "embedded-lecture");
  const std::string a = recovery_key("/home/a/scene.json", false);
  EXPECT_EQ(a.rfind("file-", 0), 0U);
  EXPECT_EQ(a.size(), 5U + 16U);
  EXPECT_EQ(a, recovery_key("/home/a/scene.json", false)) << "the same path, the same file";
  EXPECT_NE(a, recovery_key("/home/b/scene.json", false)) << "two files of one name, two recovery files";
  EXPECT_EQ(recovery_key("", false), "file-cbf29ce484222325") << "FNV-1a's offset basis: the hash is the published one";
}

TEST(Recovery, SourceTextRoundTripsAndRefusesOtherText) {
  RecoveryEntry e;
  e.source = "/tmp/my scene.json";
  e.saved = 1796193569;
  e.base = "1234:00ff00ff00ff00ff";
  const auto back = parse_recovery_source(recovery_source_text(e), "/x/file-1.json");
  ASSERT_TRUE(back);
  EXPECT_EQ(back->base, e.base);
  EXPECT_TRUE(parse_recovery_source("phonglab recovery 1\nfile /a\nsaved 1\n", "j")->base.empty())
      << "an older file, with no identity";
  EXPECT_FALSE(parse_recovery_source("phonglab recovery 1\nfile /a\nsaved 1\nbose 2:ab\n", "j"));
  EXPECT_EQ(back->source, e.source);
  EXPECT_FALSE(back->embedded);
  EXPECT_EQ(back->saved, e.saved);
  EXPECT_EQ(back->scene_path, "/x/file-1.json");
  e.embedded = true;
  e.source = "lecture";
  EXPECT_TRUE(parse_recovery_source(recovery_source_text(e), "j")->embedded);
  EXPECT_FALSE(parse_recovery_source("", "j"));
  EXPECT_FALSE(parse_recovery_source("phonglab recovery 2\nfile /a\nsaved 1\n", "j")) << "another version";
  EXPECT_FALSE(parse_recovery_source("phonglab recovery 1\nfile /a\nsaved x\n", "j"));
  EXPECT_FALSE(parse_recovery_source("phonglab recovery 1\nsomething /a\nsaved 1\n", "j"));
}

TEST(Recovery, ListsPairsNewestFirst) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("phonglab_recovery_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const auto put = [&](const std::string& key, const std::string& source, std::int64_t saved, bool with_json) {
    RecoveryEntry e;
    e.source = source;
    e.saved = saved;
    std::ofstream(dir / (key + ".source")) << recovery_source_text(e);
    if (with_json) std::ofstream(dir / (key + ".json")) << "{}";
  };
  put("file-a", "/a.json", 100, true);
  put("file-b", "/b.json", 300, true);
  put("file-c", "/c.json", 200, false);  // its scene is missing: not offered
  std::ofstream(dir / "stray.source") << "not a recovery";
  const auto all = list_recoveries(dir.string());
  ASSERT_EQ(all.size(), 2U);
  EXPECT_EQ(all[0].source, "/b.json");
  EXPECT_EQ(all[1].source, "/a.json");
  EXPECT_TRUE(list_recoveries((dir / "none").string()).empty());
  fs::remove_all(dir);
}

TEST(Recovery, StateFolderFollowsXdg) {
  const char* old = std::getenv("XDG_STATE_HOME");
  const std::string saved = old != nullptr ? old : "";
  setenv("XDG_STATE_HOME", "/tmp/xdg", 1);
  EXPECT_EQ(state_dir(), "/tmp/xdg/phonglab");
  unsetenv("XDG_STATE_HOME");
  if (std::getenv("HOME") != nullptr) {
    EXPECT_EQ(state_dir(), std::string(std::getenv("HOME")) + "/.local/state/phonglab");
  }
  if (old != nullptr) setenv("XDG_STATE_HOME", saved.c_str(), 1);
}

}  // namespace
}  // namespace phonglab::ui
