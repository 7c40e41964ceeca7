#include "cnclab/motion/path_grid.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "cnclab/core/error.hpp"

namespace cnclab {

std::vector<double> arc_length_grid(const PlanarPath& path, double spacing, int min_intervals) {
  if (!(spacing > 0.0 && std::isfinite(spacing))) {
    std::ostringstream m;
    m << "arc_length_grid: spacing = " << spacing << " mm: must be > 0 and finite";
    throw Error(m.str());
  }
  const double u0 = path.u_begin(), u1 = path.u_end();
  // Table of cumulative arc length on a parameter grid 8x finer than the
  // target (each piece integrated by Gauss-Legendre); the inverse s -> u is
  // then linear interpolation in the table.
  const double total_estimate = arc_length(path, 256);
  const long table_pieces =
      std::max<long>(64, 8 * static_cast<long>(std::ceil(total_estimate / spacing)));
  std::vector<double> u_table(table_pieces + 1), s_table(table_pieces + 1, 0.0);
  for (long k = 0; k <= table_pieces; ++k) u_table[k] = u0 + (u1 - u0) * k / table_pieces;
  for (long k = 0; k < table_pieces; ++k) {
    s_table[k + 1] = s_table[k] + arc_length(path, u_table[k], u_table[k + 1], 1);
  }
  const double total = s_table.back();
  const int n = std::max(min_intervals, static_cast<int>(std::ceil(total / spacing)));
  std::vector<double> grid(n + 1);
  grid.front() = u0;
  grid.back() = u1;
  long j = 0;
  for (int i = 1; i < n; ++i) {
    const double s = total * i / n;
    while (s_table[j + 1] < s) ++j;
    const double f = (s - s_table[j]) / (s_table[j + 1] - s_table[j]);
    grid[i] = u_table[j] + f * (u_table[j + 1] - u_table[j]);
  }
  return grid;
}

}  // namespace cnclab
