// The workbench's slicing: the /slice page and POST /api/slice (Api::State::route_slice), a
// multipart upload of a mesh (STL, OBJ, PLY, OFF, glTF/GLB, 3MF) sliced exactly as `strand
// slice` slices it, on the worker pool, and kept in the gallery.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "jobs/slice_job.h"
#include "serve/api.h"

namespace strand::serve {

// One slice as the form asks for it: field file (the mesh), name, machine, and the flags of
// `strand slice` by their long names (pattern, perimeters, mesh-units, place, rotate, scale,
// scale-to-fit, up, repair, strict, and the pattern's own flags), each converted as the
// command line converts them.
struct SliceForm {
  std::string mesh;                // the file's bytes
  std::string input = "part.stl";  // the server's name for it, by its content: part.EXT
  std::string name;                // the gallery name (the form's, else the client's file name)
  jobs::SliceSettings settings;    // everything but the part's path and the output
  nlohmann::json fields = nlohmann::json::object();  // the flags as written, for "open to edit"
};

// The mesh format of `bytes` by their content: ".stl", ".obj", ".ply", ".off", ".gltf",
// ".glb", ".3mf", or "" for none of them.
std::string mesh_extension(const std::string& bytes);

// Refuses a mesh that would make its reader open another file (a glTF's external buffers or
// images, an OBJ's material library by a path): InputError "FIELD: ...".
void check_mesh_references(const std::string& bytes, const std::string& ext, const std::string& field);

// Throws InputError naming the first bad field ("scaffold.nozzle = -1: must be in ..."), or
// HttpError 413 past kMaxUploadBytes. The client's file name is never a path: the server
// keeps the mesh as part.EXT, and a mesh that names other files (a glTF's external buffers,
// an OBJ's material library outside its directory) is refused.
SliceForm read_slice_form(const Request& r);

}  // namespace strand::serve
