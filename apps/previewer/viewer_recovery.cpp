// Nothing lost: unsaved edits go to a recovery file in the state folder a few seconds after the
// last edit and when SIGINT, SIGTERM or SIGHUP arrives; the next start offers them back; a clean
// save or quit removes the file (docs/previewer.md#recovery).
#include "apps/previewer/viewer_app.h"

#include <pthread.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <thread>

#include "io/scene/scene_io.h"

namespace phonglab {

namespace {

constexpr double kAutosaveDelay = 2.0;  // seconds after the last edit: a drag's many edits are one write
std::atomic<int> g_signal{0};

std::string recovery_folder() {
  const std::string base = ui::state_dir();
  return base.empty() ? std::string() : base + "/recovery";
}

std::string read_all(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

void start_signal_watcher() {
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGTERM);
  sigaddset(&set, SIGHUP);
  pthread_sigmask(SIG_BLOCK, &set, nullptr);
  std::thread([set] {
    for (;;) {
      int sig = 0;
      if (sigwait(&set, &sig) != 0) continue;
      if (g_signal.exchange(sig) != 0) _exit(128 + sig);  // asked twice: no more waiting
      glfwPostEmptyEvent();  // GLFW allows it from any thread
    }
  }).detach();
}

int pending_signal() { return g_signal.load(); }

std::optional<std::pair<std::string, bool>> Viewer::recovery_source() const {
  if (!doc_.embedded_name().empty()) return std::pair{doc_.embedded_name(), true};
  if (doc_.file_path().empty()) return std::nullopt;  // a lesson's step: nobody's file
  std::error_code ec;
  const auto path = std::filesystem::absolute(doc_.file_path(), ec).lexically_normal();
  return std::pair{ec ? doc_.file_path() : path.string(), false};
}

std::string Viewer::write_recovery() {
  const auto source = recovery_source();
  const std::string dir = recovery_folder();
  if (!source || dir.empty()) return "";
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  const std::string key = ui::recovery_key(source->first, source->second);
  const std::string json = dir + "/" + key + ".json";
  // Embedded meshes keep their embedded names; meshes on disk are named from the recovery folder.
  const std::string text = scene_to_json(doc_.scene(), source->second ? "" : dir);
  if (json == recovery_.written && text == recovery_.written_text) return json;
  ui::RecoveryEntry entry;
  entry.scene_path = json;
  entry.source = source->first;
  entry.embedded = source->second;
  entry.saved = static_cast<std::int64_t>(std::time(nullptr));
  std::string error = write_file_atomically(json, text);
  if (error.empty()) error = write_file_atomically(dir + "/" + key + ".source", ui::recovery_source_text(entry));
  if (!error.empty()) {
    if (error != recovery_.error) std::cerr << "phonglab: cannot keep the unsaved edits in " << json << ": " << error << "\n";
    recovery_.error = error;
    return "";
  }
  recovery_.error.clear();
  if (!recovery_.written.empty() && recovery_.written != json) remove_recovery();
  recovery_.written = json;
  recovery_.written_text = text;
  return json;
}

void Viewer::remove_recovery() {
  if (recovery_.written.empty()) return;
  std::error_code ec;
  std::filesystem::remove(recovery_.written, ec);
  std::filesystem::remove(std::filesystem::path(recovery_.written).replace_extension(".source"), ec);
  recovery_.written.clear();
  recovery_.written_text.clear();
}

void Viewer::autosave(double now) {
  if (!doc_.dirty()) {
    remove_recovery();  // saved, or every edit undone: nothing to keep
    return;
  }
  // Once per burst of edits: the file is written when the last edit is kAutosaveDelay old, not again each frame.
  if (recovery_.written_for == recovery_.last_edit || now - recovery_.last_edit < kAutosaveDelay) return;
  if (!write_recovery().empty()) recovery_.written_for = recovery_.last_edit;
}

bool Viewer::handle_signal() {
  const int sig = pending_signal();
  if (sig == 0) return false;
  doc_.update_dirty();
  if (doc_.dirty()) {
    const std::string path = write_recovery();
    if (!path.empty()) std::cerr << "recovery: " << path << "\n";
  }
  recovery_.keep = true;
  exit_code_ = 128 + sig;
  quit_ = true;
  return true;
}

void Viewer::find_recovery() {
  const std::vector<ui::RecoveryEntry> all = ui::list_recoveries(recovery_folder());
  const auto source = recovery_source();
  for (const ui::RecoveryEntry& e : all) {
    // On that scene, or with no SCENE at all the newest of any scene.
    if (!options_.scene_given || (source && e.source == source->first && e.embedded == source->second)) {
      recovery_.offer = e;
      recovery_.open_modal = true;
      return;
    }
  }
}

void Viewer::handle_recovery_modal() {
  if (!recovery_.offer) return;
  char when[64] = "earlier";
  const std::time_t t = static_cast<std::time_t>(recovery_.offer->saved);
  if (std::tm tm{}; localtime_r(&t, &tm) != nullptr) std::strftime(when, sizeof when, "at %Y-%m-%d %H:%M:%S", &tm);
  const std::string source = recovery_.offer->embedded ? "the embedded scene '" + recovery_.offer->source + "'"
                                                       : recovery_.offer->source;
  const auto choice = ui::recovery_modal(recovery_.open_modal, source, when,
                                         static_cast<ui::RecoveryChoice>(recovery_.scripted));
  if (recovery_.open_modal) recovery_.modal_visible = true;
  recovery_.open_modal = false;
  recovery_.scripted = 0;
  if (choice == ui::RecoveryChoice::kNone) return;
  recovery_.modal_visible = false;
  const ui::RecoveryEntry entry = *recovery_.offer;
  recovery_.offer.reset();
  if (choice == ui::RecoveryChoice::kRestore) {
    restore_recovery(entry);
  } else if (choice == ui::RecoveryChoice::kDiscard) {
    std::error_code ec;
    std::filesystem::remove(entry.scene_path, ec);
    std::filesystem::remove(std::filesystem::path(entry.scene_path).replace_extension(".source"), ec);
  }
}

void Viewer::restore_recovery(const ui::RecoveryEntry& entry) {
  const auto source = recovery_source();
  if (!source || source->first != entry.source || source->second != entry.embedded) {
    open_scene(entry.source);
    const auto now_source = recovery_source();
    if (!now_source || now_source->first != entry.source) {
      file_state_.error_text = "cannot restore: " + entry.source + " does not open (" + file_state_.error_text +
                               "); the kept edits stay in " + entry.scene_path;
      return;
    }
  }
  const std::string text = read_all(entry.scene_path);
  const std::string dir = std::filesystem::path(entry.scene_path).parent_path().string();
  LoadResult r = load_scene_text(text, entry.scene_path, dir, entry.embedded);
  if (!r.ok()) {
    file_state_.error_text = r.error_text();
    return;
  }
  doc_.scene() = std::move(*r.scene);
  doc_.update_dirty();
  recovery_.written = entry.scene_path;  // this document's now: removed once saved, rewritten on edits
  recovery_.written_text.clear();
  recovery_.written_for = recovery_.last_edit;  // the file holds what is restored
  file_state_.status = "restored the unsaved edits kept in " + entry.scene_path;
  edits_.replaced = true;
}

}  // namespace phonglab
