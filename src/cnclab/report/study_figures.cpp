#include "cnclab/report/study_figures.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "cnclab/core/error.hpp"

namespace cnclab {
namespace fs = std::filesystem;

namespace {

std::uint32_t big_endian32(const std::string& b, std::size_t at) {
  std::uint32_t v = 0;
  for (std::size_t i = 0; i < 4; ++i) v = (v << 8) | static_cast<unsigned char>(b[at + i]);
  return v;
}

std::string read_bytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw IoError(file.string() + ": cannot read");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Shown at 1.5x the size the figure was drawn for (a 7 in figure at 1008 px
// of a 1280 px window; 8 pt text at 16 px), at most the page width (CSS).
constexpr double kCssPixelsPerInch = 144;

}  // namespace

std::string base64_encode(const std::string& bytes) {
  static constexpr char kAlphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::size_t n = std::min<std::size_t>(3, bytes.size() - i);
    std::uint32_t v = 0;
    for (std::size_t k = 0; k < 3; ++k)
      v = (v << 8) | (k < n ? static_cast<unsigned char>(bytes[i + k]) : 0u);
    for (std::size_t k = 0; k < 4; ++k) out += k <= n ? kAlphabet[(v >> (18 - 6 * k)) & 63] : '=';
  }
  return out;
}

std::optional<PngInfo> png_info(const std::string& b) {
  // PNG signature, then IHDR (width, height) first (PNG spec, section 5.6).
  static const std::string kSignature = "\x89PNG\r\n\x1a\n";
  if (b.size() < 33 || b.compare(0, 8, kSignature) != 0 || b.compare(12, 4, "IHDR") != 0)
    return std::nullopt;
  PngInfo info{big_endian32(b, 16), big_endian32(b, 20), 0};
  // pHYs: pixels per unit x, y and the unit (1 = metre); before IDAT.
  for (std::size_t at = 8; at + 12 <= b.size();) {
    const std::uint32_t length = big_endian32(b, at);
    const std::string type = b.substr(at + 4, 4);
    if (type == "IDAT" || type == "IEND") break;
    if (type == "pHYs" && length == 9 && at + 17 <= b.size() && b[at + 16] == 1) {
      info.dpi = big_endian32(b, at + 8) * 0.0254;
    }
    at += 12 + static_cast<std::size_t>(length);
  }
  return info;
}

std::size_t add_study_figures(HtmlPage& page, const StudyFigureOptions& o) {
  if (o.topics.empty()) return 0;
  page.heading(3, "Figures", o.anchor);
  std::size_t embedded = 0, used = 0;
  for (const auto& topic : o.topics) {
    const fs::path dir = o.figures_dir / topic;
    std::vector<fs::path> files;
    std::error_code ec;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
      const fs::path& p = it->path();
      // Not the scripts' temporary files (".NAME.partial.png").
      if (p.extension() == ".png" && p.filename().string().front() != '.') files.push_back(p);
    }
    std::sort(files.begin(), files.end());
    if (files.empty()) {
      page.paragraph("No figures in " + dir.string() + " (not drawn yet): " + o.draw_command +
                         " draws them from the results.",
                     "note");
      continue;
    }
    for (const auto& f : files) {
      const std::string bytes = read_bytes(f);
      const auto info = png_info(bytes);
      if (!info) {
        page.paragraph(f.string() + ": not a PNG file; left out.", "note");
        continue;
      }
      const std::string data = base64_encode(bytes);
      if (used + data.size() > o.budget_bytes) {
        page.paragraph(f.string() + ": left out to keep the page small (" +
                           std::to_string(bytes.size() / 1024) + " kB); open the file.",
                       "note");
        continue;
      }
      used += data.size();
      ++embedded;
      std::string size;
      if (info->dpi > 0) {
        const auto css = [&](std::size_t px) {
          return std::to_string(static_cast<long>(std::lround(px * kCssPixelsPerInch / info->dpi)));
        };
        size = " width=\"" + css(info->width) + "\" height=\"" + css(info->height) + "\"";
      }
      std::string caption = topic + "/" + f.filename().string();
      if (o.newest_source && fs::last_write_time(f, ec) < *o.newest_source && !ec) {
        caption +=
            " — drawn before the newest result behind the tables above: it may be out of "
            "date (" +
            o.draw_command + " draws it again)";
      }
      page.figure("<img class=\"figure\" src=\"data:image/png;base64," + data + "\" alt=\"" +
                      html_escape(topic + " " + f.stem().string()) + "\"" + size + ">",
                  caption);
    }
  }
  return embedded;
}

}  // namespace cnclab
