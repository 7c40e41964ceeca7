#pragma once
// Calling Slurm's command-line tools (sbatch, squeue, sacct, scontrol): the
// only way cnclab talks to Slurm, so a cluster needs nothing but its usual
// client commands on PATH (and SLURM_CONF where the site sets it).
#include <optional>
#include <string>
#include <vector>

namespace cnclab {

struct ToolRun {
  int exit_code = 0;  // the tool's exit status; 128 + N when killed by signal N
  std::string out;    // its standard output
  std::string err;    // its standard error
};

// The full path of `name` on PATH (as execvp would find it), nullopt if absent.
std::optional<std::string> find_on_path(const std::string& name);

// Runs argv (argv[0] looked up on PATH) with stdin from /dev/null, waits, and
// returns its exit status and output. Error naming the tool when it is not on
// PATH ("sbatch: not found on PATH (is this a Slurm login node?)") or cannot
// be started.
ToolRun run_tool(const std::vector<std::string>& argv);

// `text` as one word for bash: single-quoted unless it needs no quoting.
std::string shell_quote(const std::string& text);

}  // namespace cnclab
