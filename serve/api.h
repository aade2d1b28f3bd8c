// The workbench's request handling, apart from the HTTP library: a Request in, a Response
// out, so the same code is served by server.cpp, tested and fuzzed. Every request gets an
// answer: a malformed one a 4xx JSON {"error": "..."} of one line, never an exception.
#pragma once

#include <cstddef>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace strand::serve {

// Largest request body accepted (a job file's JSON is a few hundred bytes).
inline constexpr std::size_t kMaxBodyBytes = 1 << 20;
// Largest multipart upload to POST /api/plot and /api/slice (the drawing, image or mesh and
// the form's fields).
inline constexpr std::size_t kMaxUploadBytes = 16 << 20;
// Longest saved-job name, in bytes.
inline constexpr std::size_t kMaxNameBytes = 200;
// Unsaved jobs (the design page's live previews) kept on disk; older ones are removed.
inline constexpr int kKeepUnsavedJobs = 50;
// Generation requests waiting for a worker beyond the running ones; more get 503.
inline constexpr std::size_t kMaxWaitingJobs = 16;
// Longest a request waits for its job before it gets 503 (the job still finishes).
inline constexpr int kMaxJobWaitSeconds = 300;

// One part of a multipart/form-data body: a form field (no filename) or an uploaded file.
struct Upload {
  std::string name;          // the field's name
  std::string filename;      // as the client sent it: shown at most, never a path
  std::string content_type;
  std::string content;
};

struct Request {
  std::string method;  // "GET", "POST", ...
  std::string path;    // decoded, without the query: "/api/jobs/3"
  std::map<std::string, std::string> query;
  std::map<std::string, std::string> headers;  // names in lower case
  std::string body;           // empty for multipart/form-data: see files
  std::vector<Upload> files;  // multipart/form-data parts, by field name
};

struct Response {
  int status = 200;
  std::string content_type = "application/json";
  std::string body;
  std::vector<std::pair<std::string, std::string>> headers;
  // A streamed answer (Server-Sent Events) instead of `body`: called again and again on the
  // connection's thread, it appends the next piece to `out` ("" when nothing came within
  // its wait of at most a second) and returns false when the stream ends. It is destroyed
  // when the client goes away.
  std::function<bool(std::string& out)> stream;
};

struct ApiOptions {
  std::string data_dir;  // created if missing
  std::string token;     // "" = none required
  int workers = 0;       // generation threads; 0 = min(4, cores)
  // False: generation requests are checked but not run (the fuzz target's bound on work).
  bool run_jobs = true;
};

class Api {
 public:
  // Opens (creates) the data directory and its database; throws InputError when it cannot.
  explicit Api(const ApiOptions& options);
  ~Api();
  Api(const Api&) = delete;
  Api& operator=(const Api&) = delete;

  Response handle(const Request& request);

 private:
  struct State;
  std::unique_ptr<State> s_;
};

// "$XDG_DATA_HOME/strand", else "$HOME/.local/share/strand", else "strand-data".
std::string default_data_dir();
// 127.0.0.0/8, ::1 and localhost.
bool is_loopback_host(const std::string& host);

}  // namespace strand::serve
