// Our three YAML surfaces written as STEP and IGES B-spline faces and read
// back give the same step-error datasets as the YAML, and
// the dataset's identity is the file's content, not its path.
#include <gtest/gtest.h>

#include <cmath>

#include "cad/cad_fixtures.hpp"
#include "cnclab/cad/cad_export.hpp"
#include "cnclab/cad/cad_format.hpp"
#include "cnclab/cad/cad_surface.hpp"
#include "cnclab/core/hash.hpp"
#include "cnclab/data/dataset_cache.hpp"
#include "cnclab/geometry/surface_config.hpp"
#include "common/temp_dir.hpp"

namespace cnclab {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;

// Equal datasets: the STEP/IGES text keeps 17 significant digits, so the
// surface reads back bit-identical and so do the samples.
constexpr double kRoundTripTolUm = 1e-9;  // step error [µm]
constexpr double kRoundTripTolMm = 1e-9;  // inputs [mm]

std::string surface_yaml(int i) {
  return CNCLAB_SOURCE_DIR "/configs/surfaces/surface" + std::to_string(i) + ".yaml";
}

NurbsSurface load_surface(const std::string& file) {
  const ConfigDocument doc = ConfigDocument::load(file);
  return read_nurbs_surface(doc.root());
}

void expect_same_datasets(const Dataset& yaml, const Dataset& cad, const std::string& what) {
  ASSERT_EQ(yaml.num_samples(), cad.num_samples()) << what;
  ASSERT_EQ(yaml.inputs.rows(), cad.inputs.rows()) << what;
  EXPECT_LE((yaml.targets - cad.targets).cwiseAbs().maxCoeff(), kRoundTripTolUm) << what;
  EXPECT_LE((yaml.inputs - cad.inputs).cwiseAbs().maxCoeff(), kRoundTripTolMm) << what;
  EXPECT_EQ(yaml.metadata, cad.metadata) << what;  // line, point, u, v, convex
  EXPECT_GT(yaml.targets.maxCoeff(), 0.0) << what;
}

class CadRoundTrip : public ::testing::TestWithParam<CadFormat> {};

TEST_P(CadRoundTrip, YamlSurfacesGiveTheSameStepErrorDatasets) {
  if (!cad_support_available()) GTEST_SKIP() << cad_unavailable_message();
  TempDir dir;
  const std::string ext = GetParam() == CadFormat::step ? ".step" : ".igs";
  for (int i = 1; i <= 3; ++i) {
    const NurbsSurface s = load_surface(surface_yaml(i));
    const fs::path file = dir / ("surface" + std::to_string(i) + ext);
    testing::write_file(file, cad_surface_text(s, GetParam()));
    const CadSurface cad = read_cad_surface(file, 1);
    EXPECT_EQ(cad.surface_type, "bspline");
    EXPECT_EQ(cad.surface.knots_u, s.knots_u) << file;
    EXPECT_EQ(cad.surface.weights, s.weights) << file;
    expect_same_datasets(
        testing::step_error_dataset(testing::step_error_config(surface_yaml(i))),
        testing::step_error_dataset(testing::step_error_config(testing::cad_face(file))),
        file.string());
  }
}

INSTANTIATE_TEST_SUITE_P(StepAndIges, CadRoundTrip,
                         ::testing::Values(CadFormat::step, CadFormat::iges), [](const auto& info) {
                           return info.param == CadFormat::step ? "step" : "iges";
                         });

// The cache key and the stored generator_config name the content hash, the
// face and its type; the same bytes elsewhere share the key, other bytes do
// not.
TEST(CadDatasetIdentity, IsTheFileContentNotItsPath) {
  if (!cad_support_available()) GTEST_SKIP() << cad_unavailable_message();
  TempDir dir;
  const std::string s1 = cad_surface_text(load_surface(surface_yaml(1)), CadFormat::step);
  const std::string s2 = cad_surface_text(load_surface(surface_yaml(2)), CadFormat::step);
  fs::create_directories(dir / "elsewhere");
  testing::write_file(dir / "a.step", s1);
  testing::write_file(dir / "elsewhere" / "b.stp", s1);
  testing::write_file(dir / "c.step", s2);
  const auto key = [&](const fs::path& file) {
    return dataset_config_text(
        *testing::step_error_generator(testing::step_error_config(testing::cad_face(file))), 0);
  };
  const std::string a = key(dir / "a.step");
  EXPECT_EQ(a, key(dir / "elsewhere" / "b.stp"));
  EXPECT_NE(a, key(dir / "c.step"));
  EXPECT_EQ(a.find("a.step"), std::string::npos) << a;
  EXPECT_NE(a.find("file_hash: " + hash_hex(s1)), std::string::npos) << a;
  EXPECT_NE(a.find("face: 1"), std::string::npos) << a;
  EXPECT_NE(a.find("type: bspline"), std::string::npos) << a;
}

}  // namespace
}  // namespace cnclab
