#pragma once

#include "gl/GlObjects.h"
#include "spindrift/Scene.h"

namespace spindrift {

/// Sets the light uniforms of shaders/lib/light_view.glsl that `program` uses (a stage that does not weigh
/// the light, say, has no lightColor).
void setLightUniforms(GLuint program, const Light& light);

/// Sets a uniform if the program has it; returns whether it did.
bool setUniformIfActive(GLuint program, const char* name, float value);
bool setUniformIfActive(GLuint program, const char* name, const glm::vec3& value);

}  // namespace spindrift
