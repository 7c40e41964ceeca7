#pragma once
// Fake Slurm client commands for tests without a cluster (slurm_cli_test.cpp,
// reproduce_slurm_test.cpp): scripts on PATH that answer as a cluster would
// and log how they were called.
#include <filesystem>
#include <fstream>
#include <string>

namespace cnclab::testing {

namespace fs = std::filesystem;

// The binary under test and the small experiment both Slurm CLI tests sweep
// (CNCLAB_BINARY_DIR, CNCLAB_SOURCE_DIR: the test target's definitions).
inline const std::string kSlurmTestCnclab = CNCLAB_BINARY_DIR "/cnclab";
inline const std::string kSlurmTestExperiment =
    CNCLAB_SOURCE_DIR "/experiments/friedman/friedman1_mlp.yaml";

inline void write_tool(const fs::path& bin, const std::string& name, const std::string& body) {
  fs::create_directories(bin);
  std::ofstream(bin / name) << "#!/bin/bash\n" << body << "\n";
  fs::permissions(bin / name, fs::perms::owner_all);
}

// Fake Slurm clients in dir/bin: sbatch answers job ids 100, 101, ... (and
// logs its arguments), squeue prints dir/queue.txt, scontrol and scancel log.
inline std::string fake_slurm(const fs::path& dir) {
  const fs::path bin = dir / "bin";
  write_tool(bin, "sbatch",
             "n=$(cat " + (dir / "next_id").string() +
                 " 2>/dev/null || echo 100)\n"
                 "echo $((n + 1)) > " +
                 (dir / "next_id").string() +
                 "\n"
                 "echo \"sbatch $*\" >> " +
                 (dir / "calls.txt").string() + "\necho $n");
  write_tool(bin, "squeue", "cat " + (dir / "queue.txt").string() + " 2>/dev/null; exit 0");
  write_tool(bin, "sacct", "echo 'Slurm accounting storage is disabled' >&2; exit 1");
  for (const char* tool : {"scontrol", "scancel"}) {
    write_tool(bin, tool,
               std::string("echo \"") + tool + " $*\" >> " + (dir / "calls.txt").string());
  }
  return "PATH='" + bin.string() + ":/usr/bin:/bin' ";
}

}  // namespace cnclab::testing
