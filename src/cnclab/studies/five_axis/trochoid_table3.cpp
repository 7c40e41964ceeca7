#include "cnclab/studies/five_axis/trochoid_table3.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "cnclab/core/error.hpp"
#include "cnclab/core/format.hpp"
#include "cnclab/core/units.hpp"
#include "cnclab/kinematics/gcode.hpp"
#include "cnclab/kinematics/trochoid_fit.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

// RMS of the rounding error of a point given to 4 decimals in x and y:
// sqrt(2) * 1e-4 / sqrt(12) (uniform rounding error per coordinate).
const double kTable3RoundingRms = std::sqrt(2.0) * 1e-4 / std::sqrt(12.0);

struct Table3Row {
  double t = 0, x = 0, y = 0;
  int line = 0;
  std::string coordinates;
};

std::vector<Table3Row> read_table3(const fs::path& file) {
  std::ifstream in(file);
  if (!in) throw IoError(file.string() + ": cannot read (the transcribed Table 3)");
  std::vector<Table3Row> rows;
  std::string line;
  int number = 0;
  bool header = true;
  while (std::getline(in, line)) {
    ++number;
    if (line.empty() || line[0] == '#') continue;
    if (header) {
      header = false;
      if (line != "t,x,y,line,coordinates") {
        throw IoError(file.string() + ":" + std::to_string(number) +
                      ": expected the header t,x,y,line,coordinates");
      }
      continue;
    }
    std::stringstream ss(line);
    std::string field[5];
    for (int i = 0; i < 5; ++i) std::getline(ss, field[i], i < 4 ? ',' : '\n');
    try {
      Table3Row r;
      r.t = std::stod(field[0]);
      r.x = std::stod(field[1]);
      r.y = std::stod(field[2]);
      r.line = std::stoi(field[3]);
      r.coordinates = field[4];
      if (!std::isfinite(r.t) || !std::isfinite(r.x) || !std::isfinite(r.y)) throw std::exception();
      rows.push_back(r);
    } catch (const std::exception&) {
      throw IoError(file.string() + ":" + std::to_string(number) +
                    ": not a row t,x,y,line,coordinates: " + line);
    }
  }
  if (rows.size() < 8) throw IoError(file.string() + ": needs at least 8 rows to fit a trochoid");
  return rows;
}

std::string parameters_text(const TrochoidParameters& p) {
  // Shown in (-180, 180].
  const double phase_deg =
      p.phase * kDegPerRad <= -180.0 + 1e-9 ? p.phase * kDegPerRad + 360.0 : p.phase * kDegPerRad;
  return "x0 " + fixed_decimals(p.x0, 4) + " mm, y0 " + fixed_decimals(p.y0, 4) + " mm, V (" +
         fixed_decimals(p.vx, 5) + ", " + fixed_decimals(p.vy, 5) + ") mm/unit t, R " +
         fixed_decimals(p.radius, 4) + " mm, w " + fixed_decimals(p.omega, 5) +
         " rad/unit t, phi " + fixed_decimals(phase_deg, 2) +
         " deg; advance per turn 2 pi |V| / w = " + fixed_decimals(advance_per_turn(p), 4) + " mm";
}

}  // namespace

void compare_with_table3(const fs::path& file, double our_radius, std::ostream& out) {
  const auto rows = read_table3(file);
  std::vector<double> t;
  std::vector<Eigen::Vector2d> pts;
  int inconsistent = 0;
  for (const auto& r : rows) {
    t.push_back(r.t);
    pts.emplace_back(r.x, r.y);
    if (coordinate_words({r.x, r.y}, 3) != r.coordinates) ++inconsistent;
  }
  const TrochoidFit free_fit = fit_trochoid(t, pts);
  const TrochoidFit fixed_fit = fit_trochoid(t, pts, our_radius);
  // The round values the free fit points to (2 decimals; phase to 45 deg;
  // advance direction to a quarter turn), checked point by point.
  TrochoidParameters round;
  round.x0 = std::round(free_fit.parameters.x0 * 100) / 100;
  round.y0 = std::round(free_fit.parameters.y0 * 100) / 100;
  round.radius = std::round(free_fit.parameters.radius * 100) / 100;
  round.omega = std::round(free_fit.parameters.omega * 100) / 100;
  round.phase =
      std::round(free_fit.parameters.phase / (std::numbers::pi / 4)) * (std::numbers::pi / 4);
  const double advance = std::round(advance_per_turn(free_fit.parameters) * 100) / 100;
  const double direction = std::atan2(free_fit.parameters.vy, free_fit.parameters.vx);
  const double quarter = std::round(direction / (std::numbers::pi / 2)) * (std::numbers::pi / 2);
  round.vx = advance * round.omega / (2 * std::numbers::pi) * std::cos(quarter);
  round.vy = advance * round.omega / (2 * std::numbers::pi) * std::sin(quarter);
  double round_max = 0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const Eigen::Vector2d m = trochoid_model(round, t[i]);
    round_max = std::max({round_max, std::abs(m.x() - pts[i].x()), std::abs(m.y() - pts[i].y())});
  }
  out << "\nSeed 004 Table 3 against Eq. 6 (" << file.string() << ", " << rows.size()
      << " points, t = " << shortest_double(rows.front().t) << " .. "
      << shortest_double(rows.back().t) << ")\n"
      << "- Its Coordinates column is x(t), y(t) rounded to 3 decimals: "
      << (inconsistent == 0 ? "yes, in every row"
                            : "NO, in " + std::to_string(inconsistent) + " rows")
      << ".\n"
      << "- Least-squares fit of Eq. 6 with an offset, a phase and the advance in any direction, "
         "x = x0 + Vx t + R cos(w t + phi), y = y0 + Vy t + R sin(w t + phi):\n    "
      << parameters_text(free_fit.parameters) << "\n    RMS residual "
      << fixed_decimals(free_fit.rms * 1e3, 3) << " um, max "
      << fixed_decimals(free_fit.max_residual * 1e3, 3) << " um (4-decimal rounding alone: about "
      << fixed_decimals(kTable3RoundingRms * 1e3, 3) << " um RMS)\n"
      << "- The same with R fixed at this groove's R = " << shortest_double(our_radius)
      << " mm: RMS " << fixed_decimals(fixed_fit.rms * 1e3, 3) << " um\n";
  if (free_fit.rms < 3 * kTable3RoundingRms) {
    out << "- Table 3 IS Eq. 6 at the table's precision, with the round values\n    "
        << parameters_text(round) << "\n    (largest coordinate deviation "
        << fixed_decimals(round_max * 1e3, 3)
        << " um; the table's rounding is 0.05 um): the advance "
        << "runs along " << (std::abs(std::sin(quarter)) > 0.5 ? "y" : "x")
        << ", not along x as Eq. 6 writes it, and is " << shortest_double(advance)
        << " mm per turn, not Table 2's step of 1.5 mm.\n";
  } else {
    out << "- The best residual is " << fixed_decimals(free_fit.rms / kTable3RoundingRms, 0)
        << " times the rounding level: NO trochoid of the Eq. 6 family reproduces Table 3.\n";
  }
}

}  // namespace cnclab
