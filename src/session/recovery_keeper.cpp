#include "session/recovery_keeper.h"

#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <system_error>

#include "io/scene/scene_io.h"

namespace phonglab {

std::string RecoveryKeeper::default_folder() {
  const std::string base = ui::state_dir();
  return base.empty() ? std::string() : base + "/recovery";
}

std::optional<std::pair<std::string, bool>> RecoveryKeeper::source_of(const SceneDocument& doc) {
  if (!doc.embedded_name().empty()) return std::pair{doc.embedded_name(), true};
  if (doc.file_path().empty()) return std::nullopt;  // a lesson's step: nobody's file
  std::error_code ec;
  const auto path = std::filesystem::absolute(doc.file_path(), ec).lexically_normal();
  return std::pair{ec ? doc.file_path() : path.string(), false};
}

void RecoveryKeeper::autosave(const SceneDocument& doc, double now) {
  if (!doc.dirty()) {
    remove();  // saved, or every edit undone: nothing to keep
    return;
  }
  if (written_for_ == last_edit_ || now - last_edit_ < kAutosaveDelay) return;
  if (!write(doc).empty()) written_for_ = last_edit_;
}

std::string RecoveryKeeper::write(const SceneDocument& doc) {
  const auto source = source_of(doc);
  if (!source || folder_.empty()) return "";
  std::error_code ec;
  std::filesystem::create_directories(folder_, ec);
  const std::string key = ui::recovery_key(source->first, source->second);
  const std::string json = folder_ + "/" + key + ".json";
  // Embedded meshes keep their embedded names; meshes on disk are named from the recovery folder.
  const std::string text = scene_to_json(doc.scene(), source->second ? "" : folder_);
  if (json == written_ && text == written_text_) return json;
  ui::RecoveryEntry entry;
  entry.scene_path = json;
  entry.source = source->first;
  entry.embedded = source->second;
  entry.saved = static_cast<std::int64_t>(std::time(nullptr));
  entry.base = doc.base_identity();  // what the edits are made over
  std::string error = write_file_atomically(json, text);
  if (error.empty()) error = write_file_atomically(folder_ + "/" + key + ".source", ui::recovery_source_text(entry));
  if (!error.empty()) {
    if (error != error_) std::cerr << "phonglab: cannot keep the unsaved edits in " << json << ": " << error << "\n";
    error_ = error;
    return "";
  }
  error_.clear();
  if (!written_.empty() && written_ != json) remove();
  written_ = json;
  written_text_ = text;
  return json;
}

void RecoveryKeeper::remove() {
  if (written_.empty()) return;
  std::error_code ec;
  std::filesystem::remove(written_, ec);
  std::filesystem::remove(std::filesystem::path(written_).replace_extension(".source"), ec);
  written_.clear();
  written_text_.clear();
}

std::optional<ui::RecoveryEntry> RecoveryKeeper::find(const SceneDocument& doc, bool any_source) const {
  const auto source = source_of(doc);
  for (const ui::RecoveryEntry& e : ui::list_recoveries(folder_)) {
    if (any_source || (source && e.source == source->first && e.embedded == source->second)) return e;
  }
  return std::nullopt;
}

RecoveryKeeper::Restored RecoveryKeeper::restore(SceneDocument& doc, const ui::RecoveryEntry& entry) {
  std::ifstream in(entry.scene_path);
  std::ostringstream text;
  text << in.rdbuf();
  const std::string dir = std::filesystem::path(entry.scene_path).parent_path().string();
  LoadResult r = load_scene_text(text.str(), entry.scene_path, dir, entry.embedded);
  if (!r.ok()) return Restored{r.error_text(), false, {}};
  doc.restore_edits(std::move(*r.scene));
  Restored out;
  if (!entry.embedded) out.changed_on_disk = doc.edits_made_over(entry.base);
  out.status = "restored the unsaved edits kept in " + entry.scene_path;
  if (out.changed_on_disk) {
    out.status += "; " + entry.source + " changed on disk since they were made: Save asks before it overwrites that change";
  }
  adopt(entry);
  return out;
}

void RecoveryKeeper::adopt(const ui::RecoveryEntry& entry) {
  written_ = entry.scene_path;
  written_text_.clear();
  written_for_ = last_edit_;
}

}  // namespace phonglab
