// The file browser's listing and recent files (src/interaction/file_browser.h), on a folder
// made for the test.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "interaction/file_browser.h"

using namespace phonglab::ui;
namespace fs = std::filesystem;

TEST(FileBrowser, ListsFoldersThenTheFilteredFilesSortedWithoutHiddenOnes) {
  const fs::path dir = fs::temp_directory_path() / "phonglab_browser_test";
  fs::remove_all(dir);
  fs::create_directories(dir / "b_folder");
  fs::create_directories(dir / "a_folder");
  fs::create_directories(dir / ".hidden_folder");
  for (const char* name : {"z.json", "m.OBJ", "notes.txt", ".hidden.json", "a.json"}) std::ofstream(dir / name) << "x";
  const FolderListing listing = list_folder(dir.string(), {".json", ".obj"});
  EXPECT_EQ(listing.folder, dir.string());
  EXPECT_TRUE(listing.error.empty());
  std::vector<std::string> names;
  for (const FileEntry& e : listing.entries) names.push_back(e.name + (e.folder ? "/" : ""));
  EXPECT_EQ(names, (std::vector<std::string>{"../", "a_folder/", "b_folder/", "a.json", "m.OBJ", "z.json"}));
  EXPECT_EQ(entry_path(listing, listing.entries[0]), dir.parent_path().string());
  EXPECT_EQ(entry_path(listing, listing.entries[3]), (dir / "a.json").string());
  const FolderListing json_only = list_folder((dir / "").string(), {".json"});  // a trailing slash
  EXPECT_EQ(json_only.folder, dir.string());
  EXPECT_EQ(json_only.entries.size(), 5u);
  const FolderListing missing = list_folder((dir / "nope").string(), {".json"});
  EXPECT_FALSE(missing.error.empty());
  ASSERT_EQ(missing.entries.size(), 1u);  // the way up
  fs::remove_all(dir);
}

TEST(FileBrowser, RecentFilesNewestFirstWithoutDuplicatesAndBounded) {
  std::vector<std::string> recent;
  for (int i = 0; i < 15; ++i) remember_recent(recent, "/f" + std::to_string(i));
  remember_recent(recent, "/f10");
  ASSERT_EQ(recent.size(), kMaxRecent);
  EXPECT_EQ(recent[0], "/f10");
  EXPECT_EQ(recent[1], "/f14");
  EXPECT_EQ(parse_recent(recent_text(recent)), recent);
  EXPECT_EQ(parse_recent("/a\n\n/b\n/a\n"), (std::vector<std::string>{"/a", "/b"}));
  EXPECT_EQ(start_folder("/x/y/scene.json"), "/x/y");
}
