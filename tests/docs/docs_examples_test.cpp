// Runs the shell examples of README.md and docs/*.md that are marked runnable, and checks
// that the relative links of those pages point to existing files (and headings, for links
// with an #anchor into a page). One test of each kind per page, named after the page.
//
// The marker: a fenced block whose info string is `console` (the fence at the start of a
// line, not indented). Inside it
//   - a line starting with "$ " is a command; a command line ending in "\" continues on the
//     next line (the shell joins them, as in a terminal);
//   - the lines after a command, up to the next "$ " line or the closing fence, are its
//     expected output, matched line by line and exactly; a line "..." stands for zero or more
//     lines;
//   - the command must exit 0, unless its last line ends in "# exit N" (a shell comment, so
//     the line still runs when pasted): then it must exit N, and its stderr is matched after
//     its stdout, since errors are printed there ("strand: error: ..."). The stderr of a
//     command that exits 0 is ignored (sweep progress, for one).
// Fences with any other info string (```sh, ```json, plain ```) are illustrations, not run.
// Mark only examples whose output is deterministic and fast (well under 2 s each).
//
// Where commands run: every page gets a fresh temporary directory, and its commands run there
// one after another in document order through /bin/sh, so a later command may read a file an
// earlier one wrote. `strand` is the built binary: PATH starts with its directory. The
// directory holds `samples`, a symbolic link to the repository's samples/, so paths such as
// `samples/sweeps/scaffold-nozzle-gap.json` work as they do in a checkout.
//
// The pages are listed when the test binary starts (README.md and docs/*.md of the source
// tree), so a new page is covered once this test is rebuilt; edits to existing pages are read
// on every run.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support/cli_runner.h"

namespace strand::testing {
namespace {

namespace fs = std::filesystem;

constexpr char kSourceDir[] = STRAND_SOURCE_DIR;

// One runnable command of a page and what it must print.
struct Example {
  int line = 0;  // 1-based line of the "$ " line in the page
  std::string command;
  int exit_code = 0;
  std::vector<std::string> expected;
};

// What a page holds: its runnable examples, and problems with the marker itself.
struct Page {
  std::vector<Example> examples;
  std::vector<std::string> problems;
};

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

bool is_fence(const std::string& line) { return line.rfind("```", 0) == 0; }

std::string trimmed(const std::string& s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t") - b + 1);
}

// The expected exit code from a trailing "# exit N" comment, else 0.
int expected_exit(const std::string& command) {
  const std::regex exit_comment(R"(#\s*exit\s+(\d+)\s*$)");
  std::smatch m;
  return std::regex_search(command, m, exit_comment) ? std::stoi(m[1]) : 0;
}

Page parse_page(const std::vector<std::string>& lines) {
  Page page;
  enum class In { Text, Console, OtherFence } in = In::Text;
  bool block_has_command = false;
  for (size_t i = 0; i < lines.size(); ++i) {
    const std::string& line = lines[i];
    if (in == In::Text) {
      if (is_fence(line)) in = trimmed(line.substr(3)) == "console" ? In::Console : In::OtherFence;
      block_has_command = false;
    } else if (is_fence(line)) {
      in = In::Text;
    } else if (in == In::OtherFence) {
      continue;
    } else if (line.rfind("$ ", 0) == 0) {
      Example ex{static_cast<int>(i) + 1, line.substr(2)};
      while (!ex.command.empty() && ex.command.back() == '\\' && i + 1 < lines.size()) {
        ex.command += "\n" + lines[++i];
      }
      ex.exit_code = expected_exit(ex.command);
      page.examples.push_back(ex);
      block_has_command = true;
    } else if (!block_has_command) {
      page.problems.push_back("line " + std::to_string(i + 1) +
                              ": output before any \"$ \" command in a console block");
    } else {
      page.examples.back().expected.push_back(line);
    }
  }
  if (in == In::Console) page.problems.push_back("a console block is not closed");
  return page;
}

// Does `actual` match `expected`, where an expected line "..." matches any run of lines?
bool lines_match(const std::vector<std::string>& expected, size_t e,
                 const std::vector<std::string>& actual, size_t a) {
  if (e == expected.size()) return a == actual.size();
  if (expected[e] == "...") {
    for (size_t skip = a; skip <= actual.size(); ++skip) {
      if (lines_match(expected, e + 1, actual, skip)) return true;
    }
    return false;
  }
  return a < actual.size() && expected[e] == actual[a] &&
         lines_match(expected, e + 1, actual, a + 1);
}

std::string joined(const std::vector<std::string>& lines) {
  std::string s;
  for (const auto& l : lines) s += "    " + l + "\n";
  return s;
}

// Runs `command` with /bin/sh in `work`, with the built strand first on PATH. Captures go
// next to `work`, not into it, so a command listing its directory sees only its own files.
CliResult run_shell(const std::string& command, const fs::path& work) {
  const fs::path base = work.parent_path();
  { std::ofstream(base / "command.sh") << command << "\n"; }
  const std::string bin_dir = fs::path(STRAND_CLI).parent_path().string();
  const std::string cmd = "cd '" + work.string() + "' && PATH='" + bin_dir + "':\"$PATH\" " +
                          "/bin/sh '" + (base / "command.sh").string() + "' >'" +
                          (base / "stdout").string() + "' 2>'" + (base / "stderr").string() + "'";
  const int status = std::system(cmd.c_str());
  CliResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp((base / "stdout").string());
  r.err = slurp((base / "stderr").string());
  return r;
}

// README.md and docs/*.md, relative to the source dir, sorted.
std::vector<std::string> doc_pages() {
  std::vector<std::string> pages{"README.md"};
  const fs::path docs = fs::path(kSourceDir) / "docs";
  if (!fs::is_directory(docs)) return pages;
  for (const auto& entry : fs::directory_iterator(docs)) {
    if (entry.path().extension() == ".md") {
      pages.push_back(fs::relative(entry.path(), kSourceDir).generic_string());
    }
  }
  std::sort(pages.begin() + 1, pages.end());
  return pages;
}

std::string page_test_name(const ::testing::TestParamInfo<std::string>& info) {
  std::string name = info.param;
  for (char& c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  }
  return name;
}

class DocsPage : public ::testing::TestWithParam<std::string> {
 protected:
  std::vector<std::string> page_lines() const {
    const fs::path path = fs::path(kSourceDir) / GetParam();
    EXPECT_TRUE(fs::exists(path)) << path;
    return lines_of(slurp(path.string()));
  }
};

TEST_P(DocsPage, ConsoleExamplesPrintWhatThePageShows) {
  const Page page = parse_page(page_lines());
  for (const auto& p : page.problems) ADD_FAILURE() << GetParam() << ": " << p;

  const fs::path base = fresh_dir("docs"), work = base / "work";
  fs::create_directories(work);
  fs::create_directory_symlink(fs::path(kSourceDir) / "samples", work / "samples");
  for (const Example& ex : page.examples) {
    SCOPED_TRACE(GetParam() + ":" + std::to_string(ex.line) + ": $ " + ex.command);
    const CliResult r = run_shell(ex.command, work);
    EXPECT_EQ(r.exit_code, ex.exit_code) << "stderr:\n" << r.err;
    const std::string shown = ex.exit_code == 0 ? r.out : r.out + r.err;
    const std::vector<std::string> actual = lines_of(shown);
    EXPECT_TRUE(lines_match(ex.expected, 0, actual, 0))
        << "the page shows:\n"
        << joined(ex.expected) << "the command printed:\n"
        << joined(actual);
  }
  RecordProperty("runnable_examples", static_cast<int>(page.examples.size()));
  fs::remove_all(base);
}

// GitHub's anchor for a heading: lower case, spaces to "-", ASCII punctuation other than "-"
// and "_" dropped ("Preview copy: `--viewer-e`" -> "preview-copy---viewer-e").
std::string anchor_of(const std::string& heading) {
  std::string anchor;
  for (const char c : heading) {
    const auto u = static_cast<unsigned char>(c);
    if (c == ' ') {
      anchor += '-';
    } else if (u >= 0x80 || std::isalnum(u) || c == '-' || c == '_') {
      anchor += static_cast<char>(std::tolower(u));
    }
  }
  return anchor;
}

// The anchors of a page's headings (lines starting with "#" outside code blocks).
std::vector<std::string> anchors_of(const std::vector<std::string>& lines) {
  std::vector<std::string> anchors;
  bool in_code = false;
  for (const std::string& line : lines) {
    if (is_fence(line)) in_code = !in_code;
    if (in_code || line.empty() || line[0] != '#') continue;
    anchors.push_back(anchor_of(trimmed(line.substr(line.find_first_not_of('#')))));
  }
  return anchors;
}

// Relative links [text](file#anchor) outside code blocks must name an existing file and, if
// they have an anchor into a Markdown page, one of its headings.
TEST_P(DocsPage, RelativeLinksPointToExistingFilesAndHeadings) {
  const std::regex link(R"(\]\(([^)\s]+)(\s+"[^"]*")?\))");
  const fs::path page = fs::path(kSourceDir) / GetParam();
  const std::vector<std::string> lines = page_lines();
  bool in_code = false;
  for (size_t i = 0; i < lines.size(); ++i) {
    if (is_fence(lines[i])) in_code = !in_code;
    if (in_code) continue;
    for (std::sregex_iterator it(lines[i].begin(), lines[i].end(), link), end; it != end; ++it) {
      const std::string target = (*it)[1];
      if (target.find("://") != std::string::npos || target.rfind("mailto:", 0) == 0) continue;
      const std::string where = GetParam() + ":" + std::to_string(i + 1) + ": link " + target;
      const auto hash = target.find('#');
      const fs::path file = hash == 0 ? page : page.parent_path() / target.substr(0, hash);
      if (!fs::exists(file)) {
        ADD_FAILURE() << where << ": no such file";
      } else if (hash != std::string::npos && file.extension() == ".md") {
        const auto anchors = anchors_of(lines_of(slurp(file.string())));
        const bool found =
            std::find(anchors.begin(), anchors.end(), target.substr(hash + 1)) != anchors.end();
        EXPECT_TRUE(found) << where << ": no such heading in " << file.filename();
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(docs_examples, DocsPage, ::testing::ValuesIn(doc_pages()), page_test_name);

}  // namespace
}  // namespace strand::testing
