#pragma once
// The step-error dataset of seed 000 (Table 1) and patent 003 (claim 3): one
// sample per segment of an iso-parametric ball-end tool path on a NURBS
// surface (geometry/tool_path.hpp), i.e. per pair of neighbouring CC points
// of one run of a line: a line cut by a face's trims, an unreachable or a
// degenerate part (`unreachable: clip`) splits into runs, and no sample spans
// a cut.
//
// Inputs (3K + 13, all mm): the K points p_j = C(t_i + j (t_i+1 - t_i)/(K+1)),
// j = 1..K, on the local CC curve C (iso-parametric along the feed,
// excluding the two CC points), then CC_i, CC_i+1, CL_i, CL_i+1 (x, y, z
// each), then R.
// Target: the exact step error e_i (seed 000 Eq. 1) in µm; always below R (a
// larger one means the CL line left the tool's reach: refused).
// Metadata (not inputs): line index, segment (run) index within the line,
// CC point index i within the line, (u, v) of CC_i and of CC_i+1, convex (1
// convex, 0 concave), gouge (1 where the ball cuts into the surface, kept
// by `gouge: allow`).
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
  // How messages name it: "surface configs/surfaces/surface1.yaml" (not the identity).
  std::string surface_name = "the surface";
  // Set when `surface` is a face of a STEP/IGES file (cad/cad_surface.hpp):
  // its NURBS form is `surface`; its trims and orientation shape the path.
  std::shared_ptr<const CadSurface> cad;
  // Lines, CC points per line, ball radius R (defaults: seed 000's 200 x 100,
  // 5 mm), feed direction, tool axis and what to do where the face cannot be
  // machined.
  ToolPathOptions tool_path;
  // K, discrete points per local CC curve given as inputs; 73 inputs at 20 (see above). >= 1.
  std::size_t curve_points = 20;
  // Accuracy of the theoretical value (bracketing grid + Newton to 1e-12 in u).
  ExactStepErrorOptions exact;

  void validate() const;  // each part's validate(), field names prefixed
  std::size_t num_inputs() const { return 3 * curve_points + 13; }
  // The face the path is planned on: the CAD face's context, or the surface alone.
  FaceContext face() const;
};

// options.validate(), plan_tool_path, then the dataset.
Dataset generate_step_error_dataset(const StepErrorDatasetOptions& options);

// The 3K + 13 inputs of pair i (CC points i and i + 1 of one run) of a
// planned line, in the column order above, written to x (size 3K + 13).
void step_error_inputs(const ToolPathLine& line, std::size_t i, std::size_t k,
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
//   feed: u                 # or v
//   tool_axis: [0, 0, 1]
//   max_normal_angle: 85    # deg
//   unreachable: refuse     # or clip
//   gouge: refuse           # or allow
//   tool_side: auto         # or front, back
// A CAD face's map may also give read_timeout (seconds; cad_surface.hpp).
// options_yaml() writes the surface inline, so the cache key covers the
// geometry itself, not the file name; a CAD face is written as
// {file_hash, face, type}: the file's content, not its path, is the identity
// (and the dataset's generator_config records them).
class StepErrorGenerator : public DatasetGenerator {
 public:
  // Validates and plans the tool path (PathRefused naming the face, line
  // and CC point where it cannot be machined as the options say).
  explicit StepErrorGenerator(StepErrorDatasetOptions options);
  std::string name() const override { return "step_error"; }
  // 2: runs (trims, reachability, poles, gouges), feed along v, the
  // segment/(u, v)/gouge metadata.
  int version() const override { return 2; }
  DatasetShape shape() const override { return {path_->samples.size(), options_.num_inputs(), 1}; }
  std::string options_yaml() const override;
  // From the options and the path the constructor made (not again: a CAD
  // face's path planning is not free).
  Dataset generate(Rng&) const override;
  bool uses_seed() const override { return false; }  // pure geometry
  // 1e-6 µm (1 pm): the step error is computed in mm from coordinates of
  // ~100 mm in double precision (rounding ~1e-14 mm = 1e-11 µm, what a flat
  // face gives), five orders below this floor and four below seed 000's
  // smallest step error (0.01 µm).
  std::vector<double> target_resolution() const override { return {1e-6}; }
  const StepErrorDatasetOptions& options() const { return options_; }
  const ToolPath& path() const { return *path_; }

 private:
  StepErrorDatasetOptions options_;
  std::shared_ptr<const ToolPath> path_;
};

// dataset.options of `step_error`: {surface, lines, points_per_line,
// tool_radius, curve_points, feed, tool_axis, max_normal_angle, unreachable,
// gouge, tool_side}.
const FieldList<StepErrorDatasetOptions>& step_error_fields();

std::shared_ptr<const DatasetGenerator> read_step_error(const ConfigReader& options);

}  // namespace cnclab
