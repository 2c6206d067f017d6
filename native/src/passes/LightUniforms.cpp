#include "passes/LightUniforms.h"

#include <cmath>

#include <glm/trigonometric.hpp>

namespace spindrift {

bool setUniformIfActive(GLuint program, const char* name, float value) {
  const GLint location = glGetUniformLocation(program, name);
  if (location >= 0) glProgramUniform1f(program, location, value);
  return location >= 0;
}

bool setUniformIfActive(GLuint program, const char* name, const glm::vec3& value) {
  const GLint location = glGetUniformLocation(program, name);
  if (location >= 0) glProgramUniform3fv(program, location, 1, &value.x);
  return location >= 0;
}

void setLightUniforms(GLuint program, const Light& light) {
  const GLint type = glGetUniformLocation(program, "lightType");
  if (type >= 0)
    glProgramUniform1i(program, type, int(light.type));  // The order of shaders' kSun, kSpot, kPoint.
  setUniformIfActive(program, "lightDirection", light.direction);
  setUniformIfActive(program, "lightPosition", light.position);
  setUniformIfActive(program, "lightColor", light.color);
  setUniformIfActive(program, "lightStrength", light.strength);
  setUniformIfActive(program, "spotCosine", std::cos(glm::radians(0.5f * light.spotAngleDegrees)));
}

}  // namespace spindrift
