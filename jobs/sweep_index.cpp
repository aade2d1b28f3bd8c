// Contact sheet HTML for a sweep manifest.
#include "jobs/sweep_index.h"

#include <cmath>

#include "slicer/params.h"

namespace strand::jobs {

namespace {

std::string esc(const std::string& s) {
  std::string o;
  for (char c : s) {
    switch (c) {
      case '&': o += "&amp;"; break;
      case '<': o += "&lt;"; break;
      case '>': o += "&gt;"; break;
      case '"': o += "&quot;"; break;
      default: o += c;
    }
  }
  return o;
}

std::string text(const nlohmann::json& v) {
  if (v.is_null()) return "";
  if (v.is_string()) return v.get<std::string>();
  if (v.is_number()) return slicer::short_number(v.get<double>());
  if (v.is_array()) {
    std::string s;
    for (const auto& e : v) s += (s.empty() ? "" : "x") + text(e);
    return s;
  }
  return v.dump();
}

double sort_number(const nlohmann::json& v) {
  if (v.is_number()) return v.get<double>();
  if (v.is_array() && !v.empty() && v[0].is_number()) return v[0].get<double>();
  return 0.0;
}

const char* kHead = R"(<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>Strand sweep</title>
<style>
body{font:14px sans-serif;margin:16px;background:#f4f4f4;color:#222}
#sheet{display:flex;flex-wrap:wrap;gap:12px}
.card{background:#fff;border:1px solid #ccc;border-radius:6px;padding:8px;width:250px}
.card.failed{border-color:#c00;background:#fee}.card.dropped{opacity:.55}
.card img{width:240px;height:200px;object-fit:contain;background:#fff;display:block}
.card h3{font-size:12px;margin:4px 0;word-break:break-all}
.card table{font-size:12px;border-collapse:collapse}.card td{padding:0 6px 0 0}
.bad{color:#c00;font-weight:bold}.ok{color:#080}
</style></head><body>
)";

const char* kScript = R"(<script>
function sortCards(){
  const key=document.getElementById('key').value, dir=document.getElementById('dir').value==='desc'?-1:1;
  const sheet=document.getElementById('sheet');
  const cards=[...sheet.children];
  cards.sort((a,b)=>{const x=parseFloat(a.dataset[key]),y=parseFloat(b.dataset[key]);
    return (x===y?(+a.dataset.index)-(+b.dataset.index):(x<y?-1:1))*dir;});
  cards.forEach(c=>sheet.appendChild(c));
}
document.getElementById('key').onchange=sortCards;document.getElementById('dir').onchange=sortCards;
window.addEventListener('load',()=>{const imgs=[...document.querySelectorAll('#sheet img')];
  document.getElementById('status').textContent='cards: '+document.getElementById('sheet').children.length+
    ', thumbnails shown: '+imgs.filter(i=>i.complete&&i.naturalWidth>0).length;});
</script></body></html>
)";

// data-* attribute names must be lower case without dashes.
std::string data_key(const std::string& key) {
  std::string k;
  for (char c : key) k += std::isalnum(static_cast<unsigned char>(c)) ? static_cast<char>(std::tolower(c)) : 'x';
  return "p" + k;
}

std::string card(const nlohmann::json& r, const nlohmann::json& keys) {
  const std::string status = r.at("status").get<std::string>();
  std::string data = " data-index=\"" + text(r.at("index")) + "\"";
  std::string rows;
  for (const auto& k : keys) {
    const auto v = r.at("parameters").value(k.get<std::string>(), nlohmann::json());
    data += " data-" + data_key(k.get<std::string>()) + "=\"" + slicer::short_number(sort_number(v)) + "\"";
    rows += "<tr><td>" + esc(k.get<std::string>()) + "</td><td>" + esc(text(v)) + "</td></tr>";
  }
  if (r.contains("derived") && r.at("derived").contains("footprint_mm")) {
    nlohmann::json rounded = nlohmann::json::array();
    for (const auto& v : r.at("derived").at("footprint_mm")) rounded.push_back(std::round(v.get<double>() * 1000) / 1000);
    rows += "<tr><td>footprint</td><td>" + esc(text(rounded)) + " mm</td></tr>";
  }
  for (const char* f : {"porosity", "ink_volume_ml", "time_s", "layers"}) {
    const auto v = r.value(f, nlohmann::json());
    data += std::string(" data-") + data_key(f) + "=\"" + (v.is_number() ? slicer::short_number(v.get<double>()) : "NaN") + "\"";
    if (v.is_null()) continue;
    const std::string shown = std::string(f) == "porosity" ? slicer::short_number(std::round(v.get<double>() * 1000) / 10) + " %" : text(v);
    rows += "<tr><td>" + std::string(f) + "</td><td>" + shown + "</td></tr>";
  }
  std::string body;
  if (status == "ok") {
    const bool ok = r.at("check").at("ok").get<bool>();
    const std::string preview = r.value("preview", nlohmann::json()).is_string() ? r.at("preview").get<std::string>() : "";
    if (!preview.empty()) body += "<a href=\"" + esc(preview) + "\"><img src=\"" + esc(preview) + "\" alt=\"preview\"></a>";
    rows += std::string("<tr><td>check</td><td class=\"") + (ok ? "ok\">ok" : "bad\">problems") + "</td></tr>";
    body += "<table>" + rows + "</table><a href=\"" + esc(r.at("output").get<std::string>()) + "\">G-code</a>";
    const auto page = r.value("preview_html", nlohmann::json());
    if (page.is_string()) body += " &middot; <a href=\"" + esc(page.get<std::string>()) + "\">interactive view</a>";
  } else {
    const std::string why = r.contains("error") ? r.at("error").get<std::string>() : r.value("reason", "");
    body += "<table>" + rows + "</table><p class=\"bad\">" + esc(status + ": " + why) + "</p>";
  }
  return "<div class=\"card " + status + "\"" + data + "><h3>" + esc(r.at("name").get<std::string>()) +
         "</h3>" + body + "</div>\n";
}

}  // namespace

std::string sweep_index_html(const nlohmann::json& m) {
  const auto& s = m.at("sweep");
  const auto& keys = s.at("vary");
  std::size_t ok = 0, failed = 0, dropped = 0;
  for (const auto& r : m.at("points")) {
    const auto st = r.at("status").get<std::string>();
    ok += st == "ok";
    failed += st == "failed";
    dropped += st == "dropped";
  }
  std::string h = kHead;
  h += "<h1>Sweep: " + esc(s.at("generator").get<std::string>()) + " on " + esc(s.at("machine").get<std::string>()) + "</h1>\n";
  if (s.contains("description")) h += "<p>" + esc(s.at("description").get<std::string>()) + "</p>\n";
  h += "<p>" + std::to_string(ok) + " ok, " + std::to_string(failed) + " failed, " + std::to_string(dropped) +
       " dropped; <a href=\"manifest.csv\">manifest.csv</a>, <a href=\"manifest.json\">manifest.json</a>"
       " <span id=\"status\"></span></p>\n";
  h += "<p>Sort by <select id=\"key\"><option value=\"index\">point</option>";
  for (const auto& k : keys) h += "<option value=\"" + data_key(k.get<std::string>()) + "\">" + esc(k.get<std::string>()) + "</option>";
  for (const char* f : {"porosity", "ink_volume_ml", "time_s", "layers"}) h += "<option value=\"" + data_key(f) + "\">" + f + "</option>";
  h += "</select> <select id=\"dir\"><option value=\"asc\">ascending</option><option value=\"desc\">descending</option></select></p>\n";
  h += "<div id=\"sheet\">\n";
  for (const auto& r : m.at("points")) h += card(r, keys);
  h += "</div>\n";
  return h + kScript;
}

}  // namespace strand::jobs
