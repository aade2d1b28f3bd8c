// The self-contained 3D viewer page.
#include "postprocess/preview/viewer_html.h"

#include <string_view>

namespace strand::post {

namespace {

// RFC 4648 base64 (none of the preview room's libraries exports an encoder).
std::string base64(std::string_view in) {
  static constexpr char kDigits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((in.size() + 2) / 3 * 4 + in.size() / 57);
  for (std::size_t i = 0; i < in.size(); i += 3) {
    unsigned v = static_cast<unsigned char>(in[i]) << 16;
    if (i + 1 < in.size()) v |= static_cast<unsigned char>(in[i + 1]) << 8;
    if (i + 2 < in.size()) v |= static_cast<unsigned char>(in[i + 2]);
    out += kDigits[(v >> 18) & 63];
    out += kDigits[(v >> 12) & 63];
    out += i + 1 < in.size() ? kDigits[(v >> 6) & 63] : '=';
    out += i + 2 < in.size() ? kDigits[v & 63] : '=';
    if (i % 57 == 54) out += '\n';  // 76-character lines
  }
  return out;
}

std::string escape_html(const std::string& s) {
  std::string out;
  for (const char c : s) {
    if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else if (c == '&') out += "&amp;";
    else if (c == '"') out += "&quot;";
    else out += c;
  }
  return out;
}

// JSON inside <script>: "</" could end it, so every '<' is written as \u003c.
std::string script_json(const nlohmann::json& j) {
  const std::string text = j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  std::string out;
  out.reserve(text.size());
  for (const char c : text) c == '<' ? out += "\\u003c" : out += c;
  return out;
}

}  // namespace

std::string render_viewer_html(const ViewerData& data, const std::string& title) {
  std::string page =
      "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n"
      "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
      "<title>" + escape_html(title) + " - Strand viewer</title>\n"
      "<style>body{font:14px/1.4 system-ui,sans-serif;margin:0;padding:8px;color:#222;background:#fafafa}"
      "h1{font-size:16px;margin:0 0 8px}#viewer{height:calc(100vh - 56px)}</style>\n"
      "</head><body>\n<h1>" + escape_html(title) + "</h1>\n<div id=\"viewer\"></div>\n"
      "<script id=\"strand-view-index\" type=\"application/json\">" + script_json(viewer_index(data)) +
      "</script>\n<script id=\"strand-view-blocks\" type=\"text/plain\">\n";
  page += base64(data.blocks);
  page += "</script>\n<script>\n";
  page += viewer_script();
  page += "\n</script>\n</body></html>\n";
  return page;
}

}  // namespace strand::post
