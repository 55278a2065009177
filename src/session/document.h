// The scene being edited and the file behind it: open, save, save-as, reload, noticing
// changes on disk. A failed load keeps the current scene and reports the file's diagnostics.
// No GL, no ImGui.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "core/scene/scene.h"

namespace phonglab {

// What the unsaved state compares: the scene as its file's text, the camera aside (navigation
// is not an edit, though Save writes it).
std::string scene_content(const Scene& scene);

class SceneDocument {
 public:
  // Opens SCENE: an embedded scene's name or a file path. On failure the current scene stays
  // and error_text() holds the diagnostics.
  bool open(const std::string& scene_arg);
  // Makes `scene` the document, with no file behind it (a lesson's step: Save asks where, so
  // the lesson file never changes unless saved explicitly); `source` names it.
  void adopt(const Scene& scene, const std::string& source);
  // Reads the file again. With `keep_view`, the current camera stays if the file's camera is
  // the one last loaded (someone edited materials in a text editor, not the view).
  bool reload(bool keep_view);
  // What save() did.
  enum class SaveResult : std::uint8_t { kSaved, kFailed, kChangedOnDisk };
  // Writes the scene (with the current camera) to file_path(), atomically. When the file changed
  // on disk since it was read or written here, nothing is written (kChangedOnDisk) unless
  // `overwrite_outside_change`: another program's change is never overwritten silently.
  SaveResult save(bool overwrite_outside_change = false);
  // Writes to `path`, which then becomes the document's file.
  bool save_as(const std::string& path);
  // True when the document is an OBJ opened on its own (Save must not write JSON over it).
  bool opened_mesh() const;
  // True when the file's modification time differs from the one last loaded or saved, or the
  // scene is edits restored over the file as it was before another program changed it.
  bool changed_on_disk() const;
  // The file's identity (ui::file_identity) when last read or written here: what the edits are
  // made over. Empty with no file behind the document.
  const std::string& base_identity() const { return base_; }
  // The scene now holds edits that were made over the file as it was at `base` (a recovery's):
  // when the file holds something else now, or `base` is unknown (empty), it counts as changed
  // on disk until it is read again or saved over with consent, so Save asks before it
  // overwrites. Returns whether it counts as changed.
  bool edits_made_over(const std::string& base);

  // The scene; only the session writes it (its edits, undo and redo: Session).
  const Scene& scene() const { return scene_; }
  // Counts the changes the scene may have had (an edit, undo, redo, open, reload, a lesson's
  // step adopted, a recovery restored): what the renderer's schedule compares with the snapshot
  // it sent (RenderSchedule::send_scene), so no caller has to report an edit.
  std::uint64_t version() const { return version_; }
  // The scene becomes `scene`, edits made over the document's file (a recovery's restore):
  // unsaved as far as it differs from what the file held.
  void restore_edits(Scene scene);
  // Camera as loaded from the file (for Reset).
  const Camera& loaded_camera() const { return loaded_camera_; }
  // The embedded scene the document was opened from; empty for a file or a lesson's step.
  const std::string& embedded_name() const { return embedded_name_; }
  // File the scene came from and saves to; empty for an embedded scene.
  const std::string& file_path() const { return file_path_; }
  // "embedded scene 'lecture'" or the path.
  const std::string& source() const { return source_; }
  // Unsaved edits: the scene differs from what was last loaded or saved (camera moves do not
  // count: they are navigation, though Save writes them). Undoing every edit makes it clean.
  bool dirty() const { return dirty_; }
  // Compares the scene with the saved state again; call after edits.
  void update_dirty();
  // The same, given scene_content(scene()) already taken.
  void update_dirty(const std::string& content) { dirty_ = content != saved_content_; }
  // Diagnostics of the last failed operation; empty after a success.
  const std::string& error_text() const { return error_text_; }
  // What the last successful operation did.
  const std::string& status() const { return status_; }
  // Whether any scene was loaded successfully yet.
  bool loaded() const { return loaded_; }

 private:
  friend class Session;  // the one writer of the scene
  Scene& edited_scene() {
    ++version_;
    return scene_;
  }
  bool write(const std::string& path);
  void mark_saved();                              // the scene as it is now is what the file holds
  std::optional<std::filesystem::file_time_type> current_mtime() const;

  Scene scene_;
  std::uint64_t version_ = 0;
  Camera loaded_camera_;
  std::string file_path_;
  std::string embedded_name_;
  std::string source_;
  bool dirty_ = false;
  bool loaded_ = false;
  std::string error_text_;
  std::string status_;
  std::string saved_content_;  // content() of the scene when last loaded or saved
  std::optional<std::filesystem::file_time_type> mtime_;  // of file_path_ when last read or written
  std::string base_;             // file_identity(file_path_) when last read or written
  bool outside_change_ = false;  // edits_made_over found the file changed since the edits' base
};

}  // namespace phonglab
