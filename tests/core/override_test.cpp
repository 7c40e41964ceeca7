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

// `model.hidden=[16, 8]` unquoted reaches us as
// `model.hidden=[16,`; the message says the shell split it.
TEST(Override, UnclosedBracketSuggestsQuoting) {
  const auto message = [](const char* text) {
    try {
      parse_override(text);
    } catch (const ConfigError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(message("model.hidden=[16,")
                .find("the shell may have split the word at a space: "
                      "quote it, e.g. 'model.hidden=[16, ...'"),
            std::string::npos)
      << message("model.hidden=[16,");
  EXPECT_NE(message("trainer={type: lm,").find("quote it"), std::string::npos);
  // Balanced but invalid: no such hint.
  EXPECT_EQ(message("a=[1, ]]").find("quote it"), std::string::npos);
}

}  // namespace
}  // namespace cnclab
