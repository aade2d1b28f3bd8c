// One row per point: run, check, preview, or record why not.
#include "jobs/sweep_runner.h"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <filesystem>
#include <mutex>

#include "postprocess/inspect/gcode_parser.h"
#include "postprocess/preview/preview_html.h"
#include "postprocess/preview/preview_image.h"
#include "jobs/content_hash.h"
#include "jobs/sweep_check.h"
#include "jobs/sweep_journal.h"
#include "jobs/sweep_manifest.h"
#include "slicer/file_io.h"
#include "slicer/input_error.h"
#include "slicer/json_input.h"
#include "slicer/tolerances.h"

namespace strand::jobs {

namespace fs = std::filesystem;

namespace {

// A machine given as a file path counts by its content, so editing the profile reruns.
std::string machine_key(const std::string& machine) {
  std::error_code ec;
  if (!fs::is_regular_file(machine, ec)) return machine;
  return machine + "#" + fnv1a_hex(slicer::read_file(machine));
}

std::string params_hash(const SweepSpec& s, const SweepPoint& p) {
  const nlohmann::json key = {{"strand", STRAND_VERSION},
                              {"generator", s.job.generator->name},
                              {"machine", machine_key(s.job.settings.machine)},
                              {"arc-tolerance", s.job.settings.arc_tolerance_mm},
                              {"params", p.params}};
  return fnv1a_hex(key.dump());
}

nlohmann::json base_row(const SweepPoint& p, const std::string& status) {
  return {{"index", p.index}, {"name", p.name}, {"status", status}, {"parameters", p.varied}};
}

nlohmann::json figures(const nlohmann::json& report) {
  const auto& d = report.at("derived");
  const auto& tot = report.at("totals");
  return {{"derived", d},
          {"porosity", d.value("porosity", nlohmann::json())},
          {"ink_volume_ml", tot.at("ink_volume_ml")},
          {"time_s", tot.at("time_naive_s")},
          {"layers", tot.at("layers")},
          {"strands_per_layer", report.at("strands_per_layer")}};
}

bool up_to_date(const nlohmann::json* prev, const std::string& hash, const std::string& dir) {
  if (!prev || prev->value("status", "") != "ok" || prev->value("params_hash", "") != hash) return false;
  const fs::path file = fs::path(dir) / prev->value("output", "");
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) return false;
  if (prev->contains("report") && !fs::is_regular_file(fs::path(dir) / prev->value("report", ""), ec)) return false;
  return fnv1a_hex(slicer::read_file(file.string())) == prev->value("content_hash", "");
}

// The PNG thumbnail and the interactive HTML page of one point, from one parse.
void write_previews(const std::string& dir, const std::string& name, std::string_view gcode) {
  const post::PreviewScene scene =
      post::preview_scene(post::parse_gcode(gcode).program, slicer::kDefaultArcToleranceMm);
  const fs::path base = fs::path(dir) / "previews";
  slicer::write_file_atomic((base / (name + ".png")).string(), thumbnail_png(scene));
  slicer::write_file_atomic((base / (name + ".html")).string(), post::render_html(scene, name + ".gcode"));
}

nlohmann::json run_point(const SweepSpec& s, const SweepPoint& p, const SweepOptions& o,
                         const nlohmann::json* prev, bool& reused) {
  if (!p.dropped.empty()) {
    nlohmann::json row = base_row(p, "dropped");
    row["reason"] = p.dropped;
    return row;
  }
  nlohmann::json row = base_row(p, "failed");
  if (!p.error.empty()) {
    row["error"] = p.error;
    return row;
  }
  const std::string hash = params_hash(s, p);
  row["params_hash"] = hash;
  try {
    const std::string preview = "previews/" + p.name + ".png";
    const std::string page = "previews/" + p.name + ".html";
    if (up_to_date(prev, hash, o.dir) && prev->value("preview", nlohmann::json()).is_string() == o.previews) {
      reused = true;
      if (o.previews && !(fs::exists(fs::path(o.dir) / preview) && fs::exists(fs::path(o.dir) / page))) {
        write_previews(o.dir, p.name, slicer::read_file((fs::path(o.dir) / prev->at("output").get<std::string>()).string()));
      }
      return *prev;
    }
    JobSettings settings = s.job.settings;
    settings.output = p.name + ".gcode";
    settings.report.clear();
    const post::Produced produced = produce_job(*s.job.generator, p.params, settings);
    slicer::write_file_atomic((fs::path(o.dir) / settings.output).string(), produced.gcode);
    if (o.previews) write_previews(o.dir, p.name, produced.gcode);
    row["status"] = "ok";
    row["output"] = settings.output;
    row["preview"] = o.previews ? nlohmann::json(preview) : nlohmann::json();
    row["preview_html"] = o.previews ? nlohmann::json(page) : nlohmann::json();
    if (!s.job.settings.report.empty()) {  // the base job asked for reports: one per point
      row["report"] = p.name + ".report.json";
      slicer::write_file_atomic((fs::path(o.dir) / row["report"].get<std::string>()).string(), slicer::dump_json(produced.report) + "\n");
    }
    row["content_hash"] = fnv1a_hex(produced.gcode);
    row["check"] = sweep_check_summary(produced.gcode, settings.machine);
    row.update(figures(produced.report));
  } catch (const std::exception& e) {  // InputError and bugs alike: record, keep going
    row["error"] = e.what();
  }
  return row;
}

// Rows of earlier runs: the manifest, then the journal of a run that was interrupted
// before writing it (newer, so it wins). Unreadable input only means less is reused.
std::map<std::string, nlohmann::json> previous_rows(const fs::path& manifest, const fs::path& journal) {
  std::map<std::string, nlohmann::json> rows;
  std::error_code ec;
  try {
    if (fs::is_regular_file(manifest, ec)) {
      const nlohmann::json m = nlohmann::json::parse(slicer::read_file(manifest.string()));
      for (const auto& r : m.at("points")) rows[r.at("name").get<std::string>()] = r;
    }
  } catch (const std::exception&) {
    rows.clear();
  }
  for (auto& [name, row] : journal_rows(journal.string())) rows[name] = std::move(row);
  return rows;
}

}  // namespace

std::string thumbnail_png(const post::PreviewScene& scene) {
  post::ImageOptions o;
  // The size the contact sheet shows (240 x 200): PNG encoding and drawing cost grow with
  // the pixels, and at 360 x 300 they were most of a sweep's time.
  o.width_px = 240;
  o.height_px = 200;
  o.view = post::PreviewView::Top;
  return post::render_png(scene, o);
}

SweepResult run_sweep(const SweepSpec& spec, const nlohmann::json& source, const SweepOptions& o,
                      const ProgressFn& progress) {
  std::vector<SweepPoint> points;
  const std::vector<SweepPoint> all = expand_points(spec);
  for (const auto& p : all) {
    if (in_shard(p.index, o.shard)) points.push_back(p);
  }
  std::error_code ec;
  fs::create_directories(fs::path(o.dir) / (o.previews ? "previews" : ""), ec);
  if (ec) throw InputError("-o = " + o.dir + ": cannot create the directory");
  // Finished points are journalled as they complete, so an interrupted sweep resumes; the
  // journal's lock keeps a second run of this shard out until this one ends.
  const fs::path journal_file = fs::path(o.dir) / journal_file_name(o.shard);
  SweepJournal journal(journal_file.string(), o.shard, all.size());
  const auto prev = previous_rows(fs::path(o.dir) / manifest_file_name(o.shard), journal_file);
  std::vector<nlohmann::json> rows(points.size());
  std::mutex m;
  SweepProgress state;
  state.total = points.size();
  const int threads = o.jobs > 0 ? o.jobs : tbb::this_task_arena::max_concurrency();
  tbb::task_arena arena(threads);
  arena.execute([&] {
    tbb::parallel_for(std::size_t{0}, points.size(), [&](std::size_t i) {
      const auto it = prev.find(points[i].name);
      bool reused = false;
      rows[i] = run_point(spec, points[i], o, it == prev.end() ? nullptr : &it->second, reused);
      const std::lock_guard<std::mutex> lock(m);
      if (rows[i].at("status") == "ok") journal.append(rows[i]);
      ++state.done;
      state.failed += rows[i].at("status") == "failed";
      state.reused += reused;
      state.row = &rows[i];
      if (progress) progress(state);
    });
  });
  SweepResult r;
  r.manifest = make_manifest(spec, source, rows, o.shard);
  write_manifest(r.manifest, o.dir, o.shard);
  journal.finish();
  for (const auto& row : rows) {
    r.failed += row.at("status") == "failed";
    r.dropped += row.at("status") == "dropped";
  }
  r.reused = state.reused;
  r.ran = rows.size() - r.failed - r.dropped - r.reused;
  return r;
}

}  // namespace strand::jobs
