// User JSON: bounded depth, library errors as one InputError, typed reads naming the key.
#include "slicer/json_input.h"

#include <gtest/gtest.h>

#include <functional>

#include "slicer/input_error.h"

namespace strand::slicer {
namespace {

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(JsonInput, DepthIsLimitedBeforeParsing) {
  const std::string ok = std::string(kMaxJsonDepth, '[') + std::string(kMaxJsonDepth, ']');
  EXPECT_TRUE(parse_json(ok, "x").is_array());
  const std::string deep = "[" + ok + "]";
  EXPECT_NE(error_of([&] { parse_json(deep, "x = f"); }).find("x = f: nested deeper than 64"),
            std::string::npos);
  EXPECT_TRUE(parse_json(R"(["[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[["])", "x")
                  .is_array())
      << "brackets inside strings do not count";
}

TEST(JsonInput, OverflowAndSyntaxErrorsAreInputErrors) {
  EXPECT_NE(error_of([] { parse_json("[1e999]", "job = j"); }).find("job = j: unreadable JSON value"),
            std::string::npos);
  EXPECT_NE(error_of([] { parse_json("{\"a\":", "job = j"); }).find("malformed JSON at byte"),
            std::string::npos);
}

TEST(JsonInput, TypedReadsNameTheKeyAndTheRule) {
  const auto j = nlohmann::json::parse(R"({"a": 5, "b": "t", "c": true})");
  EXPECT_EQ(get_text(j, "b", "job", ""), "t");
  EXPECT_EQ(get_text(j, "zz", "job", "dflt"), "dflt");
  EXPECT_EQ(error_of([&] { get_text(j, "a", "job", ""); }), "job.a = 5: must be text");
  EXPECT_EQ(error_of([&] { get_number(j, "b", "job", 0); }), "job.b = \"t\": must be a finite number");
  EXPECT_EQ(error_of([&] { get_bool(j, "a", "job", false); }), "job.a = 5: must be true or false");
  EXPECT_DOUBLE_EQ(get_number(j, "a", "job", 0), 5.0);
}

}  // namespace
}  // namespace strand::slicer
