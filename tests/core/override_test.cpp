#include "cnclab/core/override.hpp"

#include <gtest/gtest.h>

#include "cnclab/core/error.hpp"

namespace cnclab {
namespace {

TEST(Override, ParsesDottedKeyAndYamlTypedValue) {
  const auto o = parse_override("trainer.learning_rate=1e-4");
  EXPECT_EQ(o.path, (std::vector<std::string>{"trainer", "learning_rate"}));
  EXPECT_EQ(o.dotted_key(), "trainer.learning_rate");
  EXPECT_TRUE(o.value.IsScalar());
  EXPECT_EQ(o.value.Scalar(), "1e-4");
  EXPECT_TRUE(parse_override("model.hidden=[28, 20]").value.IsSequence());
  EXPECT_EQ(parse_override("a=b=c").value.Scalar(), "b=c");  // only the first '=' splits
}

TEST(Override, RejectsMalformedText) {
  for (const char* bad : {"novalue", "=3", "a..b=1", ".a=1", "a.=1", "a b=1",
                          "a=", "a=  ", "a=[1, 2", "a=~", "a=null"}) {
    EXPECT_THROW(parse_override(bad), ConfigError) << bad;
  }
}

TEST(Override, MessageNamesTheOverride) {
  try {
    parse_override("a..b=1");
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("override 'a..b=1'"), std::string::npos);
  }
}

}  // namespace
}  // namespace cnclab
