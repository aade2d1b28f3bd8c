// Fuzz target: any bytes as an HTTP request to the workbench's handlers (serve::Api), read as
// "METHOD TARGET\nName: value\n...\n\nBODY"; a head line "@field=text" is an uploaded part (a
// multipart form's field or file, as cpp-httplib hands them over). Every request must get an answer with a status
// and, for errors, one line of JSON; nothing may throw. Generation is checked but not run
// (ApiOptions::run_jobs = false): the bound on work per input.
#include <stdlib.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <nlohmann/json.hpp>
#include <filesystem>
#include <string>

#include "serve/api.h"

namespace {

strand::serve::Api& api() {
  static std::unique_ptr<strand::serve::Api> a = [] {
    std::string dir =
        (std::filesystem::temp_directory_path() / "strand-serve-fuzz-XXXXXX").string();
    if (!::mkdtemp(dir.data())) std::abort();
    strand::serve::ApiOptions o;
    o.data_dir = dir;
    o.run_jobs = false;
    o.workers = 1;
    return std::make_unique<strand::serve::Api>(o);
  }();
  return *a;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace strand::serve;
  const std::string text(reinterpret_cast<const char*>(data), size);
  Request r;
  const auto head_end = text.find("\n\n");
  const std::string head = text.substr(0, head_end);
  r.body = head_end == std::string::npos ? "" : text.substr(head_end + 2);
  std::size_t pos = 0;
  bool first = true;
  while (pos <= head.size()) {
    const auto end = std::min(head.find('\n', pos), head.size());
    const std::string line = head.substr(pos, end - pos);
    if (first) {
      const auto sp = line.find(' ');
      r.method = line.substr(0, sp);
      const std::string target = sp == std::string::npos ? "/" : line.substr(sp + 1);
      const auto q = target.find('?');
      r.path = target.substr(0, q);
      if (q != std::string::npos) {
        const std::string query = target.substr(q + 1);
        const auto eq = query.find('=');
        r.query[query.substr(0, eq)] = eq == std::string::npos ? "" : query.substr(eq + 1);
      }
      first = false;
    } else if (!line.empty() && line[0] == '@') {
      const auto eq = line.find('=');
      Upload u;
      u.name = line.substr(1, eq == std::string::npos ? std::string::npos : eq - 1);
      u.filename = u.name + ".svg";
      u.content = eq == std::string::npos ? "" : line.substr(eq + 1);
      for (char& c : u.content) c = c == '\x01' ? '\n' : c;  // newlines inside a part
      r.files.push_back(u);
    } else {
      const auto colon = line.find(": ");
      if (colon != std::string::npos) r.headers[line.substr(0, colon)] = line.substr(colon + 2);
    }
    pos = end + 1;
  }
  const Response out = api().handle(r);
  if (out.status < 200 || out.status > 599) std::abort();
  if (out.status >= 400) {
    const auto j = nlohmann::json::parse(out.body, nullptr, false);
    if (!j.is_object() || !j.contains("error") || out.body.find('\n') != out.body.size() - 1) std::abort();
  }
  return 0;
}
