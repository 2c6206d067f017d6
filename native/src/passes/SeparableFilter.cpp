#include "passes/SeparableFilter.h"

#include "gl/ShaderLibrary.h"

namespace spindrift {

const Texture2D& runSeparableFilter(GLuint program, const Texture2D& eyeDepth, int iterations,
                                    DepthPingPong& targets) {
  const GLint direction = uniformLocation(program, "direction");
  const Texture2D* current = &eyeDepth;
  for (int iteration = 0; iteration < iterations; ++iteration) {
    glUniform2i(direction, 1, 0);
    current = &targets.draw(*current);
    glUniform2i(direction, 0, 1);
    current = &targets.draw(*current);
  }
  return *current;
}

}  // namespace spindrift
