// What POST /api/jobs and /api/generate read: a job file as JSON, whose curved substrate is
// its "substrate" object or the CLI's flags by name (substrate, substrate-radius,
// substrate-length, wrap, arc-length-at, extrusion), or multipart/form-data with that JSON in
// field `job` and the substrate mesh uploaded in field `substrate-mesh`. The client never
// names a file the server reads: an uploaded mesh is kept as substrate.EXT in the job's folder.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "serve/api.h"

namespace strand::serve {

struct JobRequest {
  nlohmann::json job;     // the job file, its substrate as the object job files hold
  std::string mesh;       // the uploaded substrate mesh's bytes; "" for none
  std::string mesh_name;  // the server's name for it, by its content: substrate.EXT
};

// Throws InputError naming the first bad key or field (a substrate's are checked here, as
// `strand job` checks them: "substrate.radius = 0: must be > 0 (mm)"), HttpError 413 past
// kMaxUploadBytes. With a mesh, job.substrate is {"type": "mesh", "mesh": mesh_name, ...}.
JobRequest read_job_request(const Request& r);

}  // namespace strand::serve
