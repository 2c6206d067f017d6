#include "spindrift/Parameters.h"

#include <cmath>
#include <sstream>

#include "spindrift/Error.h"

namespace spindrift {
namespace {

using nlohmann::json;

std::vector<std::string> splitChoices(const char* choices) {
  std::vector<std::string> result;
  std::stringstream stream(choices);
  for (std::string choice; std::getline(stream, choice, '|');)
    if (!choice.empty()) result.push_back(choice);
  return result;
}

std::string formatRange(double minimum, double maximum) {
  std::ostringstream text;
  text << "[" << minimum << ", " << maximum << "]";
  return text.str();
}

// One reader per parameter type: each validates the JSON value and its range, naming `where` on failure.
struct ValueReader {
  const std::string& where;
  double minimum;
  double maximum;
  const char* choices;

  [[noreturn]] void fail(const std::string& problem) const { throw Error(where + ": " + problem); }

  double number(const json& value) const {
    if (!value.is_number()) fail("expected a number, got " + value.dump());
    const double number = value.get<double>();
    if (!std::isfinite(number)) fail("expected a finite number");
    return number;
  }
  double bounded(const json& value) const {
    const double result = number(value);
    if (result < minimum || result > maximum)
      fail(value.dump() + " is outside " + formatRange(minimum, maximum));
    return result;
  }
  glm::vec3 vector(const json& value, bool bounded) const {
    if (!value.is_array() || value.size() != 3) fail("expected three numbers, got " + value.dump());
    glm::vec3 result;
    for (int i = 0; i < 3; ++i)
      result[i] = float(bounded ? this->bounded(value[i]) : number(value[i]));
    return result;
  }

  void read(const json& value, float& out) const { out = float(bounded(value)); }
  void read(const json& value, int& out) const {
    const double result = bounded(value);
    if (result != std::floor(result)) fail("expected an integer, got " + value.dump());
    out = int(result);
  }
  void read(const json& value, bool& out) const {
    if (!value.is_boolean()) fail("expected true or false, got " + value.dump());
    out = value.get<bool>();
  }
  void readColor(const json& value, glm::vec3& out) const { out = vector(value, true); }
  void readVec3(const json& value, glm::vec3& out) const { out = vector(value, false); }
  void read(const json& value, std::string& out) const {
    if (!value.is_string()) fail("expected a string, got " + value.dump());
    const auto options = splitChoices(choices);
    for (const auto& option : options)
      if (option == value.get<std::string>()) {
        out = option;
        return;
      }
    fail("\"" + value.get<std::string>() + "\" is not one of " + choices);
  }
};

json toJson(float value) {
  return value;
}
json toJson(int value) {
  return value;
}
json toJson(bool value) {
  return value;
}
json toJson(const glm::vec3& value) {
  return json::array({value.x, value.y, value.z});
}
json toJson(const std::string& value) {
  return value;
}

// Color and Vec3 share a C++ type; the type name picks the reader.
#define SPINDRIFT_READ_Float(reader, value, member) reader.read(value, member)
#define SPINDRIFT_READ_Int(reader, value, member) reader.read(value, member)
#define SPINDRIFT_READ_Bool(reader, value, member) reader.read(value, member)
#define SPINDRIFT_READ_Choice(reader, value, member) reader.read(value, member)
#define SPINDRIFT_READ_Color(reader, value, member) reader.readColor(value, member)
#define SPINDRIFT_READ_Vec3(reader, value, member) reader.readVec3(value, member)

}  // namespace

const std::vector<ParameterInfo>& parameterTable() {
  static const std::vector<ParameterInfo> table = [] {
    std::vector<ParameterInfo> rows;
    const Parameters defaults;
#define SPINDRIFT_TABLE_ROW(group, name, type, defaultValue, minimum, maximum, choices, doc) \
  rows.push_back(                                                                            \
      {#group "." #name, #type, toJson(defaults.group.name), minimum, maximum, splitChoices(choices), doc});
#define SPINDRIFT_TABLE_GROUP(group, Group, PARAMETERS) PARAMETERS(SPINDRIFT_TABLE_ROW)
    SPINDRIFT_PARAMETER_GROUPS(SPINDRIFT_TABLE_GROUP)
#undef SPINDRIFT_TABLE_GROUP
#undef SPINDRIFT_TABLE_ROW
    return rows;
  }();
  return table;
}

void setParameter(Parameters& parameters, const std::string& key, const json& value) {
#define SPINDRIFT_SET_ROW(group, name, type, defaultValue, minimum, maximum, choices, doc) \
  if (key == #group "." #name) {                                                           \
    const ValueReader reader{key, minimum, maximum, choices};                              \
    SPINDRIFT_READ_##type(reader, value, parameters.group.name);                           \
    return;                                                                                \
  }
#define SPINDRIFT_SET_GROUP(group, Group, PARAMETERS) PARAMETERS(SPINDRIFT_SET_ROW)
  SPINDRIFT_PARAMETER_GROUPS(SPINDRIFT_SET_GROUP)
#undef SPINDRIFT_SET_GROUP
#undef SPINDRIFT_SET_ROW
  throw Error("unknown parameter \"" + key + "\" (`spindrift params` lists them)");
}

json getParameter(const Parameters& parameters, const std::string& key) {
#define SPINDRIFT_GET_ROW(group, name, type, defaultValue, minimum, maximum, choices, doc) \
  if (key == #group "." #name) return toJson(parameters.group.name);
#define SPINDRIFT_GET_GROUP(group, Group, PARAMETERS) PARAMETERS(SPINDRIFT_GET_ROW)
  SPINDRIFT_PARAMETER_GROUPS(SPINDRIFT_GET_GROUP)
#undef SPINDRIFT_GET_GROUP
#undef SPINDRIFT_GET_ROW
  throw Error("unknown parameter \"" + key + "\" (`spindrift params` lists them)");
}

void setParameterGroup(Parameters& parameters, const std::string& group, const json& object,
                       const std::string& fileLabel) {
  if (!object.is_object()) throw Error(fileLabel + ": " + group + ": expected an object of parameters");
  for (const auto& [name, value] : object.items()) {
    try {
      setParameter(parameters, group + "." + name, value);
    } catch (const Error& error) {
      throw Error(fileLabel + ": " + error.what());
    }
  }
}

std::string parametersMarkdown() {
  std::ostringstream text;
  text << "# Parameters\n\n"
          "Generated by `spindrift params --markdown` from `native/include/spindrift/parameters.def`, the "
          "one\n"
          "table that also feeds the scene file, `spindrift render --set`, and the Blender add-on. Do not "
          "edit\n"
          "this file by hand.\n\n"
          "In a scene file, parameters sit in their group's object (`\"liquid\": {\"base_color\": [0.3, 0.5, "
          "0.8]}`);\non the command line, `--set liquid.base_color=[0.3,0.5,0.8]` (the value is JSON).\n";
  std::string currentGroup;
  for (const auto& row : parameterTable()) {
    const std::string group = row.key.substr(0, row.key.find('.'));
    if (group != currentGroup) {
      currentGroup = group;
      text << "\n## `" << group
           << "`\n\n| Parameter | Type | Default | Range | Description |\n|---|---|---|---|---|\n";
    }
    std::string range = "";
    if (row.type == "Float" || row.type == "Int" || row.type == "Color")
      range = formatRange(row.minimum, row.maximum);
    if (row.type == "Choice") {
      for (const auto& choice : row.choices)
        range += (range.empty() ? "" : ", ") + ("`" + choice + "`");
    }
    text << "| `" << row.key << "` | " << row.type << " | `" << row.defaultValue.dump() << "` | " << range
         << " | " << row.doc << " |\n";
  }
  return text.str();
}

}  // namespace spindrift
