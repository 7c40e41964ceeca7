#pragma once
// Text forms of numbers that configs, dataset files and messages share.
#include <string>
#include <string_view>
#include <vector>

namespace cnclab {

// The shortest decimal text (printf %g, 1 to 17 significant digits) that
// reads back to exactly `x`: 0.1 -> "0.1", 1e-05 -> "1e-05"; whole numbers
// below 1e15 keep their digits: 2000 -> "2000".
std::string shortest_double(double x);

// printf's %.<decimals>f: fixed_decimals(-4.00004, 3) -> "-4.000".
std::string fixed_decimals(double x, int decimals);

// The items separated by `sep`: join({"a", "b"}, ", ") -> "a, b".
std::string join(const std::vector<std::string>& items, std::string_view sep);

}  // namespace cnclab
