#pragma once
// The optional `slurm:` block of an experiment file or a `kind: sweep` file
// (or of a configs/ fragment they `include:`): defaults of `--slurm`'s
// options, declared once here (core/fields.hpp) for the reader, the checks
// and `cnclab schema`.
//
//   slurm: {partition: short, time: "02:00:00", cpus_per_task: 4, mem: 8G}
//
// Precedence, key by key: a flag given on the command line, else the block
// (a `kind: sweep` file's over its base experiment's), else SlurmOptions'
// defaults. Local runs ignore the block, and it is never part of a result's
// identity: the experiment and sweep readers consume it without emitting it.
#include <filesystem>
#include <string>
#include <vector>

#include "cnclab/core/fields.hpp"
#include "cnclab/sweep/slurm_script.hpp"

namespace cnclab {

// partition, time, cpus_per_task, mem, max_concurrent, tasks, signal.
const FieldList<SlurmOptions>& slurm_fields();

// The `slurm` key as an optional section (for a file's own declarations).
FieldInfo slurm_block_info();

// Reads the `slurm:` block of `file` (its includes merged, `profile`
// applied) over `options`; for a `kind: sweep` file its base experiment's
// block first. ConfigError naming file, key and value for an unknown key, a
// wrong type or a value breaking its rule. No block: `options` unchanged.
void read_slurm_block(const std::filesystem::path& file, const std::string& profile,
                      SlurmOptions& options);

// The options a submission of `file` uses: SlurmOptions' defaults, then the
// file's block, then the keys in `command_line.given` (set on the command
// line) from `command_line`; dry_run always from `command_line`.
SlurmOptions resolve_slurm_options(const SlurmOptions& command_line,
                                   const std::filesystem::path& file, const std::string& profile);

}  // namespace cnclab
