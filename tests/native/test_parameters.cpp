#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "spindrift/Error.h"
#include "spindrift/Parameters.h"

using namespace spindrift;

TEST(Parameters, TableListsEveryParameterWithItsDefault) {
  const Parameters defaults;
  ASSERT_FALSE(parameterTable().empty());
  for (const ParameterInfo& row : parameterTable()) {
    EXPECT_EQ(getParameter(defaults, row.key), row.defaultValue) << row.key;
    EXPECT_FALSE(row.doc.empty()) << row.key;
  }
}

TEST(Parameters, SetValidatesTypeAndRange) {
  Parameters parameters;
  setParameter(parameters, "liquid.ior", 1.5);
  EXPECT_FLOAT_EQ(parameters.liquid.ior, 1.5f);
  setParameter(parameters, "liquid.absorption_rgb", nlohmann::json::array({0.1, 0.2, 0.3}));
  EXPECT_FLOAT_EQ(parameters.liquid.absorption_rgb.y, 0.2f);
  EXPECT_THROW(setParameter(parameters, "liquid.ior", 5.0), Error);
  EXPECT_THROW(setParameter(parameters, "liquid.ior", "high"), Error);
  EXPECT_THROW(setParameter(parameters, "liquid.absorption_rgb", nlohmann::json::array({0.1, 0.2})), Error);
  EXPECT_THROW(setParameter(parameters, "liquid.absorption_rgb", nlohmann::json::array({0.1, 0.2, -1.5})),
               Error);
  EXPECT_THROW(setParameter(parameters, "liquid.no_such_thing", 1), Error);
  EXPECT_FLOAT_EQ(parameters.liquid.ior, 1.5f) << "a rejected value must leave the old one";
}

TEST(Parameters, GroupErrorsNameFileAndKey) {
  Parameters parameters;
  try {
    setParameterGroup(parameters, "liquid", {{"absorbtion", 0.2}}, "scene.json");
    FAIL() << "a misspelt key must be an error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("scene.json"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("liquid.absorbtion"), std::string::npos) << error.what();
  }
}

// docs/parameters.md is generated from the table; this fails when someone edits one without the other.
TEST(Parameters, DocsMatchTheTable) {
  std::ifstream file(std::string(SPINDRIFT_SOURCE_DIR) + "/docs/parameters.md");
  ASSERT_TRUE(file)
      << "docs/parameters.md is missing: run `spindrift params --markdown > docs/parameters.md`";
  std::stringstream text;
  text << file.rdbuf();
  EXPECT_EQ(text.str(), parametersMarkdown())
      << "docs/parameters.md is stale: run `build/bin/spindrift params --markdown > docs/parameters.md`";
}
