#include "apps/previewer/shell_state.h"

#include <algorithm>
#include <cmath>

#include "interaction/camera_control.h"

namespace phonglab {

namespace {

double mean(const std::vector<double>& v) {
  double sum = 0;
  for (const double x : v) sum += x;
  return v.empty() ? 0 : sum / static_cast<double>(v.size());
}

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const auto i = static_cast<std::size_t>(std::lround(p * static_cast<double>(v.size() - 1)));
  return v[std::min(i, v.size() - 1)];
}

}  // namespace

Cells cells(const ShellState& s) {
  Cells c;
  c.columns = s.instruments.small_multiples ? kMultiplesColumns : 1;
  c.rows = s.instruments.small_multiples ? kMultiplesRows : 1;
  c.x = s.viewport.x;
  c.y = s.viewport.y;
  c.width = s.viewport.width / static_cast<float>(c.columns);
  c.height = s.viewport.height / static_cast<float>(c.rows);
  return c;
}

double view_aspect(const ShellState& s) {
  if (!(s.viewport.width >= 1 && s.viewport.height >= 1)) return 0;
  const Cells c = cells(s);
  return static_cast<double>(c.width) / static_cast<double>(c.height);
}

Camera view_camera(const ShellState& s) {
  const Scene& scene = s.doc.scene();
  const double framed = scene.height > 0 ? static_cast<double>(scene.width) / scene.height : 0;
  return ui::fit_to_view(scene.camera, framed, view_aspect(s));
}

bool image_is_final(const ShellState& s) {
  const ProgressiveStatus status = s.renderer.status();
  return status.idle && status.serial > 0 && s.drawn_serial == status.serial && s.drawn_generation == status.generation &&
         !s.upload_pending;
}

void apply_edit(ShellState& s, const Edit& edit) {
  s.session.apply(edit);
  s.edits.scene = true;  // a restart, as for any edit a panel reports
}

void move_camera(ShellState& s, const Camera& camera) {
  s.session.apply({edit::SetCamera{camera}});
  s.edits.camera = true;
}

void write_stats_summary(ShellStats& stats, const std::string& label) {
  if (!stats.log) return;
  std::ofstream& log = stats.log;
  log << "summary " << label << " ui_frames " << stats.busy_frame_ms.size() << " mean_ms " << mean(stats.busy_frame_ms)
      << " p50_ms " << percentile(stats.busy_frame_ms, 0.5) << " p95_ms " << percentile(stats.busy_frame_ms, 0.95)
      << " p99_ms " << percentile(stats.busy_frame_ms, 0.99) << " max_ms " << percentile(stats.busy_frame_ms, 1.0) << "\n";
  log << "summary " << label << " edit_to_image n " << stats.latencies_ms.size() << " mean_ms " << mean(stats.latencies_ms)
      << " p50_ms " << percentile(stats.latencies_ms, 0.5) << " p95_ms " << percentile(stats.latencies_ms, 0.95)
      << " max_ms " << percentile(stats.latencies_ms, 1.0) << "\n";
  const auto frames_at = [&](int divisor) {
    const auto it = stats.frames_at_level.find(divisor);
    return it == stats.frames_at_level.end() ? 0 : it->second;
  };
  log << "levels " << label << " full=" << frames_at(1) << " half=" << frames_at(2) << " quarter=" << frames_at(4)
      << " eighth=" << frames_at(8) << "\n";
  log << "levels " << label << " rung quads=" << frames_at(0) << "\n";
  // Cores taken since the reset: the UI thread's (drawing included, llvmpipe being on it) and
  // the whole previewer's.
  const CpuClock cpu = CpuClock::now();
  const double wall = cpu.wall - stats.cpu_mark.wall;
  if (stats.cpu_mark.wall > 0 && wall > 0) {
    log << "summary " << label << " cores ui " << (cpu.thread - stats.cpu_mark.thread) / wall << " all "
        << (cpu.process - stats.cpu_mark.process) / wall << " drawn_frames " << stats.frames_drawn << "\n";
  }
  log << "summary " << label << " edit_to_full n " << stats.edit_to_full_ms.size() << " p50_ms "
      << percentile(stats.edit_to_full_ms, 0.5) << " p95_ms " << percentile(stats.edit_to_full_ms, 0.95) << "\n";
  // The passes' ray rates by level, each as a share of the full-resolution median ("small passes
  // as efficient as large ones", as the stats overlay shows them).
  const auto full = stats.pass_mrays.find(1);
  const double full_median = full != stats.pass_mrays.end() ? percentile(full->second, 0.5) : 0;
  for (const auto& [divisor, mrays] : stats.pass_mrays) {
    const double median = percentile(mrays, 0.5);
    log << "summary " << label << " passes " << (divisor == 0 ? "quads" : "1/" + std::to_string(divisor)) << " n "
        << mrays.size() << " median_mrays " << median << " of_full " << (full_median > 0 ? median / full_median : 0) << "\n";
  }
  log.flush();
}

}  // namespace phonglab
