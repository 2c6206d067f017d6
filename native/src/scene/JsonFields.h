#pragma once

#include <filesystem>
#include <initializer_list>
#include <string>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

namespace spindrift {

/// Reads typed, validated fields of one JSON object of a scene file. Every failure throws Error as
/// "<file>: <key path>: <problem>", so a user knows which line to edit.
class JsonFields {
 public:
  JsonFields(const nlohmann::json& object, std::string fileLabel, std::string path);

  /// Fails on any key not in `allowed`: a typo must not pass silently.
  void allowOnly(std::initializer_list<const char*> allowed) const;
  bool has(const char* key) const { return object_.contains(key); }
  JsonFields child(const char* key) const;
  const nlohmann::json& raw(const char* key) const;

  int integer(const char* key, int minimum, int maximum) const;
  float number(const char* key, float minimumExclusive, float maximum) const;
  std::string string(const char* key) const;
  glm::vec3 vec3(const char* key) const;
  glm::vec3 color(const char* key) const;
  /// 16 numbers, row-major, an invertible affine transform (last row 0 0 0 1).
  glm::mat4 affineMatrix(const char* key) const;
  std::filesystem::path path(const char* key, const std::filesystem::path& baseDirectory) const;

  [[noreturn]] void fail(const std::string& key, const std::string& problem) const;
  std::string keyPath(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }

 private:
  const nlohmann::json& object_;
  std::string fileLabel_;
  std::string path_;
};

}  // namespace spindrift
