#pragma once
// Memory checks before large allocations: a dataset or network that cannot
// fit is a ResourceError naming the size, not a std::bad_alloc or an OOM kill.
#include <cstdint>
#include <string>

namespace cnclab {

// The memory this process may use: the smaller of physical RAM and the
// address-space / data-segment limits (RLIMIT_AS, RLIMIT_DATA) when set.
std::uint64_t memory_budget_bytes();

// Throws ResourceError "<what> needs about <bytes> of memory but only
// <budget> is available" when bytes exceed the budget. `bytes` is a double
// so estimates cannot overflow.
void check_memory(double bytes, const std::string& what);

// "1.5 GiB", "12 KiB", "7.3 TiB".
std::string format_bytes(double bytes);

}  // namespace cnclab
