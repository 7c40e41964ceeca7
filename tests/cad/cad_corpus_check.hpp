#pragma once
// Every face of a real STEP/IGES file through the step-error dataset path,
// each result checked against Open CASCADE itself: a face either gives a
// dataset that agrees with an independent evaluation, or is refused naming
// the face (and the line, where a line is to blame) and the reason. Used by
// the ctest cad_tests (the small files in tests/cad/data) and by
// scripts/check_cad_corpus (any files, e.g. large ones fetched by hand).
//
// The independent check of a dataset, per checked sample (metadata: line,
// (u, v) of both CC points, convex):
//   - CC_i, CC_i+1 against the face's NURBS form evaluated by OCCT
//     (Geom_BSplineSurface::D1, not our evaluator), and against the face's
//     own surface (GeomAPI_ProjectPointOnSurf: the conversion was exact);
//   - both on the face: BRepClass_FaceClassifier from the 3-D point (not the
//     2-D classifier the planner uses);
//   - CL = CC + R n, n OCCT's unit normal times one sign for the whole face,
//     within max_normal_angle of the tool axis; for a solid's face, CC + d n
//     outside every solid and CC - d n inside one (BRepClass3d_SolidClassifier);
//   - the target e_i against |R - L| at the extreme of L over a dense scan
//     (2,000 intervals, then 2,000 more over the two around its extreme) of
//     the CC curve between the two CC points, the curve evaluated by OCCT;
//     and e_i < R.
#include <filesystem>
#include <string>
#include <vector>

#include "cnclab/geometry/tool_path.hpp"

namespace cnclab::testing {

struct CorpusOptions {
  std::size_t lines = 30, points_per_line = 30;  // the path on each face
  double tool_radius = 5.0;                      // R [mm]
  std::size_t checked_samples = 30;  // per dataset, spread evenly over it (all when fewer)
  int scan_intervals = 2000;         // of the dense scan of L
  double read_timeout = 0;           // 0: the default for the file's size
};

struct FaceCheck {
  int face = 1;
  std::string type;     // plane, cylinder, bspline, ...
  bool curved = false;  // not a plane
  std::string outcome;  // "dataset", or the refusal's reason
  std::string message;  // the refusal's message (empty for a dataset)
  std::size_t samples = 0;
  double max_step_error_um = 0;  // of the dataset
  double max_deviation_um = 0;   // |target - dense scan| over the checked samples
  std::string disagreement;      // empty: agrees (or refused with face, line and reason)
};

struct FileCheck {
  std::string file, writer, unit;
  std::string read_error;               // the file could not be read (then no faces)
  std::vector<FaceCheck> refuse, clip;  // unreachable: refuse (default) / clip
};

// Reads `file` once and runs every face with both unreachable policies.
FileCheck check_cad_file(const std::filesystem::path& file, const CorpusOptions& options);

}  // namespace cnclab::testing
