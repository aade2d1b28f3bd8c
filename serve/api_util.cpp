// Shared pieces of the route handlers (see api_state.h).
#include <algorithm>
#include <filesystem>
#include <thread>

#include "serve/api_state.h"
#include "serve/pages.h"
#include "serve/queue.h"

namespace strand::serve {

namespace fs = std::filesystem;
using nlohmann::json;

Api::State::State(const ApiOptions& o, const fs::path& d)
    : options(o), dir(d), store((d / "strand.sqlite").string()),
      pool(o.workers > 0 ? o.workers : static_cast<int>(std::clamp(std::thread::hardware_concurrency(), 1u, 4u)),
           kMaxWaitingJobs),
      queue(std::make_unique<Queue>(d, o.run_jobs)) {}

Api::State::~State() { queue.reset(); }

json figures_of(const json& report) {
  json f = json::object();
  try {
    const json& d = report.at("derived");
    const json& t = report.at("totals");
    f["derived"] = d;
    f["porosity"] = d.value("porosity", json());
    f["ink_volume_ml"] = t.value("ink_volume_ml", json());
    f["time_s"] = t.value("time_naive_s", json());
    f["layers"] = t.value("layers", json());
    f["strands_per_layer"] = report.value("strands_per_layer", json());
  } catch (const std::exception&) {  // a curved job's report: the summary says it all
  }
  return f;
}

std::string dump(const json& j) { return j.dump(-1, ' ', false, json::error_handler_t::replace); }

Response json_response(int status, const json& j) {
  Response r;
  r.status = status;
  r.body = dump(j) + "\n";
  return r;
}

Response error(int status, const std::string& message) {
  std::string line = message.substr(0, 1000);
  return json_response(status, {{"error", line}});
}

std::vector<std::string> split_path(const std::string& path) {
  std::vector<std::string> parts;
  std::size_t start = 1;
  if (path.empty() || path[0] != '/') return {"\x01"};  // matches no route
  while (start <= path.size()) {
    const std::size_t next = path.find('/', start);
    parts.push_back(path.substr(start, next == std::string::npos ? std::string::npos : next - start));
    if (next == std::string::npos) break;
    start = next + 1;
  }
  return parts;
}

std::int64_t parse_id(const std::string& text) {
  if (text.empty() || text.size() > 15 || !std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; })) {
    throw HttpError(404, "no job " + text.substr(0, 40) + " (ids are numbers, see GET /api/jobs)");
  }
  return std::stoll(text);
}

std::string header(const Request& r, const std::string& name) {
  const auto it = r.headers.find(name);
  return it == r.headers.end() ? "" : it->second;
}

namespace {
// "http://h:1/x" -> "h:1"
std::string authority_of(const std::string& url) {
  const auto scheme = url.find("://");
  if (scheme == std::string::npos) return "";
  const auto start = scheme + 3;
  const auto end = url.find_first_of("/?#", start);
  return url.substr(start, end == std::string::npos ? std::string::npos : end - start);
}
}  // namespace

std::string host_name(const std::string& authority) {
  if (!authority.empty() && authority[0] == '[') {
    const auto close = authority.find(']');
    return close == std::string::npos ? authority : authority.substr(1, close - 1);
  }
  return authority.substr(0, authority.find(':'));
}

bool same_origin(const Request& r) {
  const std::string host = header(r, "host");
  const std::string site = header(r, "sec-fetch-site");
  if (!site.empty() && site != "same-origin" && site != "none") return false;
  const std::string origin = header(r, "origin");
  if (!origin.empty()) return authority_of(origin) == host;
  const std::string referer = header(r, "referer");
  if (!referer.empty()) return authority_of(referer) == host;
  return true;  // not a browser (curl, scripts): CSRF needs a browser
}

bool equal_constant_time(const std::string& a, const std::string& b) {
  unsigned diff = a.size() == b.size() ? 0u : 1u;
  for (std::size_t i = 0; i < a.size(); ++i) diff |= static_cast<unsigned char>(a[i]) ^ static_cast<unsigned char>(b[i % (b.size() + 1)]);
  return diff == 0;
}

std::string cookie(const Request& r, const std::string& name) {
  const std::string all = header(r, "cookie");
  std::size_t pos = 0;
  while (pos < all.size()) {
    const std::size_t end = std::min(all.find(';', pos), all.size());
    std::string part = all.substr(pos, end - pos);
    part.erase(0, part.find_first_not_of(' '));
    if (part.rfind(name + "=", 0) == 0) return part.substr(name.size() + 1);
    pos = end + 1;
  }
  return "";
}

Response page_response(const std::string& name, const std::string& method) {
  if (method != "GET" && method != "HEAD")
    throw HttpError(405, method.substr(0, 20) + " " + name + ": use GET");
  for (const Page& pg : pages()) {
    if (name == pg.name) {
      Response out;
      out.content_type = "text/html; charset=utf-8";
      out.body = pg.text;
      return out;
    }
  }
  throw HttpError(404, "no page " + name);
}

std::string content_type_for(const std::string& name) {
  const std::string ext = fs::path(name).extension().string();
  if (ext == ".png") return "image/png";
  if (ext == ".html") return "text/html; charset=utf-8";
  if (ext == ".json") return "application/json";
  if (ext == ".csv") return "text/csv; charset=utf-8";
  if (ext == ".gcode" || ext == ".java" || ext == ".src" || ext == ".dat" || ext == ".txt" || ext == ".mod" || ext == ".script") {
    return "text/plain; charset=utf-8";
  }
  return "application/octet-stream";
}

}  // namespace strand::serve
