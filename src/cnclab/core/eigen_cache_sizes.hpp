#pragma once
// Eigen picks its GEMM block sizes from the cache sizes it reads from the
// CPU, and the block sizes set the order of the sums, so products would
// differ in the last bits between machines with different caches. cnclab sets
// these fixed sizes at start for every copy of Eigen in the program
// (core/isa.cpp; each instruction-set level's kernels, nn/kernels_level.cpp):
// what Eigen 3.4 reads on the AMD EPYC machine the project's reference
// results come from, so those results keep their bits. No includes: the
// kernel translation units include this with a renamed Eigen.
namespace cnclab {

inline constexpr long kEigenL1CacheBytes = 32768;
inline constexpr long kEigenL2CacheBytes = 1048576;
inline constexpr long kEigenL3CacheBytes = 335544320;

}  // namespace cnclab
