// Manifest assembly, CSV flattening, shard merging.
#include "jobs/sweep_manifest.h"

#include <filesystem>
#include <set>

#include "jobs/content_hash.h"
#include "jobs/sweep_index.h"
#include "slicer/file_io.h"
#include "slicer/input_error.h"
#include "slicer/params.h"

namespace strand::jobs {

namespace {

std::string csv_field(const nlohmann::json& v) {
  std::string s;
  if (v.is_null()) return "";
  if (v.is_string()) {
    s = v.get<std::string>();
  } else if (v.is_number_float()) {
    s = slicer::short_number(v.get<double>());
  } else if (v.is_array()) {
    for (const auto& e : v) s += (s.empty() ? "" : " ") + csv_field(e);
  } else {
    s = v.dump();
  }
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

const char* const kFigureColumns[] = {"porosity", "ink_volume_ml", "time_s", "layers", "strands_per_layer"};

std::string csv_row(const std::vector<std::string>& cells) {
  std::string line;
  for (std::size_t i = 0; i < cells.size(); ++i) line += (i ? "," : "") + cells[i];
  return line + "\n";
}

}  // namespace

std::string manifest_file_name(const Shard& shard) {
  if (shard.count == 1) return "manifest.json";
  return "manifest-shard-" + std::to_string(shard.index) + "-of-" + std::to_string(shard.count) + ".json";
}

nlohmann::json make_manifest(const SweepSpec& spec, const nlohmann::json& source,
                             const std::vector<nlohmann::json>& rows, const Shard& shard) {
  nlohmann::json m;
  m["sweep"] = {{"generator", spec.job.generator->name},
                {"machine", spec.job.settings.machine},
                {"mode", spec.mode == SweepMode::Zip ? "zip" : "product"},
                {"vary", spec.keys},
                {"points", expand_points(spec).size()},
                {"sweep_hash", fnv1a_hex(source.dump())},
                {"content_hash", "FNV-1a 64 of the G-code bytes"}};
  if (!spec.job.description.empty()) m["sweep"]["description"] = spec.job.description;
  if (shard.count > 1) m["shard"] = std::to_string(shard.index) + "/" + std::to_string(shard.count);
  m["points"] = rows;
  return m;
}

std::string manifest_csv(const nlohmann::json& m) {
  const auto& keys = m.at("sweep").at("vary");
  std::set<std::string> derived;
  for (const auto& r : m.at("points")) {
    if (r.contains("derived")) {
      for (const auto& [k, v] : r.at("derived").items()) derived.insert(k);
    }
  }
  std::vector<std::string> head = {"index", "name", "status"};
  for (const auto& k : keys) head.push_back(k.get<std::string>());
  for (const char* f : kFigureColumns) head.push_back(f);
  for (const auto& d : derived) head.push_back("derived." + d);
  for (const char* f : {"check_ok", "crossings", "output", "content_hash", "error"}) head.push_back(f);
  std::string out = csv_row(head);
  for (const auto& r : m.at("points")) {
    std::vector<std::string> c = {csv_field(r.at("index")), csv_field(r.at("name")), csv_field(r.at("status"))};
    for (const auto& k : keys) c.push_back(csv_field(r.at("parameters").value(k.get<std::string>(), nlohmann::json())));
    for (const char* f : kFigureColumns) c.push_back(csv_field(r.value(f, nlohmann::json())));
    for (const auto& d : derived) {
      c.push_back(r.contains("derived") ? csv_field(r.at("derived").value(d, nlohmann::json())) : "");
    }
    const nlohmann::json check = r.value("check", nlohmann::json::object());
    c.push_back(csv_field(check.value("ok", nlohmann::json())));
    c.push_back(csv_field(check.value("crossings", nlohmann::json())));
    c.push_back(csv_field(r.value("output", nlohmann::json())));
    c.push_back(csv_field(r.value("content_hash", nlohmann::json())));
    c.push_back(csv_field(r.contains("error") ? r.at("error") : r.value("reason", nlohmann::json())));
    out += csv_row(c);
  }
  return out;
}

void write_manifest(const nlohmann::json& m, const std::string& dir, const Shard& shard) {
  const std::filesystem::path d(dir);
  slicer::write_file_atomic((d / manifest_file_name(shard)).string(), m.dump(2) + "\n");
  if (shard.count > 1) return;
  slicer::write_file_atomic((d / "manifest.csv").string(), manifest_csv(m));
  slicer::write_file_atomic((d / "index.html").string(), sweep_index_html(m));
}

nlohmann::json merge_manifests(const std::vector<nlohmann::json>& shards, const std::vector<std::string>& paths) {
  if (shards.empty()) throw InputError("--merge: no shard manifests given or found");
  std::map<int, nlohmann::json> rows;
  std::set<std::string> seen;
  int count = 0;
  for (std::size_t i = 0; i < shards.size(); ++i) {
    const auto& s = shards[i];
    if (!s.is_object() || !s.contains("shard") || !s.contains("sweep") || !s.contains("points")) {
      throw InputError("--merge " + paths[i] + ": not a shard manifest (no \"shard\" key)");
    }
    const std::string id = s.at("shard").get<std::string>();
    const int n = parse_shard(id).count;
    if (count == 0) count = n;
    if (n != count || s.at("sweep") != shards[0].at("sweep")) {
      throw InputError("--merge " + paths[i] + ": shard " + id + " is from another sweep than " + paths[0]);
    }
    if (!seen.insert(id).second) throw InputError("--merge " + paths[i] + ": shard " + id + " given twice");
    for (const auto& r : s.at("points")) rows[r.at("index").get<int>()] = r;
  }
  if (static_cast<int>(seen.size()) != count) {
    throw InputError("--merge: " + std::to_string(seen.size()) + " of " + std::to_string(count) + " shards given");
  }
  nlohmann::json m;
  m["sweep"] = shards[0].at("sweep");
  m["points"] = nlohmann::json::array();
  for (auto& [index, r] : rows) m["points"].push_back(std::move(r));
  return m;
}

}  // namespace strand::jobs
