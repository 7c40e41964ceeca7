#include "cnclab/deploy/prediction_file.hpp"

#include "cnclab/core/error.hpp"
#include "cnclab/deploy/csv_table.hpp"
#include "cnclab/io/atomic_file.hpp"
#include "cnclab/io/eigen_std.hpp"
#include "cnclab/io/file_format.hpp"
#include "cnclab/io/h5.hpp"
#include "cnclab/io/provenance.hpp"

namespace cnclab {
namespace fs = std::filesystem;

void check_prediction_path(const fs::path& out) {
  const std::string ext = out.extension().string();
  if (ext != ".h5" && ext != ".csv") {
    throw ConfigError("-o " + out.string() + ": the output is a .h5 or a .csv file");
  }
}

std::vector<std::pair<std::string, std::string>> prediction_provenance(const DeployedModel& m,
                                                                       const PredictionInput& in,
                                                                       const PredictOptions& o,
                                                                       const Prediction& p) {
  const Provenance now = make_provenance(0);  // this cnclab's version and commit
  return {{"result_file", m.result_file},
          {"result_identity", m.identity},
          {"experiment", m.experiment},
          {"config_hash", m.config_hash},
          {"input", in.source},
          {"input_kind", to_string(in.kind)},
          {"input_hash", in.hash},
          {"split", o.split},
          {"initial_state", p.initial_state.empty() ? "-" : p.initial_state},
          {"first_step", std::to_string(p.first_step)},
          {"samples", std::to_string(p.samples)},
          {"cnclab_version", now.cnclab_version},
          {"git_commit", now.git_commit},
          {"created_utc", now.start_utc}};
}

void write_prediction(const fs::path& out, const DeployedModel& m, const PredictionInput& in,
                      const PredictOptions& o, const Prediction& p) {
  check_prediction_path(out);
  const auto provenance = prediction_provenance(m, in, o, p);
  if (out.extension() == ".csv") {
    std::vector<std::string> comments = {"cnclab predict"};
    for (const auto& [key, value] : provenance) comments.push_back(key + ": " + value);
    write_text_atomically(out, csv_text(comments, p.columns));
    return;
  }
  AtomicOutput file(out);
  try {
    H5File f = H5File::create(file.temp_path());
    write_format(f, kPredictionFormat, kPredictionFormatVersion);
    f.create_group("/provenance");
    for (const auto& [key, value] : provenance) f.set_attribute("/provenance", key, value);
    std::vector<std::string> names;
    for (const auto& c : p.columns) {
      names.push_back(c.name);
      f.write_vector("/predictions/" + c.name, to_std(c.values), c.unit);
    }
    f.write_strings("/columns", names);
    mark_complete(f);
    f.close();
    file.commit();
  } catch (const IoError& e) {
    throw IoError(out.string() + ": prediction not written: " + std::string(e.what()));
  }
}

}  // namespace cnclab
