#include "cli/schema_command.hpp"

#include "cnclab/experiment/experiment_schema.hpp"
#include "cnclab/sweep/slurm_fields.hpp"
#include "cnclab/sweep/sweep_fields.hpp"

namespace cnclab {

int schema_command(const std::string& kind, std::ostream& out) {
  out << experiment_file_schema(kind, sweep_fields().info(), slurm_fields().info()).dump(2) << "\n";
  return 0;
}

}  // namespace cnclab
