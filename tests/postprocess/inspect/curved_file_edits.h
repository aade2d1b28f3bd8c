// Test helpers for tampering with curved-substrate files (pose CSVs, rotary G-code): a
// sample job's main file as produce_curved writes it, lines by index, and "which finding names
// this row". Shared by pose_check_test and rotary_check_test.
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "machines/profile.h"
#include "patterns/registry.h"
#include "postprocess/inspect/pose_check.h"
#include "postprocess/plan/produce_curved.h"
#include "tests/support/cli_runner.h"
#include "tests/support/sample_jobs.h"

namespace strand::post::curved_edits {

inline std::string produced_main(const std::string& sample, const std::string& out) {
  const auto j = nlohmann::json::parse(testing::slurp(testing::samples_dir() + "/" + sample));
  const auto* g = patterns::find_generator(j.at("generator"));
  const auto t = g->generate(slicer::resolve_params(g->table(), j.at("params")));
  return produce_curved(t, *slicer::substrate_from(j.at("substrate")),
                        machines::load_profile(j.at("machine")), 0.01, out)
      .files.front()
      .second;
}

inline std::size_t line_start(const std::string& text, std::size_t line) {  // 0-based line
  std::size_t at = 0;
  for (std::size_t k = 0; k < line; ++k) at = text.find('\n', at) + 1;
  return at;
}

inline std::string line_at(const std::string& text, std::size_t line) {
  const std::size_t at = line_start(text, line);
  return text.substr(at, text.find('\n', at) + 1 - at);
}

inline std::string without_line(std::string text, std::size_t line) {
  const std::size_t at = line_start(text, line);
  return text.erase(at, text.find('\n', at) + 1 - at);
}

inline bool names_row(const PoseFindings& f, std::size_t row) {
  for (const auto& x : f.listed)
    if (x.row == row) return true;
  return false;
}

}  // namespace strand::post::curved_edits
