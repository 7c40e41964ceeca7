#pragma once
// The step-error dataset of seed 000 (Table 1) and patent 003 (claim 3): one
// sample per tool-path segment of an iso-parametric ball-end tool path on a
// NURBS surface (geometry/tool_path.hpp).
//
// Inputs (3K + 13, all mm): the K points p_j = S(u_i + j (u_i+1 - u_i)/(K+1), v),
// j = 1..K, on the local CC curve (iso-parametric, excluding the two CC
// points), then CC_i, CC_i+1, CL_i, CL_i+1 (x, y, z each), then R.
// Target: the exact step error e_i (seed 000 Eq. 1) in µm.
// Metadata (not inputs): line index, point index i, u_i, u_i+1, v, convex
// (1 convex, 0 concave).
//
// Default K = 20: seed 000's network has 73 inputs (the text copy does not
// print the number; its Table 1 lists {p_j}, the two CC points, the two CL
// points and R, patent claim 3 the same), and 3K + 3*2 + 3*2 + 1 = 73 gives
// K = 20 points on the local CC curve, consistent with the layout. Not
// consistent: the paper's Eq. 8, n1 = sqrt(n + m) + a with a in [1, 10],
// gives 9.6..18.6 neurons for n = 73, m = 1, not its 28 (28 would need
// n >= 323, i.e. K >= 104); we keep 73 inputs and the 28/20 network.
#include <cstddef>
#include <memory>
#include <string>

#include "cnclab/cad/cad_surface.hpp"
#include "cnclab/core/config.hpp"
#include "cnclab/core/fields.hpp"
#include "cnclab/data/dataset.hpp"
#include "cnclab/data/generator.hpp"
#include "cnclab/geometry/nurbs_surface.hpp"
#include "cnclab/geometry/step_error.hpp"
#include "cnclab/geometry/tool_path.hpp"

namespace cnclab {

struct StepErrorDatasetOptions {
  // The machined surface (configs/surfaces/*.yaml; geometry/surface_config.hpp).
  NurbsSurface surface;
  // Set when `surface` is a face of a STEP/IGES file (cad/cad_surface.hpp):
  // its NURBS form is `surface`, and validate() checks the tool path stays on
  // the face.
  std::shared_ptr<const CadSurface> cad;
  // Lines, CC points per line and ball radius R (defaults: seed 000's 200 x 100, 5 mm).
  ToolPathOptions tool_path;
  // K, discrete points per local CC curve given as inputs; 73 inputs at 20 (see above). >= 1.
  std::size_t curve_points = 20;
  // Accuracy of the theoretical value (bracketing grid + Newton to 1e-12 in u).
  ExactStepErrorOptions exact;

  void validate() const;  // each part's validate(), field names prefixed
  std::size_t num_samples() const { return tool_path.lines * (tool_path.points_per_line - 1); }
  std::size_t num_inputs() const { return 3 * curve_points + 13; }
};

// options.validate(), then the dataset.
Dataset generate_step_error_dataset(const StepErrorDatasetOptions& options);

// The 3K + 13 inputs of segment i (< path.u.size() - 1) of a planned line,
// in the column order above, written to x (size 3K + 13). Sample s of the
// dataset is segment s % (M - 1) of line s / (M - 1).
void step_error_inputs(const ToolPathLine& path, std::size_t i, std::size_t k,
                       Eigen::Ref<Eigen::VectorXd> x);

// The registered generator `step_error`. Options (dataset.options):
//   surface: configs/surfaces/surface1.yaml   # a path, resolved like include:
//                                              # (relative to the naming file,
//                                              # else configs/... upward), or
//                                              # the surface map inline, or
//                                              # {file: part.step, face: 3}: a
//                                              # face of a STEP/IGES file
//   lines: 200
//   points_per_line: 100
//   tool_radius: 5          # mm
//   curve_points: 20        # K
// options_yaml() writes the surface inline, so the cache key covers the
// geometry itself, not the file name; a CAD face is written as
// {file_hash, face, type}: the file's content, not its path, is the identity
// (and the dataset's generator_config records them).
class StepErrorGenerator : public DatasetGenerator {
 public:
  explicit StepErrorGenerator(StepErrorDatasetOptions options);  // validates
  std::string name() const override { return "step_error"; }
  int version() const override { return 1; }
  DatasetShape shape() const override { return {options_.num_samples(), options_.num_inputs(), 1}; }
  std::string options_yaml() const override;
  // From the options the constructor validated (not again: a CAD face's
  // path-on-face check is not free).
  Dataset generate(Rng&) const override;
  bool uses_seed() const override { return false; }  // pure geometry
  // 1e-6 µm (1 pm): the step error is computed in mm from coordinates of
  // ~100 mm in double precision (rounding ~1e-14 mm = 1e-11 µm, what a flat
  // face gives), five orders below this floor and four below seed 000's
  // smallest step error (0.01 µm).
  std::vector<double> target_resolution() const override { return {1e-6}; }
  const StepErrorDatasetOptions& options() const { return options_; }

 private:
  StepErrorDatasetOptions options_;
};

// dataset.options of `step_error`: {surface, lines, points_per_line, tool_radius, curve_points}.
const FieldList<StepErrorDatasetOptions>& step_error_fields();

std::shared_ptr<const DatasetGenerator> read_step_error(const ConfigReader& options);

}  // namespace cnclab
