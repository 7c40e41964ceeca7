#include "cnclab/kinematics/gcode.hpp"

#include <cmath>
#include <cstdio>

#include "cnclab/core/error.hpp"
#include "cnclab/core/format.hpp"

namespace cnclab {
namespace {

std::string fixed(double v, int decimals) {
  std::string s = fixed_decimals(v, decimals);
  // "-0.000" -> "0.000": a rounded zero has no sign.
  if (s[0] == '-' && s.find_first_not_of("-0.") == std::string::npos) s.erase(0, 1);
  return s;
}

// Concatenation by appending (gcc 12's -Wrestrict misfires on "literal" + string).
template <class... Parts>
std::string cat(const Parts&... parts) {
  std::string s;
  (s += ... += parts);
  return s;
}

std::string feed_word(double f) {
  return cat("F", fixed(f, 0), ".");
}

// The entry ends at (start, cut_z) and starts between cut_z and safe_z.
void check_entry(std::span<const Eigen::Vector3d> entry, const Eigen::Vector2d& start,
                 const GcodeOptions& o) {
  for (std::size_t i = 0; i < entry.size(); ++i) {
    if (!entry[i].allFinite())
      throw Error("G-code: entry point " + std::to_string(i) + " is not finite");
  }
  const Eigen::Vector3d& last = entry.back();
  if (entry.size() < 2 || (last.head<2>() - start).norm() > 1e-9 ||
      std::abs(last.z() - o.cut_z) > 1e-9) {
    throw Error("G-code: the entry must have >= 2 points and end at the path's start at cut_z");
  }
  if (!(entry[0].z() > o.cut_z && entry[0].z() < o.safe_z)) {
    throw Error("G-code: the entry must start between cut_z and safe_z");
  }
}

}  // namespace

void GcodeOptions::validate() const {
  if (program_number < 1 || program_number > 9999) {
    throw OptionError("program_number", std::to_string(program_number), "must be in [1, 9999]");
  }
  if (title.find_first_of("()") != std::string::npos) {
    throw OptionError("title", title, "must not contain parentheses (G-code comment delimiters)");
  }
  for (const auto& [v, field] : {std::pair{feed, "feed"}, std::pair{plunge_feed, "plunge_feed"},
                                 std::pair{spindle_speed, "spindle_speed"}}) {
    if (!(v > 0) || !std::isfinite(v)) {
      throw OptionError(field, shortest_double(v), "must be a finite number > 0");
    }
  }
  if (!std::isfinite(safe_z) || !std::isfinite(cut_z) || !(cut_z < safe_z)) {
    throw OptionError("cut_z", shortest_double(cut_z),
                      "must be finite and below safe_z " + shortest_double(safe_z));
  }
  if (line_increment < 1 || line_increment > 1000) {
    throw OptionError("line_increment", std::to_string(line_increment), "must be in [1, 1000]");
  }
  if (decimals < 0 || decimals > 6) {
    throw OptionError("decimals", std::to_string(decimals), "must be in [0, 6]");
  }
}

std::string coordinate_words(const Eigen::Vector2d& p, int decimals) {
  return cat("X", fixed(p.x(), decimals), " Y", fixed(p.y(), decimals));
}

GcodeProgram write_gcode(std::span<const Eigen::Vector2d> path, const GcodeOptions& o,
                         std::span<const Eigen::Vector3d> entry) {
  o.validate();
  if (path.size() < 2) throw Error("G-code: the path needs at least 2 points");
  for (std::size_t i = 0; i < path.size(); ++i) {
    if (!path[i].allFinite())
      throw Error("G-code: path point " + std::to_string(i) + " is not finite");
  }
  GcodeProgram prog;
  std::string& s = prog.text;
  int n = 0;
  const auto block = [&](const std::string& words) {
    n += o.line_increment;
    s += cat("N", std::to_string(n), " ", words, "\n");
    return n;
  };
  char onum[16];
  std::snprintf(onum, sizeof onum, "O%04d", o.program_number);
  s += "%\n";
  s += cat(onum, o.title.empty() ? "" : cat(" (", o.title, ")"), "\n");
  block("G21 G17 G90 G94 (mm, XY plane, absolute, feed per minute)");
  block(cat("G00 Z", fixed(o.safe_z, o.decimals)));
  block(cat("S", fixed(o.spindle_speed, 0), " M03"));
  if (entry.empty()) {
    prog.point_line_numbers.push_back(block(cat("G00 ", coordinate_words(path[0], o.decimals))));
    block(cat("G01 Z", fixed(o.cut_z, o.decimals), " ", feed_word(o.plunge_feed)));
  } else {
    check_entry(entry, path[0], o);
    block(cat("G00 ", coordinate_words(entry[0].head<2>(), o.decimals)));
    block(cat("G00 Z", fixed(entry[0].z(), o.decimals)));
    int last = 0;
    for (std::size_t i = 1; i < entry.size(); ++i) {
      last = block(cat("G01 ", coordinate_words(entry[i].head<2>(), o.decimals), " Z",
                       fixed(entry[i].z(), o.decimals),
                       i == 1 ? cat(" ", feed_word(o.plunge_feed)) : ""));
    }
    prog.point_line_numbers.push_back(last);
  }
  for (std::size_t i = 1; i < path.size(); ++i) {
    prog.point_line_numbers.push_back(block(cat("G01 ", coordinate_words(path[i], o.decimals),
                                                i == 1 ? cat(" ", feed_word(o.feed)) : "")));
  }
  block(cat("G00 Z", fixed(o.safe_z, o.decimals), " (safe retract)"));
  block("M05");
  block("M30");
  s += "%\n";
  return prog;
}

}  // namespace cnclab
