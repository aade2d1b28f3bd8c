// A `strand serve` on an ephemeral port with a fresh data directory, for the workbench's tests.
#pragma once

#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "serve/server.h"
#include "tests/support/cli_runner.h"

namespace strand::testing {

class ServeFixture : public ::testing::Test {
 protected:
  // Starts the server; its data directory is `dir_ + "/data"` under fresh_dir(name).
  void start_server(const std::string& name) {
    dir_ = fresh_dir(name);
    serve::ServeOptions o;
    o.port = 0;
    o.data_dir = dir_ + "/data";
    server_ = std::make_unique<serve::Server>(o);
    port_ = server_->start();
    ASSERT_GT(port_, 0);
  }
  // The server's address of `path` ("/sweep?job=1"), for a browser.
  std::string url(const std::string& path) const {
    return "http://127.0.0.1:" + std::to_string(port_) + path;
  }
  void TearDown() override {
    if (server_) server_->stop();
  }
  std::string dir_;
  std::unique_ptr<serve::Server> server_;
  int port_ = 0;
};

}  // namespace strand::testing
