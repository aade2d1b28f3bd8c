// A minimal HTTP/1.1 client for tests of `strand serve`: one request per connection to
// 127.0.0.1, read to the end; multipart/form-data bodies for uploads.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace strand::testing {

struct HttpReply {
  int status = 0;  // 0: no answer
  std::string head, body;
  nlohmann::json j() const { return nlohmann::json::parse(body, nullptr, false); }
};

// A socket connected to 127.0.0.1:port with `timeout_s` on reads and writes, or -1.
int connect_to(int port, int timeout_s);

// `headers` are extra lines ("Name: value\r\n" each; a first "Host:" line replaces the default
// 127.0.0.1:port); 30 s at most per read or write.
HttpReply http_request(int port, const std::string& method, const std::string& target,
                       const std::string& body = "",
                       const std::string& content_type = "application/json",
                       const std::string& headers = "");

struct FormPart {
  std::string name, content, filename;  // no filename: a plain field
};
// The body and its Content-Type ("multipart/form-data; boundary=...").
std::pair<std::string, std::string> multipart_body(const std::vector<FormPart>& parts);

struct DocCommand {
  std::string line;  // as written in the docs
  int exit_code = -1;
  std::string output;  // stdout and stderr
};
// Runs, in order and in `dir`, each `curl ` line of the ```sh blocks in the section of
// docs/workbench.md headed `heading` ("## Draw", up to the next "## "), aimed at 127.0.0.1:port
// instead of the documented 127.0.0.1:8080; each within 60 s.
std::vector<DocCommand> run_doc_curl_lines(const std::string& heading, int port,
                                           const std::string& dir);

}  // namespace strand::testing
