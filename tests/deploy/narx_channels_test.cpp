// predict and export take one input channel per narx network (seed 002's
// networks); a result whose networks read more (model.inputs, the planning
// predictor's [v, direction]) is refused naming the file, the network and
// its channels, not exported with the extra channels dropped.
#include <gtest/gtest.h>

#include "cnclab/core/error.hpp"
#include "cnclab/deploy/deployed_model.hpp"
#include "cnclab/experiment/run_record.hpp"
#include "common/expect_error.hpp"

namespace cnclab {
namespace {

TEST(DeployedNarx, NetworksWithSeveralInputChannelsAreRefused) {
  RunRecord r;
  r.kind = "train";
  r.provenance.status = "complete";
  r.provenance.derived_seeds["generator"] = 1;
  r.resolved_yaml = "dataset:\n  generator: following_error\n";
  r.input_names = {"v_x", "v_y", "direction_x", "direction_y"};
  r.target_names = {"e_x", "e_y"};
  NarxRecord narx;
  narx.options.inputs = 2;
  narx.networks = {{"x", {"v_x", "direction_x"}, "e_x", {}, {}, 0.0},
                   {"y", {"v_y", "direction_y"}, "e_y", {}, {}, 0.0}};
  r.narx = narx;
  const std::string message =
      testing::error_message<ConfigError>([&] { deployed_model(r, "narx_any_feed.h5"); });
  EXPECT_NE(message.find("narx_any_feed.h5: network x has 2 input channels (v_x, direction_x)"),
            std::string::npos)
      << message;
}

}  // namespace
}  // namespace cnclab
