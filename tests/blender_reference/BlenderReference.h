#pragma once

#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <glm/mat4x4.hpp>
#include <nlohmann/json.hpp>

namespace spindrift::test {

/// reference.json as written by tests/fixtures/bake_blender_reference.py (the CTest fixture bakes it).
inline const nlohmann::json& blenderReference() {
  static const nlohmann::json reference = [] {
    const std::string path = std::string(SPINDRIFT_FIXTURE_DIR) + "/blender_reference/reference.json";
    std::ifstream file(path);
    if (!file) throw std::runtime_error(path + " is missing: run the bake_blender_reference_fixture test");
    return nlohmann::json::parse(file);
  }();
  return reference;
}

/// Blender's row-major matrix_world as a GLM (column-major) matrix.
inline glm::mat4 matrixFromRows(const nlohmann::json& rows) {
  glm::mat4 matrix(1.0f);
  for (int row = 0; row < 4; ++row) {
    for (int column = 0; column < 4; ++column)
      matrix[column][row] = rows.at(row).at(column).get<float>();
  }
  return matrix;
}

inline glm::vec3 vec3(const nlohmann::json& value) {
  return {value.at(0).get<float>(), value.at(1).get<float>(), value.at(2).get<float>()};
}

}  // namespace spindrift::test
