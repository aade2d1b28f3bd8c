// Headers nearly every translation unit parses (the JSON library and Eigen are most of a
// unit's compile time): precompiled once per library (CMake target_precompile_headers).
#pragma once
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <vector>
