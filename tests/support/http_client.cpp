// One request per connection over a blocking socket (see http_client.h).
#include "tests/support/http_client.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <regex>
#include <sstream>

#include "tests/support/cli_runner.h"

namespace strand::testing {

int connect_to(int port, int timeout_s) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  timeval tv{timeout_s, 0};
  ::setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
  ::setsockopt(fd, SOL_SOCKET, SO_SNDTIMEO, &tv, sizeof tv);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(static_cast<uint16_t>(port));
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) {
    ::close(fd);
    return -1;
  }
  return fd;
}

HttpReply http_request(int port, const std::string& method, const std::string& target,
                       const std::string& body, const std::string& content_type,
                       const std::string& headers) {
  const int fd = connect_to(port, 30);
  HttpReply r;
  if (fd < 0) return r;
  // `headers` starting with its own Host line replaces the default one (Host checks).
  const std::string host = headers.rfind("Host:", 0) == 0 ? "" : "Host: 127.0.0.1:" + std::to_string(port) + "\r\n";
  const std::string req =
      method + " " + target + " HTTP/1.1\r\n" + host +
      "Connection: close\r\nContent-Type: " + content_type +
      "\r\nContent-Length: " + std::to_string(body.size()) + "\r\n" + headers + "\r\n" + body;
  std::size_t sent = 0;
  while (sent < req.size()) {
    const ssize_t n = ::send(fd, req.data() + sent, req.size() - sent, MSG_NOSIGNAL);
    if (n <= 0) break;  // the server may answer (413) before reading it all
    sent += static_cast<std::size_t>(n);
  }
  std::string all;
  char buf[65536];
  for (int i = 0; i < 100000; ++i) {
    const ssize_t n = ::recv(fd, buf, sizeof buf, 0);
    if (n <= 0) break;
    all.append(buf, static_cast<std::size_t>(n));
  }
  ::close(fd);
  const auto end = all.find("\r\n\r\n");
  if (end == std::string::npos) return r;
  r.head = all.substr(0, end);
  r.body = all.substr(end + 4);
  if (r.head.size() > 12) r.status = std::stoi(r.head.substr(9, 3));
  return r;
}

std::pair<std::string, std::string> multipart_body(const std::vector<FormPart>& parts) {
  const std::string boundary = "strand-test-boundary-7d1f";
  std::string body;
  for (const FormPart& p : parts) {
    body += "--" + boundary + "\r\nContent-Disposition: form-data; name=\"" + p.name + "\"";
    if (!p.filename.empty())
      body += "; filename=\"" + p.filename + "\"\r\nContent-Type: application/octet-stream";
    body += "\r\n\r\n" + p.content + "\r\n";
  }
  return {body + "--" + boundary + "--\r\n", "multipart/form-data; boundary=" + boundary};
}

std::vector<DocCommand> run_doc_curl_lines(const std::string& heading, int port,
                                           const std::string& dir) {
  const std::string page = slurp(std::string(STRAND_SOURCE_DIR) + "/docs/workbench.md");
  const auto start = page.find("\n" + heading + "\n");
  if (start == std::string::npos) return {};
  std::istringstream section(page.substr(start, page.find("\n## ", start + 1) - start));
  std::vector<DocCommand> ran;
  bool in_sh = false;
  for (std::string line; std::getline(section, line);) {
    if (line.rfind("```", 0) == 0) {
      in_sh = !in_sh && line == "```sh";
      continue;
    }
    if (!in_sh || line.rfind("curl ", 0) != 0) continue;
    const std::string local = std::regex_replace(line, std::regex("127\\.0\\.0\\.1:8080"),
                                                 "127.0.0.1:" + std::to_string(port));
    const CliResult r = run_in_shell("timeout 60 " + local, dir);
    ran.push_back({line, r.exit_code, r.out + r.err});
  }
  return ran;
}

}  // namespace strand::testing
