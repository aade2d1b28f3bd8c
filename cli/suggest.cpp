#include "cli/suggest.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>

namespace strand::cli {

int edit_distance(const std::string& a, const std::string& b) {
  const std::size_t n = a.size(), m = b.size();
  std::vector<std::vector<int>> d(n + 1, std::vector<int>(m + 1));
  for (std::size_t i = 0; i <= n; ++i) d[i][0] = static_cast<int>(i);
  for (std::size_t j = 0; j <= m; ++j) d[0][j] = static_cast<int>(j);
  for (std::size_t i = 1; i <= n; ++i) {
    for (std::size_t j = 1; j <= m; ++j) {
      const int cost = std::tolower(static_cast<unsigned char>(a[i - 1])) ==
                               std::tolower(static_cast<unsigned char>(b[j - 1]))
                           ? 0
                           : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) {
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
      }
    }
  }
  return d[n][m];
}

std::vector<std::string> nearest_names(const std::string& word,
                                       const std::vector<std::string>& names) {
  // Words longer than any name are not typos of one; this also bounds the table above.
  if (word.empty() || word.size() > 64) return {};
  const int reach = std::clamp(static_cast<int>(word.size()) / 3, 1, 3);
  std::vector<std::pair<int, std::string>> near;
  for (const auto& name : names) {
    const int d = edit_distance(word, name);
    if (d <= reach) near.emplace_back(d, name);
  }
  std::stable_sort(near.begin(), near.end(),
                   [](const auto& x, const auto& y) { return x.first < y.first; });
  std::vector<std::string> out;
  for (const auto& [d, name] : near) out.push_back(name);
  return out;
}

namespace {

bool is_number(const std::string& s) {
  char* end = nullptr;
  std::strtod(s.c_str(), &end);
  return end != s.c_str() && *end == '\0';
}

std::string did_you_mean(const std::vector<std::string>& near, const std::string& quote) {
  if (near.empty()) return "";
  return " (did you mean " + quote + near.front() + quote + "?)";
}

std::vector<std::string> command_names(const CLI::App& app) {
  std::vector<std::string> names;
  for (const auto* sub : app.get_subcommands([](const CLI::App*) { return true; })) {
    names.push_back(sub->get_name());
  }
  return names;
}

std::vector<std::string> flag_names(const CLI::App& app) {
  std::vector<std::string> names;
  for (const auto* option : app.get_options()) {
    for (const auto& l : option->get_lnames()) names.push_back("--" + l);
    for (const auto& s : option->get_snames()) names.push_back("-" + s);
  }
  return names;
}

}  // namespace

std::optional<std::string> explain_unknown_words(const CLI::App& app,
                                                 const std::vector<std::string>& args) {
  std::size_t i = 0;
  while (i < args.size() && !args[i].empty() && args[i][0] == '-') ++i;  // --help, --version
  if (i == args.size()) return std::nullopt;
  const CLI::App* command = &app;
  std::string path;
  // The command words: each must name a sub-command of the one before, while there are any.
  while (i < args.size()) {
    const auto names = command_names(*command);
    if (names.empty()) break;
    const auto& word = args[i];
    if (std::find(names.begin(), names.end(), word) == names.end()) {
      if (command != &app) break;  // a positional argument of a command with sub-commands
      std::string all;
      for (const auto& n : names) all += (all.empty() ? "" : ", ") + n;
      const auto near = nearest_names(word, names);
      return "unknown command '" + word + "'" +
             (near.empty() ? " (commands: " + all + ")" : did_you_mean(near, "'"));
    }
    command = command->get_subcommand(word);
    path += (path.empty() ? "" : " ") + word;
    ++i;
  }
  const auto flags = flag_names(*command);
  for (; i < args.size(); ++i) {
    const auto& word = args[i];
    if (word.size() < 2 || word[0] != '-' || is_number(word) || word == "--") continue;
    const std::string name = word.substr(0, word.find('='));
    if (std::find(flags.begin(), flags.end(), name) != flags.end()) continue;
    const auto near = nearest_names(name, flags);
    return path + ": unknown flag " + name + did_you_mean(near, "");
  }
  return std::nullopt;
}

}  // namespace strand::cli
