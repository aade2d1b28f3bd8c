// cpp-httplib glue: every method and path goes to serve::Api; bounded bodies, URIs and
// connection threads; errors of the library itself answered as JSON too.
#include "serve/server.h"

#include <httplib.h>

#include <algorithm>
#include <cctype>
#include <thread>

#include "slicer/input_error.h"

namespace strand::serve {

namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

}  // namespace

void check_options(const ServeOptions& o) {
  if (o.port < 0 || o.port > 65535) throw InputError("--port = " + std::to_string(o.port) + ": must be in [0, 65535]");
  if (!is_loopback_host(o.host) && o.token.empty()) {
    throw InputError("--host = " + o.host + ": other machines could reach the workbench; give --token T as well "
                     "(or keep the default 127.0.0.1)");
  }
  if (o.token.size() > 200 ||
      std::any_of(o.token.begin(), o.token.end(), [](char c) { return !std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_' && c != '.'; })) {
    throw InputError("--token: letters, digits, '-', '_' and '.' only, at most 200");
  }
}

struct Server::Impl {
  ServeOptions options;
  Api api;
  httplib::Server http;
  std::thread thread;
  explicit Impl(const ServeOptions& o)
      : options(o), api(ApiOptions{o.data_dir.empty() ? default_data_dir() : o.data_dir, o.token}) {}
};

namespace {
const ServeOptions& checked(const ServeOptions& o) {
  check_options(o);
  return o;
}
}  // namespace

Server::Server(const ServeOptions& options) : impl_(std::make_unique<Impl>(checked(options))) {
  httplib::Server& h = impl_->http;
  const int threads = std::max(impl_->options.http_threads, 1);
  h.new_task_queue = [threads] { return new httplib::ThreadPool(static_cast<std::size_t>(threads)); };
  // Uploads to POST /api/plot and /api/slice may be larger; Api::handle holds other bodies to
  // kMaxBodyBytes.
  h.set_payload_max_length(kMaxUploadBytes);
  h.set_read_timeout(10, 0);
  h.set_write_timeout(10, 0);
  h.set_keep_alive_max_count(20);
  Api* api = &impl_->api;
  const auto handler = [api](const httplib::Request& req, httplib::Response& res) {
    Request r;
    r.method = req.method;
    r.path = req.path;
    for (const auto& [k, v] : req.params) r.query.emplace(k, v);
    for (const auto& [k, v] : req.headers) r.headers.emplace(lower(k), v);
    r.body = req.body;
    for (const auto& [name, part] : req.files) r.files.push_back({name, part.filename, part.content_type, part.content});
    const Response out = api->handle(r);
    res.status = out.status;
    for (const auto& [k, v] : out.headers) res.set_header(k, v);
    if (out.stream) {  // Server-Sent Events: chunks as the stream yields them, until it ends
      res.set_chunked_content_provider(out.content_type, [next = out.stream](std::size_t, httplib::DataSink& sink) {
        std::string chunk;
        if (!next(chunk)) {
          sink.done();
          return true;
        }
        return chunk.empty() || sink.write(chunk.data(), chunk.size());
      });
      return;
    }
    res.set_content(out.body, out.content_type);
  };
  const char* any = ".*";
  h.Get(any, handler);
  h.Post(any, handler);
  h.Delete(any, handler);
  h.Put(any, handler);
  h.Patch(any, handler);
  h.Options(any, handler);
  // The library's own refusals (malformed request line, body or URI too large) as JSON.
  h.set_error_handler([](const httplib::Request& req, httplib::Response& res) {
    if (!res.body.empty()) return;
    const bool upload = req.path == "/api/plot" || req.path == "/api/slice";
    const std::size_t limit = upload ? kMaxUploadBytes : kMaxBodyBytes;
    const std::string why = res.status == 413   ? "request body larger than " + std::to_string(limit) + " bytes"
                            : res.status == 414 ? std::string("request URI too long")
                            : res.status == 404 ? std::string("not found")
                                                : "malformed request (HTTP " + std::to_string(res.status) + ")";
    res.set_content("{\"error\":\"" + why + "\"}\n", "application/json");
  });
  h.set_exception_handler([](const httplib::Request&, httplib::Response& res, std::exception_ptr) {
    res.status = 500;
    res.set_content("{\"error\":\"internal error\"}\n", "application/json");
  });
}

Server::~Server() { stop(); }

int Server::start() {
  httplib::Server& h = impl_->http;
  int port = impl_->options.port;
  if (port == 0) {
    port = h.bind_to_any_port(impl_->options.host);
  } else if (!h.bind_to_port(impl_->options.host, port)) {
    port = -1;
  }
  if (port <= 0) {
    throw InputError("--host " + impl_->options.host + " --port " + std::to_string(impl_->options.port) +
                     ": cannot listen there (in use, or not an address of this machine)");
  }
  impl_->thread = std::thread([&h] { h.listen_after_bind(); });
  return port;
}

void Server::stop() {
  impl_->http.stop();
  if (impl_->thread.joinable()) impl_->thread.join();
}

void Server::wait() {
  if (impl_->thread.joinable()) impl_->thread.join();
}

int run_serve(const ServeOptions& options, std::ostream& out) {
  check_options(options);
  ServeOptions o = options;
  if (o.data_dir.empty()) o.data_dir = default_data_dir();
  Server server(o);
  const int port = server.start();
  const std::string shown = o.host.find(':') != std::string::npos ? "[" + o.host + "]" : o.host;
  out << "strand serve: http://" << shown << ":" << port << "/" << (o.token.empty() ? "" : "?token=" + o.token)
      << " (data in " << o.data_dir << ")" << std::endl;
  server.wait();
  return 0;
}

}  // namespace strand::serve
