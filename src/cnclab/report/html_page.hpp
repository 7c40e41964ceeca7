#pragma once
// A self-contained HTML page for `cnclab report`: one <style> (screen and
// print), no script, no external resource; figures are inline SVG drawn
// here or PNG data URIs (study_figures.hpp). Text is escaped on the way in.
#include <string>
#include <utility>
#include <vector>

#include "cnclab/report/text_table.hpp"

namespace cnclab {

// &, <, >, " and ' as entities.
std::string html_escape(const std::string& text);

// One line of a chart: its name and points (x, y); non-finite points break it.
struct ChartSeries {
  std::string name;
  std::vector<std::pair<double, double>> points;
};
struct ChartOptions {
  std::string title;
  std::string x_label, y_label;
  bool log_y = false;            // a loss: log10 axis when every y is positive
  std::size_t max_points = 400;  // a series is thinned to this many (page size)
};
// An inline <svg> line chart with axes, ticks and a legend (role="img").
std::string svg_line_chart(const std::vector<ChartSeries>& series, const ChartOptions& options);

// Parallel coordinates: one polyline per row over the axes (numbers, or
// text placed in order of first appearance); the last axis is usually the
// objective. `rows[i][a]` is row i's value text on axis a ("" = none).
std::string svg_parallel_coordinates(const std::vector<std::string>& axes,
                                     const std::vector<std::vector<std::string>>& rows,
                                     const std::string& title);

class HtmlPage {
 public:
  explicit HtmlPage(std::string title);
  void heading(int level, const std::string& text, const std::string& id = "");
  void paragraph(const std::string& text, const std::string& css_class = "");
  // A <table> (class "data"); cells "PASS"/"FAIL" get classes pass/fail.
  void table(const TextTable& table, const std::string& caption = "");
  // Raw markup made by this module (SVG, or an <img> of a data URI): inside a <figure>.
  void figure(const std::string& svg, const std::string& caption);
  void definitions(const std::vector<std::pair<std::string, std::string>>& items);
  // The page; a list of links to every level-2 and level-3 heading follows
  // the level-1 heading when there are two or more (a study's report is long:
  // a block per run behind its numbers).
  std::string html() const;

 private:
  struct ContentsEntry {
    int level;
    std::string text, id;
  };
  std::string title_;
  std::string body_;
  std::vector<ContentsEntry> contents_;
  std::size_t contents_at_ = 0;  // where in body_ the list goes: after the h1
};

}  // namespace cnclab
