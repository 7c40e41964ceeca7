#pragma once
// Generated datasets cached as HDF5 files under a cache folder, keyed by the
// generator, its resolved options and its seed: a later run asking for the
// same dataset reads it instead of generating it again.
#include <cstdint>
#include <filesystem>
#include <ostream>
#include <string>

#include "cnclab/data/dataset.hpp"
#include "cnclab/data/dataset_spec.hpp"

namespace cnclab {

struct CachedDataset {
  Dataset dataset;
  std::filesystem::path path;
  std::string content_hash;
  bool reused = false;
};

// Generates the dataset `spec` describes with generator seed `seed`.
Dataset generate_dataset(const DatasetSpec& spec, std::uint64_t seed,
                         const ProgressCallback& progress = {});

// The generator_config text stored in a dataset and hashed into its cache
// key: the generator's resolved options, its version and the seed.
std::string dataset_config_text(const DatasetGenerator& generator, std::uint64_t seed);

// Where obtain_dataset keeps the dataset: <dir>/<generator>-<16 hex>.h5.
std::filesystem::path dataset_cache_file(const DatasetSpec& spec, std::uint64_t seed,
                                         const std::filesystem::path& dir);

// <dir>/<generator>-<16 hex digits>.h5, the hash covering generator name,
// version, options and seed. A cached file that fails to read (corrupt, partial,
// tampered) or was made by another generator config is regenerated, and so is
// every file when `regenerate` is set.
//
// Concurrent callers (parallel sweep trials, shards, Slurm jobs on several
// nodes sharing the cache folder, several `cnclab run`s) produce a dataset
// once: whoever misses the cache takes the lock file
// <dir>/.<generator>-<hash>.lock (io/lock_file.hpp: O_EXCL, which holds on
// NFS where flock(2) may not; it names the holder's host and pid), checks
// the cache again, and only then generates; the others wait and read the
// file it wrote. The lock file is removed when done; one left by a process
// killed on this host is removed by the next caller. The dataset file itself is written
// atomically (temporary + rename), so a reader never sees a torn dataset.
// `progress` (optional) hears of the generation's stages when it generates.
CachedDataset obtain_dataset(const DatasetSpec& spec, std::uint64_t seed,
                             const std::filesystem::path& dir, std::ostream* log,
                             bool regenerate = false, const ProgressCallback& progress = {});

}  // namespace cnclab
