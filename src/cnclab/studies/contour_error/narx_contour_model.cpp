#include "cnclab/studies/contour_error/narx_contour_model.hpp"

#include "cnclab/core/error.hpp"
#include "cnclab/data/dataset_cache.hpp"

namespace cnclab {
namespace {

// The network of `axis` with its channels' normalisation; the direction
// features of its channels after v into `extra` (the same for x and y).
NarxAxisModel contour_model_axis(const NarxRecord& narx, const std::string& axis,
                                 const ColumnRange& v, const ColumnRange& e_um,
                                 const std::string& result_file, std::vector<AxisFeature>& extra) {
  for (const NarxNetworkRecord& net : narx.networks) {
    if (net.axis != axis) continue;
    const auto fail = [&](const std::string& why) {
      throw Error(result_file + ": network " + axis + ": " + why);
    };
    if (net.inputs.empty() || net.inputs[0] != "v_" + axis) {
      fail("its first input must be v_" + axis + " (the reference velocity)");
    }
    const auto c = static_cast<Eigen::Index>(net.inputs.size());
    // Velocity by the dataset's mapminmax range; the features are in [-1, 1].
    Eigen::VectorXd lo = Eigen::VectorXd::Constant(c, -1.0), hi = Eigen::VectorXd::Ones(c);
    lo[0] = v.min;
    hi[0] = v.max;
    std::vector<AxisFeature> features;
    for (std::size_t i = 1; i < net.inputs.size(); ++i) {
      const std::string& name = net.inputs[i];
      const std::string suffix = "_" + axis;
      AxisFeature f{};
      if (name.size() <= suffix.size() ||
          name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0 ||
          !parse_axis_feature(name.substr(0, name.size() - suffix.size()), f)) {
        fail("input " + name + " is not a direction feature of axis " + axis +
             " (sign, direction, reversal)");
      }
      features.push_back(f);
    }
    if (axis != "x" && features != extra) fail("its direction features differ from axis x's");
    extra = features;
    return {narx.options, net.parameters, MinMaxNormaliser(lo, hi),
            MinMaxNormaliser(Eigen::VectorXd::Constant(1, e_um.min * 1e-3),
                             Eigen::VectorXd::Constant(1, e_um.max * 1e-3))};
  }
  throw Error(result_file + ": no network for axis " + axis +
              " (a seed-002 narx result has x and y)");
}

}  // namespace

ContourPredictor contour_predictor_from(const RunRecord& r, const FollowingErrorRanges& ranges,
                                        const AxisDirectionOptions& direction,
                                        const std::string& result_file) {
  if (!r.narx) throw Error(result_file + ": not a narx result (model.type narx)");
  std::vector<AxisFeature> extra;
  NarxAxisModel x = contour_model_axis(*r.narx, "x", ranges.velocity[0], ranges.following_error[0],
                                       result_file, extra);
  NarxAxisModel y = contour_model_axis(*r.narx, "y", ranges.velocity[1], ranges.following_error[1],
                                       result_file, extra);
  return ContourPredictor(std::move(x), std::move(y), extra, direction);
}

AxisDirectionOptions TrainedContourModel::direction() const {
  AxisDirectionOptions o = dataset.direction;
  o.period = dataset.machine.timing.controller_period;
  return o;
}

ContourPredictor TrainedContourModel::predictor() const {
  return contour_predictor_from(upstream.record, ranges, direction(),
                                upstream.result_file.string());
}

TrainedContourModel load_trained_contour_model(const std::filesystem::path& narx_experiment,
                                               const std::filesystem::path& results_dir,
                                               const std::filesystem::path& data_dir,
                                               const std::string& profile, std::ostream* log,
                                               Dataset* dataset) {
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
  if (dataset) *dataset = cached.dataset;
  Rng rng(seed);  // the generator's first draw is the path (following_error.cpp)
  m.path = std::make_unique<NurbsPlanarPath>(random_planar_nurbs(m.dataset.path, rng));
  const auto rms = m.upstream.record.metrics.find("validation.contour_rms");  // narx_metrics.hpp
  m.contour_rms = rms == m.upstream.record.metrics.end() ? 0.0 : rms->second * 1e-3;
  return m;
}

}  // namespace cnclab
