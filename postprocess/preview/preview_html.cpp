// The HTML preview page: scene data as inline JSON in the viewer page.
#include "postprocess/preview/preview_html.h"

#include <nlohmann/json.hpp>

#include <algorithm>

#include <Eigen/Geometry>  // triangle normals

#include "machines/gcode_format.h"
#include "postprocess/preview/preview_html_page.h"

namespace strand::post {

namespace {

std::string escape_html(const std::string& s) {
  std::string o;
  for (char c : s) {
    if (c == '<') o += "&lt;";
    else if (c == '>') o += "&gt;";
    else if (c == '&') o += "&amp;";
    else if (c == '"') o += "&quot;";
    else o += c;
  }
  return o;
}

void replace_all(std::string& s, const std::string& what, const std::string& with) {
  for (auto at = s.find(what); at != std::string::npos; at = s.find(what, at + with.size())) s.replace(at, what.size(), with);
}

std::string number_list(const std::vector<double>& values) {
  std::string out = "[";
  for (std::size_t i = 0; i < values.size(); ++i) {
    out += (i ? "," : "") + machines::fmt_xyz(values[i]);
  }
  return out + "]";
}

// Paths as raw JSON with coordinates to 3 decimals (G-code precision, stable bytes): x, y
// per point in a planar scene, x, y, z in a 3D one. Layer -1 (before the first layer, a
// purge line) stays -1 so the page can leave it out of the fit.
std::string paths_json(const PreviewScene& s, const std::vector<PreviewKey>& used, int dim) {
  std::string out = "[";
  for (std::size_t i = 0; i < s.paths.size(); ++i) {
    const auto& p = s.paths[i];
    const auto f =
        p.travel ? 0 : std::find(used.begin(), used.end(), deposit_key(s, p)) - used.begin();
    out += std::string(i ? "," : "") + "{\"l\":" + std::to_string(std::max(p.layer, -1)) +
           ",\"t\":" + (p.travel ? "1" : "0") + ",\"f\":" + std::to_string(p.travel ? 0 : f) +
           ",\"p\":[";
    for (std::size_t k = 0; k < p.points_mm.size(); ++k) {
      for (int c = 0; c < dim; ++c) {
        out += (k || c ? "," : "") + machines::fmt_xyz(p.points_mm[k][c]);
      }
    }
    out += "]}";
  }
  return out + "]";
}

// The substrate's vertices (3 decimals), triangles and unit normal per triangle.
std::string substrate_json(const slicer::TriangleMesh& m) {
  std::vector<double> v, n;
  for (const auto& p : m.vertices_mm) v.insert(v.end(), {p.x(), p.y(), p.z()});
  std::string t = "[";
  for (std::size_t i = 0; i < m.triangles.size(); ++i) {
    const auto& tri = m.triangles[i];
    t += (i ? "," : "") + std::to_string(tri[0]) + "," + std::to_string(tri[1]) + "," +
         std::to_string(tri[2]);
    const slicer::Vec3 a = m.vertices_mm[static_cast<std::size_t>(tri[0])];
    const slicer::Vec3 c = (m.vertices_mm[static_cast<std::size_t>(tri[1])] - a)
                               .cross(m.vertices_mm[static_cast<std::size_t>(tri[2])] - a);
    const slicer::Vec3 u = c.norm() > 0 ? slicer::Vec3(c.normalized()) : slicer::Vec3::UnitZ();
    n.insert(n.end(), {u.x(), u.y(), u.z()});
  }
  return "\"substrate\":{\"v\":" + number_list(v) + ",\"t\":" + t +
         "]},\"substrateNormals\":" + number_list(n) + ",";
}

std::string scene_json(const PreviewScene& s) {
  const int dim = is_3d(s) ? 3 : 2;
  const auto used = deposit_keys(s);  // the legend and the paths' colour index
  std::vector<double> bounds;
  for (const auto* b : {&s.min_mm, &s.max_mm}) {
    for (int c = 0; c < dim; ++c) bounds.push_back((*b)[c]);
  }
  nlohmann::json meta;
  meta["width"] = s.bead_width_mm > 0 ? s.bead_width_mm : 0.4;
  meta["layerValue"] = s.layer_value;
  meta["features"] = nlohmann::json::array();
  meta["colours"] = nlohmann::json::array();
  for (const auto& k : used) {
    meta["features"].push_back(k.name);
    meta["colours"].push_back(hex_colour(k.colour));
  }
  if (used.empty()) meta["colours"].push_back("#888888");
  std::string out = "{\"dim\":" + std::to_string(dim) + ",\"paths\":" + paths_json(s, used, dim) +
                    ",\"layers\":" + number_list(s.layer_z_mm) + ",\"bounds\":" +
                    number_list(bounds) + ",";
  if (!s.substrate.triangles.empty()) out += substrate_json(s.substrate);
  return out + meta.dump().substr(1);
}

}  // namespace

std::string render_html(const PreviewScene& scene, const std::string& title) {
  std::string page = html_page_template();
  std::string data = scene_json(scene);
  replace_all(data, "</", "<\\/");  // keep the JSON from closing its script element
  replace_all(page, "@TITLE@", escape_html(title));
  replace_all(page, "@DATA@", data);
  return page;
}

}  // namespace strand::post
