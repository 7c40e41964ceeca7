#pragma once
// Seed 000's published numbers (results/reference/seed000_step_error.yaml),
// read strictly: every key of that file is known here, so a typo in the
// transcription is an error, not a silently missing value.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace cnclab {

struct PaperBins {
  std::vector<double> edges;  // bin edges; +inf closes the last relative-error bin
  std::vector<double> count;  // as printed
  std::vector<double> percent;
};

struct PaperBinTable {
  PaperBins absolute_um, relative_percent;
};

// A surface section of the text ("Predict step error values of Surface 2/3").
struct PaperSurfaceText {
  double max_abs_at_0 = 0, max_abs_at_15 = 0;                  // µm
  double share_below_1um_at_0 = 0, share_below_1um_at_15 = 0;  // %
  double share_rel_below_10_at_15 = 0;                         // %
  double mean_abs_at_15 = 0;                                   // µm
  double share_below_0_4um_at_15 = 0;                          // %
};

struct Seed000Reference {
  std::vector<double> table2_p, table2_mse;
  double figure5_final_mse = 0;
  PaperBinTable table3;
  double table3_max_abs_um = 0, table3_share_below_0_5um = 0, table3_share_rel_above_10 = 0;
  std::vector<double> fine_tune_percent;  // Tables 4 and 5
  std::vector<double> test_samples;
  PaperSurfaceText surface2, surface3;
  PaperBinTable table6, table7;
  // Table 8 [s]: surface -> seconds.
  std::map<std::string, double> table8_geometric, table8_proposed;
  std::vector<std::string> checks;  // the paper's inconsistencies, one sentence each
};

// Throws MissingResults when the file is absent, ConfigError on a malformed
// or incomplete file.
Seed000Reference read_seed000_reference(const std::filesystem::path& file);

}  // namespace cnclab
