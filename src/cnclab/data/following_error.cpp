#include "cnclab/data/following_error.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

#include "cnclab/core/error.hpp"
#include "cnclab/core/format.hpp"
#include "cnclab/core/resources.hpp"
#include "cnclab/core/units.hpp"
#include "cnclab/data/following_error_runs.hpp"
#include "cnclab/motion/axis_direction.hpp"
#include "cnclab/motion/contour_error.hpp"
#include "cnclab/motion/interpolator.hpp"
#include "cnclab/motion/smoothing_spline.hpp"

namespace cnclab {
namespace {

constexpr const char* kAxis[2] = {"x", "y"};

const std::vector<std::string> kMetadata = {"time",
                                            "u",
                                            "ref_x",
                                            "ref_y",
                                            "actual_x",
                                            "actual_y",
                                            "v_ref_x",
                                            "v_ref_y",
                                            "e_ref_x",
                                            "e_ref_y",
                                            "d1_x",
                                            "d1_y",
                                            "d2_x",
                                            "d2_y",
                                            "contour_exact",
                                            "contour_taylor",
                                            "contour_tangent",
                                            "contour_osculating",
                                            "validation"};
const std::vector<std::string> kMetadataUnits = {"s",    "1",  "mm", "mm", "mm", "mm", "mm/s",
                                                 "mm/s", "µm", "µm", "mm", "mm", "mm", "mm",
                                                 "µm",   "µm", "µm", "µm", "1"};

}  // namespace

void FollowingErrorOptions::validate() const {
  auto prefixed = [](const std::string& prefix, auto&& f) {
    try {
      f();
    } catch (const OptionError& e) {
      throw OptionError(prefix + e.field(), e.value(), e.rule());
    }
  };
  prefixed("path.", [&] { path.validate(); });
  prefixed("", [&] { planner.validate(); });
  prefixed("machine.", [&] { machine.validate(); });
  if (runs < 1 || runs > 1000) {
    throw OptionError("runs", std::to_string(runs), "must be in [1, 1000]");
  }
  if (!(smoothing >= 0.0 && smoothing <= 1.0)) {
    throw OptionError("smoothing", shortest_double(smoothing), "must be in [0, 1] (csaps p)");
  }
  if (samples != 0 && samples < 8) {
    throw OptionError("samples", std::to_string(samples), "must be 0 (whole run) or >= 8");
  }
  for (std::size_t i = 0; i < feed_factors.size(); ++i) {
    const double f = feed_factors[i];
    if (!(f > 0.0 && f <= 1.0)) {
      throw OptionError("feed_factors", shortest_double(f),
                        "entry " + std::to_string(i) + " must be in (0, 1]");
    }
    for (std::size_t j = 0; j < i; ++j) {
      if (feed_factors[j] == f) {
        throw OptionError("feed_factors", shortest_double(f), "lists a factor twice");
      }
    }
  }
  for (std::size_t i = 0; i < extra_inputs.size(); ++i) {
    AxisFeature f{};
    if (!parse_axis_feature(extra_inputs[i], f)) {
      throw OptionError("extra_inputs", extra_inputs[i],
                        "must be sign, direction or reversal (motion/axis_direction.hpp)");
    }
    for (std::size_t j = 0; j < i; ++j) {
      if (extra_inputs[j] == extra_inputs[i]) {
        throw OptionError("extra_inputs", extra_inputs[i], "lists an input twice");
      }
    }
  }
  prefixed("direction.", [&] { direction.validate(); });
  if (!(plan_length >= 0.0 && std::isfinite(plan_length))) {
    throw OptionError("plan_length", shortest_double(plan_length),
                      "must be 0 (the whole path in one plan) or a length > 0 [mm]");
  }
}

Eigen::VectorXd normalise_minmax(const Eigen::VectorXd& x, const std::string& what,
                                 ColumnRange* range) {
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    if (!std::isfinite(x[i])) {
      throw Error(what + ": sample " + std::to_string(i) + " is " + shortest_double(x[i]) +
                  " (not finite); cannot normalise");
    }
  }
  const double lo = x.size() ? x.minCoeff() : 0.0, hi = x.size() ? x.maxCoeff() : 0.0;
  if (!(hi > lo)) {
    throw Error(what + ": constant column (min = max = " + shortest_double(lo) +
                "); cannot map to [-1, 1]");
  }
  if (range) *range = {lo, hi};
  // MATLAB mapminmax: y = (ymax - ymin)(x - xmin)/(xmax - xmin) + ymin.
  Eigen::VectorXd y = ((x.array() - lo) / (hi - lo) * 2.0 - 1.0).matrix();
  return y;
}

namespace {

// The metadata columns of samples [first, first + count) of `run`, from
// column `col` of d.metadata on (the first kMetadata.size() rows).
void following_error_metadata(const NurbsPlanarPath& path, const FollowingErrorRun& run,
                              Eigen::Index first, Eigen::Index count, double validation, Dataset& d,
                              Eigen::Index col, const ProgressCallback& progress, std::size_t& done,
                              std::size_t total) {
  const ReferenceTrajectory& ref = run.ref;
  for (Eigen::Index k = first; k < first + count; ++k, ++col) {
    const auto i = static_cast<std::size_t>(k);
    const PathPoint p = path.evaluate(ref.u[i]);
    const Vec2 r = ref.position.row(k).transpose();
    const Vec2 actual = r - run.e.row(k).transpose();
    const double exact = project_to_path(path, actual, ref.u[i]).distance;
    d.metadata.col(col).head(static_cast<Eigen::Index>(kMetadata.size())) << ref.time[i], ref.u[i],
        r.x(), r.y(), actual.x(), actual.y(), ref.velocity(k, 0), ref.velocity(k, 1),
        run.e(k, 0) * kUmPerMm, run.e(k, 1) * kUmPerMm, p.d1.x(), p.d1.y(), p.d2.x(), p.d2.y(),
        exact * kUmPerMm, std::abs(taylor_contour_error(p, actual)) * kUmPerMm,
        tangent_line_contour_error(p, actual) * kUmPerMm,
        osculating_circle_contour_error(p, actual) * kUmPerMm, validation;
    ++done;
    if (progress && (done % 1000 == 0 || done == total)) progress("contour errors", done, total);
  }
}

}  // namespace

Dataset generate_following_error_dataset(const FollowingErrorOptions& o, Rng& rng,
                                         const ProgressCallback& progress) {
  o.validate();
  // 1. Path, feedrate, 1 ms references: the plan, or its runs at the feed
  // factors, each for about the same part of the path as `samples` ticks of
  // the plan, an even count so that its time midpoint splits it in halves.
  const NurbsPlanarPath path(random_planar_nurbs(o.path, rng));
  const std::uint64_t run_seed = rng.next_u64();
  const FollowingErrorPlan plan = plan_following_error(o, path, progress);
  const bool feeds = !o.feed_factors.empty();
  const double period = o.machine.timing.controller_period;
  std::vector<FollowingErrorRun> runs;
  if (feeds) {
    for (const double f : o.feed_factors) {
      Eigen::Index keep = 0;
      if (o.samples != 0) {
        keep = static_cast<Eigen::Index>(std::llround(static_cast<double>(o.samples) / f));
      } else {
        keep = following_error_run(plan, f, 0, period).samples();
      }
      runs.push_back(following_error_run(plan, f, keep - keep % 2, period));
    }
  } else {
    runs.push_back(following_error_run(plan, 1.0, 0, period));
    const Eigen::Index total = runs[0].samples();
    if (o.samples != 0 && static_cast<std::size_t>(total) < o.samples) {
      std::ostringstream m;
      m << "following_error: the planned run has " << total << " samples ("
        << runs[0].ref.time.back() << " s) < samples = " << o.samples
        << "; raise path.control_points (now " << o.path.control_points << ") or lower samples";
      throw Error(m.str());
    }
    if (o.samples != 0) {
      runs[0] = following_error_run(plan, 1.0, static_cast<Eigen::Index>(o.samples), period);
    }
  }
  Eigen::Index n = 0;
  for (const auto& run : runs) n += run.samples();
  const std::size_t extra = o.extra_inputs.size();
  const std::size_t columns = kMetadata.size() + (feeds ? 3 : 0);
  check_memory(
      static_cast<double>(n) * static_cast<double>(columns + 4 + 2 * extra + 2 * o.runs) * 8.0,
      "following_error dataset");

  // 2-3. `runs` repetitions of each run, each with its own noise streams;
  // their mean, smoothed. The plan itself (factor 1) draws the streams
  // run/<k> in both layouts.
  for (auto& run : runs) {
    const std::string streams =
        run.factor == 1.0 ? "" : "feed/" + shortest_double(run.factor) + "/";
    simulate_following_error(o, run, run_seed, streams, progress);
  }

  // 4. Columns, contour errors and the normalisation. Without feed factors
  // the one run in time order, its second half validating; with them the
  // first halves of every run in factor order, then their second halves.
  struct Chunk {
    std::size_t run;
    Eigen::Index first, count;
    double validation;
  };
  std::vector<Chunk> chunks;
  if (!feeds) {
    chunks.push_back({0, 0, n / 2, 0.0});
    chunks.push_back({0, n / 2, n - n / 2, 1.0});
  } else {
    for (std::size_t i = 0; i < runs.size(); ++i) {
      chunks.push_back({i, 0, runs[i].samples() / 2, 0.0});
    }
    for (std::size_t i = 0; i < runs.size(); ++i) {
      chunks.push_back({i, runs[i].samples() / 2, runs[i].samples() / 2, 1.0});
    }
  }
  Dataset d;
  const auto channels = static_cast<Eigen::Index>(2 + 2 * extra);
  d.inputs.resize(channels, n);
  d.targets.resize(2, n);
  d.metadata.resize(static_cast<Eigen::Index>(columns), n);
  Eigen::MatrixX2d v(n, 2), e_um(n, 2);
  std::vector<AxisFeature> wanted;
  for (const auto& name : o.extra_inputs) {
    AxisFeature f{};
    parse_axis_feature(name, f);  // validate() checked the names
    wanted.push_back(f);
  }
  AxisDirectionOptions direction = o.direction;
  direction.period = period;
  // Per run, the features of every piece from rest (a cold start, as the
  // predictor starts a planned section): [run][axis][feature][sample].
  std::vector<std::vector<std::vector<std::vector<double>>>> features(runs.size());
  for (std::size_t i = 0; i < runs.size() && extra > 0; ++i) {
    const FollowingErrorRun& run = runs[i];
    features[i].resize(2);
    for (int a = 0; a < 2; ++a) {
      auto& out = features[i][static_cast<std::size_t>(a)];
      out.assign(extra, {});
      for (std::size_t p = 0; p < run.piece_starts.size(); ++p) {
        const Eigen::Index first = run.piece_starts[p];
        const Eigen::Index end =
            p + 1 < run.piece_starts.size() ? run.piece_starts[p + 1] : run.samples();
        const Eigen::VectorXd va = run.ref.velocity.col(a).segment(first, end - first);
        const auto series =
            axis_direction_series(std::vector<double>(va.begin(), va.end()), wanted, direction);
        for (std::size_t f = 0; f < extra; ++f) {
          out[f].insert(out[f].end(), series[f].begin(), series[f].end());
        }
      }
    }
  }
  // Identifiers: a piece per run and piece (a cold start), a sequence per
  // chunk and piece in it (an independent series for the NARX training).
  std::vector<double> piece_id_base(runs.size(), 0.0);
  for (std::size_t i = 1; i < runs.size(); ++i) {
    piece_id_base[i] = piece_id_base[i - 1] + static_cast<double>(runs[i - 1].piece_starts.size());
  }
  Eigen::Index col = 0;
  std::size_t done = 0;
  double sequence = -1.0;
  for (const Chunk& chunk : chunks) {
    const FollowingErrorRun& run = runs[chunk.run];
    v.middleRows(col, chunk.count) = run.ref.velocity.middleRows(chunk.first, chunk.count);
    e_um.middleRows(col, chunk.count) = run.e.middleRows(chunk.first, chunk.count) * kUmPerMm;
    for (int a = 0; a < 2 && extra > 0; ++a) {
      for (std::size_t f = 0; f < extra; ++f) {
        const auto& series = features[chunk.run][static_cast<std::size_t>(a)][f];
        for (Eigen::Index k = 0; k < chunk.count; ++k) {
          d.inputs(static_cast<Eigen::Index>(2 + 2 * f) + a, col + k) =
              series[static_cast<std::size_t>(chunk.first + k)];
        }
      }
    }
    following_error_metadata(path, run, chunk.first, chunk.count, chunk.validation, d, col,
                             progress, done, static_cast<std::size_t>(n));
    if (feeds) {
      const auto row = static_cast<Eigen::Index>(kMetadata.size());
      for (Eigen::Index k = chunk.first; k < chunk.first + chunk.count; ++k, ++col) {
        const auto piece = static_cast<std::size_t>(
            std::upper_bound(run.piece_starts.begin(), run.piece_starts.end(), k) -
            run.piece_starts.begin() - 1);
        if (k == chunk.first || k == run.piece_starts[piece]) sequence += 1.0;
        d.metadata(row, col) = run.factor;
        d.metadata(row + 1, col) = sequence;
        d.metadata(row + 2, col) = piece_id_base[chunk.run] + static_cast<double>(piece);
      }
    } else {
      col += chunk.count;
    }
  }
  for (int a = 0; a < 2; ++a) {
    d.inputs.row(a) = normalise_minmax(v.col(a), std::string("v_ref_") + kAxis[a]).transpose();
    d.targets.row(a) = normalise_minmax(e_um.col(a), std::string("e_ref_") + kAxis[a]).transpose();
  }
  d.input_names = {"v_x", "v_y"};
  d.input_units = {"1", "1"};
  for (std::size_t f = 0; f < extra; ++f) {
    for (int a = 0; a < 2; ++a) {
      // Already in [-1, 1] (axis_direction.hpp): stored as they are.
      d.input_names.push_back(o.extra_inputs[f] + "_" + kAxis[a]);
      d.input_units.push_back("1");
    }
  }
  d.target_names = {"e_x", "e_y"};
  d.target_units = {"1", "1"};
  d.metadata_names = kMetadata;
  d.metadata_units = kMetadataUnits;
  if (feeds) {
    d.metadata_names.insert(d.metadata_names.end(), {"feed_factor", "sequence", "piece"});
    d.metadata_units.insert(d.metadata_units.end(), {"1", "1", "1"});
  }
  d.generator = "following_error";
  d.validate();
  return d;
}

FollowingErrorRanges following_error_ranges(const Dataset& d) {
  auto range = [&](const std::string& name) {
    const Eigen::Index row = d.metadata_row(name);
    if (row < 0) throw Error("following_error dataset: no metadata column " + name);
    return ColumnRange{d.metadata.row(row).minCoeff(), d.metadata.row(row).maxCoeff()};
  };
  FollowingErrorRanges r;
  for (int a = 0; a < 2; ++a) {
    r.velocity[a] = range(std::string("v_ref_") + kAxis[a]);
    r.following_error[a] = range(std::string("e_ref_") + kAxis[a]);
  }
  return r;
}

std::size_t first_validation_sample(const Dataset& d) {
  return d.num_samples() / 2;
}

FollowingErrorGenerator::FollowingErrorGenerator(FollowingErrorOptions options)
    : options_(std::move(options)) {
  options_.validate();
}

DatasetShape FollowingErrorGenerator::shape() const {
  const std::size_t inputs = 2 + 2 * options_.extra_inputs.size();
  if (options_.feed_factors.empty() || options_.samples == 0) {
    return {options_.samples, inputs, 2};  // 0: known only after planning
  }
  std::size_t n = 0;
  for (const double f : options_.feed_factors) {
    const auto run =
        static_cast<std::size_t>(std::llround(static_cast<double>(options_.samples) / f));
    n += run - run % 2;
  }
  return {n, inputs, 2};
}

}  // namespace cnclab
