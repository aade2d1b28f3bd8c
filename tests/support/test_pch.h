// Headers nearly every test file reads, precompiled once for the test executable
// (tests/CMakeLists.txt). Test files still include what they use.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>
#include <vector>
