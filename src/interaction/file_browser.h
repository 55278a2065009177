// What the previewer's file browser shows: a folder's subfolders and the files it can open or
// save, and the recent files. Plain data over std::filesystem; no ImGui (the dialog is
// ui::file_browser_dialog), unit-tested.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace phonglab::ui {

struct FileEntry {
  std::string name;        // file or folder name within the folder
  bool folder = false;
};

struct FolderListing {
  std::string folder;               // absolute, normalised
  std::vector<FileEntry> entries;   // "..", then folders, then files, each sorted by name
  std::string error;                // why it could not be read (entries then hold ".." only)
};

// The folder's subfolders and the files whose extension (any case) is one of `extensions`
// (".json", ".obj"); names starting with a dot are left out. A folder that cannot be read gives
// its error and a way up.
FolderListing list_folder(const std::string& folder, const std::vector<std::string>& extensions);

// The folder a browser starts in for a document's file: its folder, or the working folder.
std::string start_folder(const std::string& file_path);

// Where an entry leads: the folder for a folder (".." goes up), the file's path otherwise.
std::string entry_path(const FolderListing& listing, const FileEntry& entry);

// The recent-files list: `path` first, no duplicates, at most kMaxRecent.
inline constexpr std::size_t kMaxRecent = 10;
void remember_recent(std::vector<std::string>& recent, const std::string& path);
// The list from its file's text (one path per line) and back.
std::vector<std::string> parse_recent(const std::string& text);
std::string recent_text(const std::vector<std::string>& recent);

}  // namespace phonglab::ui
