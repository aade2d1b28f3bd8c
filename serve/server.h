// `strand serve`: the workbench's HTTP server (cpp-httplib) around serve::Api.
#pragma once

#include <memory>
#include <ostream>
#include <string>

#include "serve/api.h"

namespace strand::serve {

struct ServeOptions {
  std::string host = "127.0.0.1";
  int port = 8080;        // 0: any free port (printed)
  std::string data_dir;   // "": default_data_dir()
  std::string token;      // required for a host other than loopback
  int http_threads = 8;   // connections served at once
};

// Throws InputError for options that must not run: a non-loopback host without a token,
// a port out of range, a token with characters a header or cookie cannot carry.
void check_options(const ServeOptions& options);

class Server {
 public:
  explicit Server(const ServeOptions& options);  // opens the data directory
  ~Server();                                    // stops
  Server(const Server&) = delete;
  Server& operator=(const Server&) = delete;

  // Binds and serves on a background thread; returns the port. Throws InputError when the
  // address cannot be bound.
  int start();
  void stop();
  // Blocks until stop() (or the process ends).
  void wait();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The command: check, start, print "strand serve: http://HOST:PORT/ (data in DIR)" on `out`,
// serve until the process is stopped. Returns the exit code.
int run_serve(const ServeOptions& options, std::ostream& out);

}  // namespace strand::serve
