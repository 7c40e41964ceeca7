#pragma once
// A study's figures in `cnclab report`: the PNG files scripts/figures/ drew
// under RESULTS/figures/<topic>/, embedded as data URIs.
//
// Why embed the scripts' PNGs rather than draw the figures again here: each
// paper figure (seed 000 Figs. 5-8, seed 002 Figs. 4-14, the feedrate plots)
// has one drawing code, the Python script beside the others in
// scripts/figures/ (density plots, shared colour scales, the papers' captions);
// a second drawing in C++ would be a second place to keep right. README
// command 1 draws them before it writes the reports, so they are there when
// the report is made from its results. The report says when a figure set is
// absent (with the command that draws it) and when a figure is older than
// the newest result behind the study's tables. PNG (not the scripts' SVG):
// an inline matplotlib SVG brings its own <style> per figure, and the page
// keeps one copy of any style.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "cnclab/report/html_page.hpp"

namespace cnclab {

// RFC 4648 base64 (with padding) of bytes.
std::string base64_encode(const std::string& bytes);

// A PNG's size in pixels and, when it records one (pHYs in metres), its
// resolution in dots per inch. nullopt: not a PNG.
struct PngInfo {
  std::size_t width = 0, height = 0;
  double dpi = 0;  // 0: not recorded
};
std::optional<PngInfo> png_info(const std::string& bytes);

struct StudyFigureOptions {
  std::filesystem::path figures_dir;  // RESULTS/figures
  std::vector<std::string> topics;    // its subfolders drawn for this study
  std::string anchor;                 // the section heading's id ("" none)
  // The newest result file behind the study's tables: a figure older than it
  // is marked as possibly out of date.
  std::optional<std::filesystem::file_time_type> newest_source;
  // Embedded image bytes (base64) at most this many; a figure beyond it is
  // named by its path instead, so that a study's report stays under the
  // 5 MB a page to share should have (its tables and histories take the rest).
  std::size_t budget_bytes = 4'000'000;
  // The command that draws them, for the note when a set is absent.
  std::string draw_command = "bash scripts/figures/run RESULTS_DIR";
};

// Adds a "Figures" section: every PNG of each topic folder (name order) as a
// figure captioned with its file; notes for absent sets, stale figures and
// figures left out by the budget. Returns the number embedded.
std::size_t add_study_figures(HtmlPage& page, const StudyFigureOptions& options);

}  // namespace cnclab
