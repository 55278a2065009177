// Recovery files: where the previewer keeps unsaved edits until they are saved or discarded
// (docs/previewer.md#recovery). One pair per scene in the state folder's recovery/: KEY.json,
// the edited scene as a scene file, and KEY.source, what it recovers. The names and the
// .source text are here; writing them is the previewer's. No ImGui, no files read or written
// but by list_recoveries.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace phonglab::ui {

// $XDG_STATE_HOME/phonglab, else ~/.local/state/phonglab; empty when neither can be known.
std::string state_dir();

// What a recovery file recovers.
struct RecoveryEntry {
  std::string scene_path;    // KEY.json: the edited scene
  std::string source;        // the scene it was edited from: an embedded scene's name or an absolute path
  bool embedded = false;     // `source` names an embedded scene
  std::int64_t saved = 0;    // when it was written, seconds since 1970
  // The file's identity (file_identity) when the edits began: what it was read or last saved
  // as. Empty for an embedded scene, or when it was not known (a file of an older version).
  std::string base;
};

// What a file holds, in a few characters: "SIZE:HASH" (its byte count and a 64-bit FNV-1a of its
// bytes); empty when it cannot be read. Two identities differ when another program changed the
// file (a touch that changes no byte is no change).
std::string file_identity(const std::string& path);

// The file name stem for a source: "embedded-NAME", or "file-" and 16 hex digits of a hash
// of the absolute path (so two files of one name do not share a recovery file).
std::string recovery_key(const std::string& source, bool embedded);

// The .source text: "phonglab recovery 1", then "embedded NAME" or "file PATH", then "saved T",
// then for a file "base IDENTITY" (a .source without that line parses with an empty base).
std::string recovery_source_text(const RecoveryEntry& entry);
// Reads it back (nullopt when it is not one); `scene_path` is set to `json_path`.
std::optional<RecoveryEntry> parse_recovery_source(const std::string& text, const std::string& json_path);

// Every recovery in `dir` (the recovery folder) whose .json and .source both exist, newest first.
std::vector<RecoveryEntry> list_recoveries(const std::string& dir);

}  // namespace phonglab::ui
