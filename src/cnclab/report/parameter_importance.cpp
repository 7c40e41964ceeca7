#include "cnclab/report/parameter_importance.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "cnclab/core/error.hpp"
#include "cnclab/core/format.hpp"
#include "cnclab/io/h5.hpp"
#include "cnclab/report/text_table.hpp"

namespace cnclab {
namespace fs = std::filesystem;

namespace {

std::string value_text(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

}  // namespace

std::optional<ParameterImportance> read_parameter_importance(const fs::path& summary_file) {
  const H5File f = H5File::open_read(summary_file);
  if (!f.exists("/importance")) return std::nullopt;
  ParameterImportance out;
  if (f.has_attribute("/importance", "evaluator"))
    out.evaluator = f.attribute_string("/importance", "evaluator");
  const auto names = f.read_strings("/importance/parameter");
  const auto values = f.read_vector("/importance/value");
  const std::string where = summary_file.string() + ": /importance: ";
  if (names.size() != values.size()) {
    throw IoError(where + std::to_string(names.size()) + " parameters but " +
                  std::to_string(values.size()) + " values (one value per parameter expected)");
  }
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (!std::isfinite(values[i]) || values[i] < 0) {
      throw IoError(where + "value of " + names[i] + " is " + value_text(values[i]) +
                    " (a finite share >= 0 expected)");
    }
    out.values.emplace_back(names[i], values[i]);
  }
  // Largest first whatever the writer's order (the layout promises it).
  std::stable_sort(out.values.begin(), out.values.end(),
                   [](const auto& a, const auto& b) { return a.second > b.second; });
  return out;
}

std::string svg_bar_chart(const std::vector<std::pair<std::string, double>>& bars,
                          const std::string& title, const std::string& value_label) {
  const double W = 640, L = 180, R = 70, T = 34, bar = 18, gap = 6;
  const double H = T + static_cast<double>(bars.size()) * (bar + gap) + 30;
  const std::string size = "viewBox=\"0 0 640 " + fixed_decimals(H, 1) +
                           "\" width=\"640\" height=\"" + fixed_decimals(H, 1);
  std::string svg = "<svg xmlns=\"http://www.w3.org/2000/svg\" " + size +
                    "\" role=\"img\" aria-label=\"" + html_escape(title) +
                    "\"><rect width=\"640\" height=\"" + fixed_decimals(H, 1) +
                    "\" fill=\"#fff\"/><text x=\"10\" y=\"18\" font-size=\"13\" "
                    "font-weight=\"600\">" +
                    html_escape(title) + "</text>";
  double top = 0;
  for (const auto& b : bars) top = std::max(top, b.second);
  if (top <= 0) top = 1;
  svg += "<g font-size=\"11\">";
  for (std::size_t i = 0; i < bars.size(); ++i) {
    const double y = T + static_cast<double>(i) * (bar + gap);
    const double w = bars[i].second / top * (W - L - R);
    svg += "<text x=\"" + fixed_decimals(L - 6, 1) + "\" y=\"" + fixed_decimals(y + bar - 5, 1) +
           "\" text-anchor=\"end\">" + html_escape(bars[i].first) + "</text>";
    svg += "<rect class=\"bar\" x=\"" + fixed_decimals(L, 1) + "\" y=\"" + fixed_decimals(y, 1) +
           "\" width=\"" + fixed_decimals(w, 1) + "\" height=\"" + fixed_decimals(bar, 1) +
           "\" fill=\"#1f77b4\"/>";
    svg += "<text x=\"" + fixed_decimals(L + w + 4, 1) + "\" y=\"" +
           fixed_decimals(y + bar - 5, 1) + "\">" + value_text(bars[i].second) + "</text>";
  }
  const double axis = T + static_cast<double>(bars.size()) * (bar + gap);
  svg += "<line x1=\"" + fixed_decimals(L, 1) + "\" y1=\"" + fixed_decimals(T - 4, 1) + "\" x2=\"" +
         fixed_decimals(L, 1) + "\" y2=\"" + fixed_decimals(axis, 1) +
         "\" stroke=\"#666\"/><text x=\"" + fixed_decimals((L + W - R) / 2, 1) + "\" y=\"" +
         fixed_decimals(axis + 18, 1) + "\" text-anchor=\"middle\" fill=\"#444\">" +
         html_escape(value_label) + "</text></g>";
  return svg + "</svg>";
}

void add_parameter_importance(HtmlPage& page, const fs::path& summary_file) {
  std::error_code ec;
  if (!fs::is_regular_file(summary_file, ec)) return;
  std::optional<ParameterImportance> importance;
  try {
    importance = read_parameter_importance(summary_file);
  } catch (const Error& e) {
    page.paragraph("parameter importance not shown: " + std::string(e.what()), "note");
    return;
  }
  if (!importance) return;
  const std::string by = importance->evaluator.empty() ? "" : " (" + importance->evaluator + ")";
  page.figure(svg_bar_chart(importance->values, "parameter importance" + by,
                            "share of the objective's variance"),
              "importance of each swept parameter for the objective, largest first (" +
                  summary_file.filename().string() + ")");
  TextTable t;
  t.header = {"parameter", "importance"};
  for (const auto& [name, value] : importance->values) t.rows.push_back({name, value_text(value)});
  page.table(t, "parameter importance" + by);
}

}  // namespace cnclab
