// "Did you mean": the known command or flag nearest to a mistyped one.
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

namespace strand::cli {

// Edit distance with transpositions ("nozle" -> "nozzle" is 1, "sacffold" -> "scaffold" 1).
int edit_distance(const std::string& a, const std::string& b);

// The names within a typo's reach of `word` (at most a third of its length, at least 1, at
// most 3 edits), nearest first, ties in the order given.
std::vector<std::string> nearest_names(const std::string& word,
                                       const std::vector<std::string>& names);

// The one-line error for a command line CLI11 refused, when the refusal comes from an
// unknown command or flag: "unknown command 'scafold' (did you mean 'scaffold'?)",
// "scaffold: unknown flag --nozle (did you mean --nozzle?)". Empty when every word is known
// (the caller then shows CLI11's own message). `args` excludes the program name.
std::optional<std::string> explain_unknown_words(const CLI::App& app,
                                                 const std::vector<std::string>& args);

}  // namespace strand::cli
