#include "interaction/file_browser.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <sstream>
#include <system_error>

namespace phonglab::ui {

namespace fs = std::filesystem;

namespace {

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

}  // namespace

FolderListing list_folder(const std::string& folder, const std::vector<std::string>& extensions) {
  FolderListing listing;
  std::error_code ec;
  fs::path dir = fs::absolute(folder.empty() ? "." : folder, ec).lexically_normal();
  if (!dir.has_filename() && dir != dir.root_path()) dir = dir.parent_path();  // "a/b/" to "a/b"
  listing.folder = dir.string();
  if (dir != dir.root_path()) listing.entries.push_back(FileEntry{"..", true});
  std::vector<FileEntry> folders, files;
  fs::directory_iterator it(dir, fs::directory_options::skip_permission_denied, ec);
  if (ec) {
    listing.error = "cannot read " + listing.folder + ": " + ec.message();
    return listing;
  }
  for (const fs::directory_entry& e : it) {
    const std::string name = e.path().filename().string();
    if (name.empty() || name[0] == '.') continue;
    std::error_code type_ec;
    if (e.is_directory(type_ec)) {
      folders.push_back(FileEntry{name, true});
    } else if (std::find(extensions.begin(), extensions.end(), lower(e.path().extension().string())) != extensions.end()) {
      files.push_back(FileEntry{name, false});
    }
  }
  const auto by_name = [](const FileEntry& a, const FileEntry& b) { return a.name < b.name; };
  std::sort(folders.begin(), folders.end(), by_name);
  std::sort(files.begin(), files.end(), by_name);
  listing.entries.insert(listing.entries.end(), folders.begin(), folders.end());
  listing.entries.insert(listing.entries.end(), files.begin(), files.end());
  return listing;
}

std::string start_folder(const std::string& file_path) {
  std::error_code ec;
  if (!file_path.empty()) return fs::absolute(file_path, ec).parent_path().lexically_normal().string();
  return fs::current_path(ec).string();
}

std::string entry_path(const FolderListing& listing, const FileEntry& entry) {
  const fs::path dir(listing.folder);
  if (entry.name == "..") return dir.parent_path().string();
  return (dir / entry.name).lexically_normal().string();
}

void remember_recent(std::vector<std::string>& recent, const std::string& path) {
  recent.erase(std::remove(recent.begin(), recent.end(), path), recent.end());
  recent.insert(recent.begin(), path);
  if (recent.size() > kMaxRecent) recent.resize(kMaxRecent);
}

std::vector<std::string> parse_recent(const std::string& text) {
  std::vector<std::string> recent;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    if (!line.empty() && std::find(recent.begin(), recent.end(), line) == recent.end() && recent.size() < kMaxRecent) {
      recent.push_back(line);
    }
  }
  return recent;
}

std::string recent_text(const std::vector<std::string>& recent) {
  std::string text;
  for (const std::string& path : recent) text += path + "\n";
  return text;
}

}  // namespace phonglab::ui
