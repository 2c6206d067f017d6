#pragma once

#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

#include "spindrift/parameters.def"

namespace spindrift {

/// The C++ type behind each parameter type name used in parameters.def.
namespace parameter_types {
using Float = float;
using Int = int;
using Bool = bool;
using Color = glm::vec3;
using Vec3 = glm::vec3;
using Choice = std::string;
}  // namespace parameter_types

#define SPINDRIFT_DECLARE_MEMBER(group, name, type, defaultValue, minimum, maximum, choices, doc) \
  parameter_types::type name = parameter_types::type defaultValue;

/// Parameters of the liquid pipeline (scene key `liquid`).
struct LiquidParameters {
  SPINDRIFT_LIQUID_PARAMETERS(SPINDRIFT_DECLARE_MEMBER)
};

/// Parameters of the foam pipeline (scene key `foam`).
struct FoamParameters {
  SPINDRIFT_FOAM_PARAMETERS(SPINDRIFT_DECLARE_MEMBER)
};

/// Parameters of the light through the liquid (scene key `light`).
struct LightParameters {
  SPINDRIFT_LIGHT_PARAMETERS(SPINDRIFT_DECLARE_MEMBER)
};

#undef SPINDRIFT_DECLARE_MEMBER

#define SPINDRIFT_COMPARE_MEMBER(group, name, type, defaultValue, minimum, maximum, choices, doc) \
  &&a.name == b.name

/// Every parameter of the group equal.
inline bool operator==(const LiquidParameters& a, const LiquidParameters& b) {
  return true SPINDRIFT_LIQUID_PARAMETERS(SPINDRIFT_COMPARE_MEMBER);
}
inline bool operator==(const LightParameters& a, const LightParameters& b) {
  return true SPINDRIFT_LIGHT_PARAMETERS(SPINDRIFT_COMPARE_MEMBER);
}

#undef SPINDRIFT_COMPARE_MEMBER

/// Every parameter, each with the default that parameters.def gives it.
struct Parameters {
  LiquidParameters liquid;
  FoamParameters foam;
  LightParameters light;
};

/// One row of parameters.def, for tools that list, document or build user interfaces from the table.
struct ParameterInfo {
  std::string key;   ///< "group.name", as in the scene file and `--set`.
  std::string type;  ///< Float, Int, Bool, Color, Vec3 or Choice.
  nlohmann::json defaultValue;
  double minimum = 0.0;
  double maximum = 0.0;
  std::vector<std::string> choices;
  std::string doc;
};

const std::vector<ParameterInfo>& parameterTable();

/// Sets one parameter from JSON ("liquid.base_color", [0.2, 0.4, 0.8]); throws Error naming the key when the
/// key is unknown, the value has the wrong type, or it lies outside the parameter's range.
void setParameter(Parameters& parameters, const std::string& key, const nlohmann::json& value);
nlohmann::json getParameter(const Parameters& parameters, const std::string& key);

/// Reads a scene file's group object (e.g. the value of "liquid"); unknown keys are errors. Messages start
/// with `fileLabel`, e.g. "scene.json: liquid.ambient: 2 is outside [0, 1]".
void setParameterGroup(Parameters& parameters, const std::string& group, const nlohmann::json& object,
                       const std::string& fileLabel);

/// docs/parameters.md, generated from the table.
std::string parametersMarkdown();

}  // namespace spindrift
