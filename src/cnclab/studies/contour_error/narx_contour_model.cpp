#include "cnclab/studies/contour_error/narx_contour_model.hpp"

#include "cnclab/core/error.hpp"
#include "cnclab/data/dataset_cache.hpp"

namespace cnclab {
namespace {

NarxAxisModel contour_model_axis(const NarxRecord& narx, const std::string& axis,
                                 const ColumnRange& v, const ColumnRange& e_um,
                                 const std::string& result_file) {
  for (const NarxNetworkRecord& net : narx.networks) {
    if (net.axis != axis) continue;
    return {
        narx.options, net.parameters,
        MinMaxNormaliser(Eigen::VectorXd::Constant(1, v.min), Eigen::VectorXd::Constant(1, v.max)),
        MinMaxNormaliser(Eigen::VectorXd::Constant(1, e_um.min * 1e-3),
                         Eigen::VectorXd::Constant(1, e_um.max * 1e-3))};
  }
  throw Error(result_file + ": no network for axis " + axis +
              " (a seed-002 narx result has x and y)");
}

}  // namespace

ContourPredictor contour_predictor_from(const RunRecord& r, const FollowingErrorRanges& ranges,
                                        const std::string& result_file) {
  if (!r.narx) throw Error(result_file + ": not a narx result (model.type narx)");
  return ContourPredictor(
      contour_model_axis(*r.narx, "x", ranges.velocity[0], ranges.following_error[0], result_file),
      contour_model_axis(*r.narx, "y", ranges.velocity[1], ranges.following_error[1], result_file));
}

TrainedContourModel load_trained_contour_model(const std::filesystem::path& narx_experiment,
                                               const std::filesystem::path& results_dir,
                                               const std::filesystem::path& data_dir,
                                               const std::string& profile, std::ostream* log) {
  TrainedContourModel m;
  m.upstream = load_upstream(narx_experiment, results_dir, profile);
  const std::string file = m.upstream.result_file.string();
  const ExperimentSpec& spec = m.upstream.experiment.spec;
  const auto* generator =
      dynamic_cast<const FollowingErrorGenerator*>(spec.dataset.generator.get());
  if (generator == nullptr || !m.upstream.record.narx) {
    throw ConfigError(narx_experiment.string() +
                      ": needs a narx experiment on the following_error dataset (seed 002)");
  }
  m.dataset = generator->options();
  const std::uint64_t seed = generator_seed(spec);
  const CachedDataset cached = obtain_dataset(spec.dataset, seed, data_dir, log);
  m.ranges = following_error_ranges(cached.dataset);
  Rng rng(seed);  // the generator's first draw is the path (following_error.cpp)
  m.path = std::make_unique<NurbsPlanarPath>(random_planar_nurbs(m.dataset.path, rng));
  const auto rms = m.upstream.record.metrics.find("validation.contour_rms");  // narx_metrics.hpp
  m.contour_rms = rms == m.upstream.record.metrics.end() ? 0.0 : rms->second * 1e-3;
  return m;
}

}  // namespace cnclab
