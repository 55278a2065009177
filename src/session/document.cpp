#include "session/document.h"

#include <filesystem>
#include <system_error>

#include "interaction/recovery.h"
#include "io/embedded_scenes.h"
#include "io/scene/scene_io.h"

namespace phonglab {

namespace {

bool same_camera(const Camera& a, const Camera& b) {
  return a.position == b.position && a.look_at == b.look_at && a.up == b.up && a.fov_y_deg == b.fov_y_deg;
}

}  // namespace

std::optional<std::filesystem::file_time_type> SceneDocument::current_mtime() const {
  if (file_path_.empty()) return std::nullopt;
  std::error_code ec;
  const auto t = std::filesystem::last_write_time(file_path_, ec);
  if (ec) return std::nullopt;
  return t;
}

std::string scene_content(const Scene& scene) {
  Scene copy = scene;
  copy.camera = Camera{};  // navigation is not an edit
  return scene_to_json(copy, ".");
}

void SceneDocument::mark_saved() {
  saved_content_ = scene_content(scene_);
  dirty_ = false;
}

void SceneDocument::update_dirty() { update_dirty(scene_content(scene_)); }

void SceneDocument::restore_edits(Scene scene) {
  scene_ = std::move(scene);
  ++version_;
  update_dirty();
}

void SceneDocument::adopt(const Scene& scene, const std::string& source) {
  scene_ = scene;
  ++version_;
  loaded_camera_ = scene_.camera;
  file_path_.clear();
  embedded_name_.clear();
  source_ = source;
  mtime_.reset();
  base_.clear();
  outside_change_ = false;
  mark_saved();
  loaded_ = true;
  error_text_.clear();
  status_ = "showing " + source_;
}

bool SceneDocument::open(const std::string& scene_arg) {
  LoadResult result = load_scene_arg(scene_arg);
  if (!result.ok()) {
    error_text_ = result.error_text();
    return false;
  }
  scene_ = std::move(*result.scene);
  ++version_;
  loaded_camera_ = scene_.camera;
  if (find_embedded_scene(scene_arg) != nullptr) {
    file_path_.clear();
    embedded_name_ = scene_arg;
    source_ = "embedded scene '" + scene_arg + "'";
  } else {
    file_path_ = scene_arg;
    embedded_name_.clear();
    source_ = scene_arg;
  }
  mtime_ = current_mtime();
  base_ = file_path_.empty() ? std::string() : ui::file_identity(file_path_);
  outside_change_ = false;
  mark_saved();
  loaded_ = true;
  error_text_.clear();
  status_ = "opened " + source_;
  return true;
}

bool SceneDocument::opened_mesh() const { return is_obj_path(file_path_); }

bool SceneDocument::reload(bool keep_view) {
  if (file_path_.empty()) {
    error_text_ = "an embedded scene has no file to reload";
    return false;
  }
  // Remember the modification time even on failure, so a broken file is reported once
  // rather than re-read twice a second.
  mtime_ = current_mtime();
  LoadResult result = load_scene_file(file_path_);
  base_ = ui::file_identity(file_path_);
  outside_change_ = false;
  if (!result.ok()) {
    error_text_ = result.error_text();
    return false;
  }
  const Camera view = scene_.camera;
  const bool file_kept_its_camera = same_camera(result.scene->camera, loaded_camera_);
  scene_ = std::move(*result.scene);
  ++version_;
  loaded_camera_ = scene_.camera;
  if (keep_view && file_kept_its_camera) scene_.camera = view;
  mark_saved();
  error_text_.clear();
  status_ = "reloaded " + file_path_;
  return true;
}

bool SceneDocument::write(const std::string& path) {
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  const std::string dir = parent.empty() ? std::string(".") : parent.string();
  // An embedded scene's meshes go beside it first: the file then opens anywhere.
  std::string error = write_embedded_meshes(scene_, dir);
  if (error.empty()) {
    // They are files on disk now, named from wherever the scene is written next (a recovery).
    for (Mesh& mesh : scene_.meshes) {
      if (mesh.resolved_path.empty() && embedded_file(mesh.file)) {
        mesh.resolved_path = std::filesystem::absolute(std::filesystem::path(dir) / mesh.file).lexically_normal().string();
      }
    }
    error = write_file_atomically(path, scene_to_json(scene_, dir));
  }
  if (!error.empty()) {
    error_text_ = error;
    return false;
  }
  error_text_.clear();
  mark_saved();
  status_ = "saved " + std::filesystem::absolute(path).lexically_normal().string();
  return true;
}

SceneDocument::SaveResult SceneDocument::save(bool overwrite_outside_change) {
  if (file_path_.empty()) {
    error_text_ = "an embedded scene has no file: use Save as";
    return SaveResult::kFailed;
  }
  if (opened_mesh()) {
    error_text_ = "this scene was opened from an OBJ file, which Save must not overwrite: use Save as (.json)";
    return SaveResult::kFailed;
  }
  if (changed_on_disk() && !overwrite_outside_change) return SaveResult::kChangedOnDisk;
  if (!write(file_path_)) return SaveResult::kFailed;
  loaded_camera_ = scene_.camera;
  mtime_ = current_mtime();  // our own write is not a change on disk
  base_ = ui::file_identity(file_path_);
  outside_change_ = false;
  return SaveResult::kSaved;
}

bool SceneDocument::save_as(const std::string& path) {
  if (path.empty()) {
    error_text_ = "Save as: type a file name into the path field first";
    return false;
  }
  if (is_obj_path(path)) {
    error_text_ = "Save as: a scene is saved as JSON; '" + path + "' would overwrite a mesh";
    return false;
  }
  if (!write(path)) return false;
  file_path_ = path;
  embedded_name_.clear();
  source_ = path;
  loaded_camera_ = scene_.camera;
  mtime_ = current_mtime();
  base_ = ui::file_identity(file_path_);
  outside_change_ = false;
  return true;
}

bool SceneDocument::changed_on_disk() const {
  if (file_path_.empty()) return false;
  return outside_change_ || current_mtime() != mtime_;
}

bool SceneDocument::edits_made_over(const std::string& base) {
  if (file_path_.empty()) return false;
  if (base.empty() || base != ui::file_identity(file_path_)) outside_change_ = true;
  if (!base.empty()) base_ = base;
  return outside_change_;
}

}  // namespace phonglab
