#include "cnclab/report/html_page.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <optional>

#include "cnclab/core/format.hpp"

namespace cnclab {

namespace {

// Screen and print: system fonts, tables that break across pages by row,
// figures kept whole, no colours needed to read PASS/FAIL (the words say it).
// Printed, numbers do not break inside a cell (7.5 pt, narrow padding: a
// paper table of 11 columns fits a portrait page).
constexpr const char* kStyle = R"(
body{font:15px/1.45 system-ui,-apple-system,"Segoe UI",Roboto,sans-serif;color:#222;max-width:1180px;margin:0 auto;padding:1em 1.5em}
h1{font-size:1.6em;border-bottom:2px solid #444}h2{font-size:1.3em;margin-top:2em;border-bottom:1px solid #bbb}h3{font-size:1.1em}
table.data{border-collapse:collapse;margin:.6em 0 1.2em;font-size:.9em}
table.data th,table.data td{border:1px solid #ccc;padding:.25em .55em;text-align:right;vertical-align:top}
table.data th{background:#f0f0f0}table.data td:first-child,table.data th:first-child{text-align:left}
table.data caption{caption-side:top;text-align:left;font-weight:600;padding:.2em 0}
td.pass{background:#e3f4e3;font-weight:600}td.fail{background:#f9dede;font-weight:600}
figure{margin:1em 0}figcaption{font-size:.85em;color:#555}svg,img.figure{max-width:100%;height:auto}
dl{display:grid;grid-template-columns:max-content auto;gap:.15em 1em;font-size:.9em}dt{font-weight:600}dd{margin:0;word-break:break-all}
p.note{font-size:.85em;color:#555}
nav.contents ul{list-style:none;padding-left:0;columns:2;font-size:.9em}nav.contents li.l3{padding-left:1.5em}
@media print{nav.contents{display:none}body{max-width:none;font-size:10.5pt;padding:0}h2{break-after:avoid}figure,tr{break-inside:avoid}
table.data{font-size:7.5pt}table.data th,table.data td{padding:.1em .3em}table.data td{white-space:nowrap}table.data td:first-child{white-space:normal}td.pass,td.fail{-webkit-print-color-adjust:exact;print-color-adjust:exact}a{color:inherit}}
)";

std::string tick_text(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

constexpr const char* kColours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd",
                                    "#ff7f0e", "#17becf", "#8c564b", "#7f7f7f"};

}  // namespace

std::string html_escape(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string svg_line_chart(const std::vector<ChartSeries>& series, const ChartOptions& o) {
  const double W = 640, H = 300, L = 70, R = 150, T = 30, B = 45;
  bool log_y = o.log_y;
  double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, y0 = x0, y1 = -x0;
  for (const auto& s : series)
    for (const auto& [x, y] : s.points) {
      if (!std::isfinite(x) || !std::isfinite(y)) continue;
      if (y <= 0) log_y = false;
    }
  const auto Y = [&](double y) { return log_y ? std::log10(y) : y; };
  for (const auto& s : series)
    for (const auto& [x, y] : s.points) {
      if (!std::isfinite(x) || !std::isfinite(y)) continue;
      x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, Y(y)), y1 = std::max(y1, Y(y));
    }
  std::string svg =
      "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 640 300\" role=\"img\" "
      "aria-label=\"" +
      html_escape(o.title) + "\" width=\"640\" height=\"300\">";
  svg += "<rect width=\"640\" height=\"300\" fill=\"#fff\"/>";
  svg += "<text x=\"" + fixed_decimals(L, 1) + "\" y=\"18\" font-size=\"13\" font-weight=\"600\">" +
         html_escape(o.title) + "</text>";
  if (!std::isfinite(x0)) return svg + "<text x=\"70\" y=\"150\">no finite values</text></svg>";
  if (x1 == x0) x1 = x0 + 1;
  if (y1 == y0) y1 = y0 + 1;
  const auto px = [&](double x) { return L + (x - x0) / (x1 - x0) * (W - L - R); };
  const auto py = [&](double y) { return H - B - (Y(y) - y0) / (y1 - y0) * (H - T - B); };
  svg += "<g stroke=\"#999\" stroke-width=\"1\"><line x1=\"" + fixed_decimals(L, 1) + "\" y1=\"" +
         fixed_decimals(H - B, 1) + "\" x2=\"" + fixed_decimals(W - R, 1) + "\" y2=\"" +
         fixed_decimals(H - B, 1) + "\"/><line x1=\"" + fixed_decimals(L, 1) + "\" y1=\"" +
         fixed_decimals(T, 1) + "\" x2=\"" + fixed_decimals(L, 1) + "\" y2=\"" +
         fixed_decimals(H - B, 1) + "\"/></g>";
  svg += "<g font-size=\"10\" fill=\"#444\">";
  for (int i = 0; i <= 4; ++i) {
    const double fx = x0 + (x1 - x0) * i / 4, fy = y0 + (y1 - y0) * i / 4;
    const double yv = log_y ? std::pow(10.0, fy) : fy;
    svg += "<text x=\"" + fixed_decimals(px(fx), 1) + "\" y=\"" + fixed_decimals(H - B + 14, 1) +
           "\" text-anchor=\"middle\">" + tick_text(fx) + "</text>";
    svg += "<text x=\"" + fixed_decimals(L - 5, 1) + "\" y=\"" +
           fixed_decimals(H - B - (fy - y0) / (y1 - y0) * (H - T - B) + 3, 1) +
           "\" text-anchor=\"end\">" + tick_text(yv) + "</text>";
  }
  svg += "<text x=\"" + fixed_decimals((L + W - R) / 2, 1) + "\" y=\"" + fixed_decimals(H - 8, 1) +
         "\" text-anchor=\"middle\">" + html_escape(o.x_label) + "</text>";
  svg += "<text transform=\"translate(14 " + fixed_decimals((T + H - B) / 2, 1) +
         ") rotate(-90)\" text-anchor=\"middle\">" +
         html_escape(o.y_label + (log_y ? " (log scale)" : "")) + "</text></g>";
  for (std::size_t k = 0; k < series.size(); ++k) {
    const auto& pts = series[k].points;
    const std::size_t step =
        std::max<std::size_t>(1, (pts.size() + o.max_points - 1) / o.max_points);
    const char* colour = kColours[k % 8];
    // Every step-th point and the last one.
    std::vector<std::size_t> shown;
    for (std::size_t i = 0; i < pts.size(); i += step) shown.push_back(i);
    if (!pts.empty() && shown.back() + 1 != pts.size()) shown.push_back(pts.size() - 1);
    std::string path;
    bool pen = false;
    for (const std::size_t i : shown) {
      const auto [x, y] = pts[i];
      if (!std::isfinite(x) || !std::isfinite(y)) {
        pen = false;
        continue;
      }
      path.append(pen ? "L" : "M")
          .append(fixed_decimals(px(x), 1))
          .append(" ")
          .append(fixed_decimals(py(y), 1));
      pen = true;
    }
    svg +=
        "<path d=\"" + path + "\" fill=\"none\" stroke=\"" + colour + "\" stroke-width=\"1.6\"/>";
    svg += "<rect x=\"" + fixed_decimals(W - R + 10, 1) + "\" y=\"" +
           fixed_decimals(T + 16 * k, 1) + "\" width=\"12\" height=\"3\" fill=\"" + colour +
           "\"/><text x=\"" + fixed_decimals(W - R + 26, 1) + "\" y=\"" +
           fixed_decimals(T + 16 * k + 5, 1) + "\" font-size=\"11\">" +
           html_escape(series[k].name) + "</text>";
  }
  return svg + "</svg>";
}

std::string svg_parallel_coordinates(const std::vector<std::string>& axes,
                                     const std::vector<std::vector<std::string>>& rows,
                                     const std::string& title) {
  const double W = 640, H = 300, T = 40, B = 40, L = 60, R = 60;
  const std::size_t n = axes.size();
  std::string svg =
      "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 640 300\" role=\"img\" "
      "aria-label=\"" +
      html_escape(title) +
      "\" width=\"640\" height=\"300\">"
      "<rect width=\"640\" height=\"300\" fill=\"#fff\"/>"
      "<text x=\"10\" y=\"18\" font-size=\"13\" font-weight=\"600\">" +
      html_escape(title) + "</text>";
  if (n < 2 || rows.empty()) return svg + "</svg>";
  // Each axis: numeric range, or categories in order of first appearance.
  std::vector<std::optional<std::pair<double, double>>> range(n);
  std::vector<std::map<std::string, std::size_t>> category(n);
  const auto parse = [](const std::string& t) -> std::optional<double> {
    char* end = nullptr;
    const double v = std::strtod(t.c_str(), &end);
    if (t.empty() || end != t.c_str() + t.size() || !std::isfinite(v)) return std::nullopt;
    return v;
  };
  for (std::size_t a = 0; a < n; ++a) {
    bool numeric = true;
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const auto& r : rows) {
      if (r[a].empty()) continue;
      const auto v = parse(r[a]);
      if (!v)
        numeric = false;
      else
        lo = std::min(lo, *v), hi = std::max(hi, *v);
      if (!category[a].count(r[a])) category[a].emplace(r[a], category[a].size());
    }
    if (numeric && std::isfinite(lo)) range[a] = std::pair(lo, hi == lo ? lo + 1 : hi);
  }
  const auto ax = [&](std::size_t a) { return L + (W - L - R) * a / (n - 1); };
  const auto ay = [&](std::size_t a, const std::string& t) -> std::optional<double> {
    if (t.empty()) return std::nullopt;
    double f = 0.5;
    if (range[a]) {
      f = (*parse(t) - range[a]->first) / (range[a]->second - range[a]->first);
    } else if (category[a].size() > 1) {
      f = static_cast<double>(category[a].at(t)) / static_cast<double>(category[a].size() - 1);
    }
    return H - B - f * (H - T - B);
  };
  svg += "<g fill=\"none\" stroke-width=\"1.2\" stroke-opacity=\"0.7\">";
  for (std::size_t i = 0; i < rows.size(); ++i) {
    std::string path;
    bool pen = false;
    for (std::size_t a = 0; a < n; ++a) {
      const auto y = ay(a, rows[i][a]);
      if (!y) {
        pen = false;
        continue;
      }
      path.append(pen ? "L" : "M")
          .append(fixed_decimals(ax(a), 1))
          .append(" ")
          .append(fixed_decimals(*y, 1));
      pen = true;
    }
    // The first rows (best ranked) drawn darkest.
    svg += "<path d=\"" + path + "\" stroke=\"" + (i == 0 ? "#d62728" : "#1f77b4") + "\"/>";
  }
  svg += "</g><g font-size=\"10\" fill=\"#333\" stroke=\"none\">";
  for (std::size_t a = 0; a < n; ++a) {
    svg += "<line x1=\"" + fixed_decimals(ax(a), 1) + "\" y1=\"" + fixed_decimals(T, 1) +
           "\" x2=\"" + fixed_decimals(ax(a), 1) + "\" y2=\"" + fixed_decimals(H - B, 1) +
           "\" stroke=\"#666\"/>";
    svg += "<text x=\"" + fixed_decimals(ax(a), 1) + "\" y=\"" + fixed_decimals(H - B + 16, 1) +
           "\" text-anchor=\"middle\">" + html_escape(axes[a]) + "</text>";
    const std::string lo = range[a] ? tick_text(range[a]->first)
                                    : (category[a].empty() ? "" : category[a].begin()->first);
    std::string hi = range[a] ? tick_text(range[a]->second) : "";
    for (const auto& [text, index] : category[a]) {
      if (!range[a] && index + 1 == category[a].size() && index > 0) hi = text;
    }
    svg += "<text x=\"" + fixed_decimals(ax(a) + 3, 1) + "\" y=\"" + fixed_decimals(H - B - 2, 1) +
           "\">" + html_escape(lo) + "</text>";
    svg += "<text x=\"" + fixed_decimals(ax(a) + 3, 1) + "\" y=\"" + fixed_decimals(T + 8, 1) +
           "\">" + html_escape(hi) + "</text>";
  }
  return svg + "</g></svg>";
}

HtmlPage::HtmlPage(std::string title) : title_(std::move(title)) {}

void HtmlPage::heading(int level, const std::string& text, const std::string& id) {
  level = std::clamp(level, 1, 4);
  const bool listed = level == 2 || level == 3;
  const std::string anchor =
      id.empty() && listed ? "section-" + std::to_string(contents_.size() + 1) : id;
  std::string h = "h";
  h += static_cast<char>('0' + level);
  body_.append("<").append(h);
  if (!anchor.empty()) body_.append(" id=\"").append(html_escape(anchor)).append("\"");
  body_.append(">").append(html_escape(text)).append("</").append(h).append(">\n");
  if (level == 1) contents_at_ = body_.size();
  if (listed) contents_.push_back({level, text, anchor});
}

void HtmlPage::paragraph(const std::string& text, const std::string& css_class) {
  body_ += "<p" + (css_class.empty() ? std::string() : " class=\"" + css_class + "\"") + ">" +
           html_escape(text) + "</p>\n";
}

void HtmlPage::table(const TextTable& t, const std::string& caption) {
  body_ += "<table class=\"data\">";
  if (!caption.empty()) body_ += "<caption>" + html_escape(caption) + "</caption>";
  body_ += "<thead><tr>";
  for (const auto& h : t.header) body_ += "<th>" + html_escape(h) + "</th>";
  body_ += "</tr></thead><tbody>\n";
  for (const auto& row : t.rows) {
    body_ += "<tr>";
    for (const auto& cell : row) {
      const char* cls =
          cell == "PASS" ? " class=\"pass\"" : (cell == "FAIL" ? " class=\"fail\"" : "");
      body_ += std::string("<td") + cls + ">" + html_escape(cell) + "</td>";
    }
    body_ += "</tr>\n";
  }
  body_ += "</tbody></table>\n";
}

void HtmlPage::figure(const std::string& svg, const std::string& caption) {
  body_ += "<figure>" + svg + "<figcaption>" + html_escape(caption) + "</figcaption></figure>\n";
}

void HtmlPage::definitions(const std::vector<std::pair<std::string, std::string>>& items) {
  body_ += "<dl>";
  for (const auto& [k, v] : items)
    body_ += "<dt>" + html_escape(k) + "</dt><dd>" + html_escape(v) + "</dd>";
  body_ += "</dl>\n";
}

std::string HtmlPage::html() const {
  std::string body = body_;
  if (contents_.size() >= 2) {
    std::string nav = "<nav class=\"contents\" aria-label=\"contents\"><ul>";
    for (const auto& e : contents_) {
      nav += "<li class=\"l" + std::to_string(e.level) + "\"><a href=\"#" + html_escape(e.id) +
             "\">" + html_escape(e.text) + "</a></li>";
    }
    body.insert(contents_at_, nav + "</ul></nav>\n");
  }
  return "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
         "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">"
         "<title>" +
         html_escape(title_) + "</title><style>" + kStyle + "</style></head>\n<body>\n" + body +
         "</body></html>\n";
}

}  // namespace cnclab
