#include "scene/JsonFields.h"

#include <cmath>
#include <sstream>

#include <glm/gtc/matrix_access.hpp>

#include "spindrift/Error.h"

namespace spindrift {

using nlohmann::json;

namespace {
// Shortest form (%g): the bounds read "(0, 1e+30]" and "(0, 179]", as docs/scene-format.md shows them, not
// std::to_string's "(0.000000, 1000000015047466219876688855040.000000]".
std::string bound(double value) {
  std::ostringstream text;
  text << value;
  return text.str();
}
}  // namespace

JsonFields::JsonFields(const json& object, std::string fileLabel, std::string path)
    : object_(object), fileLabel_(std::move(fileLabel)), path_(std::move(path)) {
  if (!object_.is_object())
    throw Error(fileLabel_ + ": " + (path_.empty() ? "the file" : path_) + ": expected an object, got " +
                object_.dump().substr(0, 60));
}

void JsonFields::fail(const std::string& key, const std::string& problem) const {
  throw Error(fileLabel_ + ": " + keyPath(key) + ": " + problem);
}

void JsonFields::allowOnly(std::initializer_list<const char*> allowed) const {
  for (const auto& item : object_.items()) {
    bool known = false;
    for (const char* key : allowed)
      known = known || item.key() == key;
    if (!known) {
      std::string list;
      for (const char* key : allowed)
        list += (list.empty() ? "" : ", ") + std::string(key);
      fail(item.key(), "unknown key (expected one of: " + list + ")");
    }
  }
}

JsonFields JsonFields::child(const char* key) const {
  return JsonFields(raw(key), fileLabel_, keyPath(key));
}

const json& JsonFields::raw(const char* key) const {
  if (!object_.contains(key)) fail(key, "missing");
  return object_.at(key);
}

int JsonFields::integer(const char* key, int minimum, int maximum) const {
  const json& value = raw(key);
  if (!value.is_number_integer() &&
      !(value.is_number_float() && value.get<double>() == std::floor(value.get<double>())))
    fail(key, "expected an integer, got " + value.dump());
  const double number = value.get<double>();
  if (number < minimum || number > maximum)
    fail(key,
         value.dump() + " is outside [" + std::to_string(minimum) + ", " + std::to_string(maximum) + "]");
  return int(number);
}

float JsonFields::number(const char* key, float minimumExclusive, float maximum) const {
  const json& value = raw(key);
  if (!value.is_number()) fail(key, "expected a number, got " + value.dump());
  const double number = value.get<double>();
  if (!std::isfinite(number) || number <= minimumExclusive || number > maximum) {
    fail(key, value.dump() + " is outside (" + bound(minimumExclusive) + ", " + bound(maximum) + "]");
  }
  return float(number);
}

std::string JsonFields::string(const char* key) const {
  const json& value = raw(key);
  if (!value.is_string()) fail(key, "expected a string, got " + value.dump());
  return value.get<std::string>();
}

glm::vec3 JsonFields::vec3(const char* key) const {
  const json& value = raw(key);
  if (!value.is_array() || value.size() != 3) fail(key, "expected three numbers, got " + value.dump());
  glm::vec3 result;
  for (int i = 0; i < 3; ++i) {
    if (!value[i].is_number() || !std::isfinite(value[i].get<double>()))
      fail(key, "expected three finite numbers, got " + value.dump());
    result[i] = value[i].get<float>();
  }
  return result;
}

glm::vec3 JsonFields::color(const char* key) const {
  const glm::vec3 result = vec3(key);
  for (int i = 0; i < 3; ++i)
    if (result[i] < 0.0f) fail(key, "colour channels must not be negative");
  return result;
}

glm::mat4 JsonFields::affineMatrix(const char* key) const {
  const json& value = raw(key);
  if (!value.is_array() || value.size() != 16)
    fail(key, "expected 16 numbers (a row-major 4x4 matrix), got " + value.dump().substr(0, 80));
  glm::mat4 matrix;
  for (int row = 0; row < 4; ++row)
    for (int column = 0; column < 4; ++column) {
      const json& element = value[row * 4 + column];
      if (!element.is_number() || !std::isfinite(element.get<double>()))
        fail(key, "element " + std::to_string(row * 4 + column) + " is not a finite number");
      matrix[column][row] = element.get<float>();  // GLM is column-major.
    }
  const glm::vec4 lastRow = glm::row(matrix, 3);
  if (lastRow != glm::vec4(0, 0, 0, 1)) fail(key, "the last row must be 0 0 0 1 (an affine transform)");
  const float determinant = glm::determinant(glm::mat3(matrix));
  if (!(std::abs(determinant) > 1e-12f)) fail(key, "the matrix is singular");
  return matrix;
}

std::filesystem::path JsonFields::path(const char* key, const std::filesystem::path& baseDirectory) const {
  const std::string text = string(key);
  if (text.empty()) fail(key, "empty path");
  const std::filesystem::path path(text);
  return (path.is_absolute() ? path : baseDirectory / path).lexically_normal();
}

}  // namespace spindrift
