// A job request read on the HTTP thread: the substrate gathered under the job file's keys and
// checked by the substrate table, an uploaded mesh told apart by its content and bounded.
#include "serve/job_request.h"

#include <string_view>

#include "serve/api_state.h"
#include "serve/slice_api.h"
#include "slicer/input_error.h"
#include "slicer/json_input.h"
#include "slicer/substrate_params.h"

namespace strand::serve {

using nlohmann::json;

namespace {

// The CLI's substrate flags as a request may name them, and the table key each sets.
constexpr std::pair<std::string_view, std::string_view> kSubstrateFlags[] = {
    {"substrate", "type"}, {"substrate-radius", "radius"}, {"substrate-length", "length"},
    {"wrap", "wrap"},      {"arc-length-at", "arc-length-at"}, {"extrusion", "extrusion"},
};

// {"substrate": "cylinder", "substrate-radius": 20, ...} -> {"substrate": {"type": ..., "radius": ...}}.
void gather_substrate(json& j) {
  json substrate = json::object();
  if (j.contains("substrate")) {
    if (j.at("substrate").is_object()) substrate = j.at("substrate");
    else if (!j.at("substrate").is_string())
      throw InputError("job.substrate: must be cylinder or mesh, or an object like {\"type\": \"cylinder\", \"radius\": 20, \"length\": 80}");
  }
  for (const auto& [flag, key] : kSubstrateFlags) {
    const std::string f(flag), k(key);
    if (!j.contains(f) || (f == "substrate" && j.at(f).is_object())) continue;
    if (substrate.contains(k)) throw InputError("job." + f + ": given twice (also as substrate." + k + ")");
    substrate[k] = j.at(f);
    j.erase(f);
  }
  if (j.contains("substrate-mesh") || substrate.contains("mesh")) {
    throw InputError("job.substrate-mesh: the server reads no path; upload the mesh as the multipart field "
                     "substrate-mesh (STL, OBJ, PLY, OFF, glTF/GLB or 3MF)");
  }
  if (!substrate.empty()) j["substrate"] = substrate;
  else j.erase("substrate");
}

// The multipart form: field job (the JSON) and, optionally, the file substrate-mesh.
JobRequest read_form(const Request& r) {
  std::size_t bytes = 0;
  for (const Upload& u : r.files) bytes += u.content.size() + u.name.size();
  if (bytes > kMaxUploadBytes) {
    throw HttpError(413, "upload of " + std::to_string(bytes) + " bytes, more than the " +
                             std::to_string(kMaxUploadBytes) + " accepted");
  }
  JobRequest out;
  bool have_job = false, have_mesh = false;
  for (const Upload& u : r.files) {
    if (u.name == "job" && !have_job) {
      if (u.content.size() > kMaxBodyBytes) throw InputError("job: longer than " + std::to_string(kMaxBodyBytes) + " bytes");
      out.job = slicer::parse_json(u.content, "job");
      have_job = true;
    } else if (u.name == "substrate-mesh" && !have_mesh) {
      const std::string ext = mesh_extension(u.content);
      if (ext.empty()) throw InputError("job.substrate-mesh: not a mesh file (STL, OBJ, PLY, OFF, glTF/GLB or 3MF)");
      check_mesh_references(u.content, ext, "job.substrate-mesh");
      out.mesh = u.content;
      out.mesh_name = "substrate" + ext;
      have_mesh = true;
    } else {
      throw InputError("job." + u.name.substr(0, 40) +
                       (u.name == "job" || u.name == "substrate-mesh" ? ": given twice"
                                                                      : ": unknown field (job: the job's JSON; substrate-mesh: the mesh file)"));
    }
  }
  if (!have_job) throw InputError("job: missing (the field job holds the job's JSON: generator, machine, params, substrate)");
  return out;
}

}  // namespace

JobRequest read_job_request(const Request& r) {
  JobRequest out = r.files.empty() ? JobRequest{slicer::parse_json(r.body, "request"), "", ""} : read_form(r);
  json& j = out.job;
  if (!j.is_object()) throw InputError("request: must be a JSON object (a job file: generator, machine, params)");
  gather_substrate(j);
  if (!out.mesh.empty()) {
    json& s = j["substrate"];
    if (!s.contains("type")) s["type"] = "mesh";
    if (s.at("type") != "mesh") {
      throw InputError("job.substrate-mesh: only with substrate mesh (substrate = " + s.at("type").dump().substr(0, 40) + ")");
    }
    s["mesh"] = out.mesh_name;
  }
  if (j.contains("substrate")) slicer::substrate_from(j.at("substrate"));  // every problem, named, before a job is made
  return out;
}

}  // namespace strand::serve
