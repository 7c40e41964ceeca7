#include "cnclab/studies/contour_error/narx_job.hpp"

#include <yaml-cpp/yaml.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <mutex>
#include <thread>

#include "cnclab/core/config.hpp"
#include "cnclab/core/error.hpp"
#include "cnclab/core/format.hpp"
#include "cnclab/core/hash.hpp"
#include "cnclab/core/rng.hpp"
#include "cnclab/data/dataset_cache.hpp"
#include "cnclab/data/following_error.hpp"
#include "cnclab/experiment/trainer_spec.hpp"
#include "cnclab/io/atomic_file.hpp"
#include "cnclab/io/h5.hpp"
#include "cnclab/motion/contour_error.hpp"
#include "cnclab/report/text_table.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

constexpr const char* kFormat = "cnclab-narx-study";
constexpr std::int64_t kFormatVersion = 1;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

const std::vector<std::pair<NarxMethod, const char*>> kMethods = {
    {NarxMethod::two_stage, "two_stage"},
    {NarxMethod::open_loop_only, "open_loop_only"},
    {NarxMethod::closed_loop_only, "closed_loop_only"}};

NarxMethod parse_method(const ConfigReader& r, const std::string& key, const std::string& name) {
  for (const auto& [m, text] : kMethods) {
    if (name == text) return m;
  }
  r.fail(key, "unknown method '" + name + "'; one of: two_stage, open_loop_only, closed_loop_only");
}

std::string resolved_yaml(const NarxJob& job, std::uint64_t dataset_seed) {
  using YAML::Key, YAML::Value, YAML::BeginMap, YAML::EndMap;
  YAML::Emitter out;
  out << BeginMap << Key << "kind" << Value << "narx" << Key << "name" << Value << job.name;
  out << Key << "description" << Value << job.description << Key << "seed" << Value << job.seed;
  out << Key << "dataset" << Value << BeginMap;
  out << Key << "generator" << Value << job.dataset.generator->name();
  out << Key << "version" << Value << job.dataset.generator->version();
  out << Key << "seed" << Value << dataset_seed;
  out << Key << "options" << Value << YAML::Load(job.dataset.generator->options_yaml());
  out << EndMap;
  out << Key << "axes" << Value << YAML::Flow << job.axes;
  const NarxOptions& n = job.narx;
  out << Key << "narx" << Value << BeginMap;
  out << Key << "input_delays" << Value << n.input_delays;
  out << Key << "feedback_delays" << Value << n.feedback_delays;
  out << Key << "hidden" << Value << n.hidden;
  out << Key << "activation" << Value << to_string(n.hidden_activation);
  out << Key << "first_input_delay" << Value << n.first_input_delay << EndMap;
  out << Key << "training" << Value << BeginMap;
  out << Key << "open_loop" << Value;
  emit_trainer(out, job.training.open_loop);
  out << Key << "closed_loop" << Value;
  emit_trainer(out, job.training.closed_loop);
  out << EndMap;
  const NarxStudyOptions& s = job.study;
  out << Key << "study" << Value << BeginMap;
  std::vector<std::string> methods;
  for (NarxMethod m : s.methods) methods.push_back(to_string(m));
  out << Key << "methods" << Value << YAML::Flow << methods;
  out << Key << "seeds" << Value << YAML::Flow << s.seeds;
  out << Key << "architectures" << Value << YAML::BeginSeq;
  for (const auto& a : s.architectures) {
    out << YAML::Flow << BeginMap << Key << "hidden" << Value << a.hidden << Key << "input_delays"
        << Value << a.input_delays << Key << "feedback_delays" << Value << a.feedback_delays
        << EndMap;
  }
  out << YAML::EndSeq;
  out << Key << "stable_bound" << Value << shortest_double(s.stable_bound) << EndMap << EndMap;
  return std::string(out.c_str()) + "\n";
}

struct Prepared {
  Dataset data;
  FollowingErrorRanges ranges;
  std::size_t half = 0;
  std::vector<int> axis_index;  // job.axes -> 0 (x) / 1 (y)
};

struct RunSeries {
  std::vector<Eigen::VectorXd> predicted_um;  // per job axis, validation steps
  Eigen::VectorXd contour_um;                 // Taylor from the predictions (NaN: none)
};

NarxRun train_one(const NarxJob& job, const Prepared& p, const NarxArchitecture& arch,
                  NarxMethod method, std::uint64_t seed, RunSeries* series) {
  NarxOptions no = job.narx;
  no.hidden = arch.hidden;
  no.input_delays = arch.input_delays;
  no.feedback_delays = arch.feedback_delays;
  const Narx narx(no);
  NarxTrainingOptions to = job.training;
  to.run_open_loop = method != NarxMethod::closed_loop_only;
  to.run_closed_loop = method != NarxMethod::open_loop_only;
  NarxRun run;
  run.architecture = arch;
  run.method = method;
  run.seed = seed;
  const auto n = static_cast<Eigen::Index>(p.data.num_samples());
  const auto half = static_cast<Eigen::Index>(p.half);
  const Eigen::Index first = narx.first_step();
  std::vector<Eigen::VectorXd> predicted(job.axes.size());
  bool all_stable = true;
  for (std::size_t a = 0; a < job.axes.size(); ++a) {
    const int axis = p.axis_index[a];
    const Eigen::VectorXd v = p.data.inputs.row(axis).transpose();
    const Eigen::VectorXd e = p.data.targets.row(axis).transpose();
    const Eigen::VectorXd v_train = v.head(half), e_train = e.head(half);
    const Eigen::VectorXd v_val = v.segment(half, n - half), e_val = e.segment(half, n - half);
    Eigen::VectorXd params(static_cast<Eigen::Index>(narx.num_parameters()));
    Rng rng(seed, "narx/init/" + job.axes[a]);
    narx.initialise(params, rng);
    const auto t0 = std::chrono::steady_clock::now();
    const NarxTrainingResult tr = train_narx(narx, v_train, e_train, params, to);
    NarxAxisScore s;
    s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (tr.open_loop) s.open_epochs = tr.open_loop->history.size();
    if (tr.closed_loop) s.closed_epochs = tr.closed_loop->history.size();
    s.termination =
        to_string(tr.closed_loop ? tr.closed_loop->termination : tr.open_loop->termination);
    // Closed loop over the whole validation half from measured initial states.
    const Eigen::VectorXd e_hat = narx.simulate_closed_loop(params, v_val, e_val);
    const ColumnRange& r = p.ranges.following_error[static_cast<std::size_t>(axis)];
    Eigen::VectorXd pred_um(n - half);
    for (Eigen::Index t = 0; t < first; ++t) pred_um[t] = to_physical(e_val[t], r);
    double sq = 0, mx = 0;
    s.stable = true;
    for (Eigen::Index t = first; t < n - half; ++t) {
      const double y = e_hat[t - first];
      if (!std::isfinite(y) || std::abs(y) > job.study.stable_bound) s.stable = false;
      pred_um[t] = to_physical(y, r);
      const double d = pred_um[t] - to_physical(e_val[t], r);
      sq += d * d;
      mx = std::max(mx, std::abs(d));
    }
    s.rms_um = s.stable ? std::sqrt(sq / static_cast<double>(n - half - first)) : kNaN;
    s.max_um = s.stable ? mx : kNaN;
    all_stable = all_stable && s.stable;
    predicted[a] = std::move(pred_um);
    run.axes.push_back(s);
  }
  // Contour error predicted by the Taylor estimate (Eqs. 3-6) from the
  // predicted following errors against the exact contour error of the data.
  run.contour_rms_um = run.contour_max_um = kNaN;
  Eigen::VectorXd contour = Eigen::VectorXd::Constant(n - half, kNaN);
  if (all_stable && job.axes.size() == 2) {
    const Dataset& d = p.data;
    const auto row = [&](const char* name) { return d.metadata_row(name); };
    const Eigen::Index rx = row("ref_x"), ry = row("ref_y"), d1x = row("d1_x"), d1y = row("d1_y"),
                       d2x = row("d2_x"), d2y = row("d2_y"), ex = row("contour_exact");
    double sq = 0, mx = 0;
    for (Eigen::Index t = first; t < n - half; ++t) {
      const Eigen::Index k = half + t;
      PathPoint pp;
      pp.position = {d.metadata(rx, k), d.metadata(ry, k)};
      pp.d1 = {d.metadata(d1x, k), d.metadata(d1y, k)};
      pp.d2 = {d.metadata(d2x, k), d.metadata(d2y, k)};
      Vec2 e_mm;
      for (std::size_t a = 0; a < 2; ++a) e_mm[p.axis_index[a]] = predicted[a][t] / 1000.0;
      const double c = std::abs(taylor_contour_error(pp, pp.position - e_mm)) * 1000.0;
      contour[t] = c;
      const double diff = c - d.metadata(ex, k);
      sq += diff * diff;
      mx = std::max(mx, std::abs(diff));
    }
    run.contour_rms_um = std::sqrt(sq / static_cast<double>(n - half - first));
    run.contour_max_um = mx;
  }
  if (series) {
    series->predicted_um = std::move(predicted);
    series->contour_um = std::move(contour);
  }
  return run;
}

}  // namespace

void check_narx_dataset(const Dataset& d, const std::string& origin) {
  if (d.generator != "following_error") {
    throw Error(origin + ": generator " + d.generator + ", expected following_error");
  }
  d.validate();  // every value finite: a NaN is an error naming the column and sample
  if (d.num_samples() < 64) {
    throw Error(origin + ": " + std::to_string(d.num_samples()) +
                " samples; at least 64 needed for two halves");
  }
}

std::string to_string(NarxMethod m) {
  for (const auto& [method, text] : kMethods) {
    if (method == m) return text;
  }
  return "?";
}

void NarxStudyOptions::validate() const {
  if (methods.empty()) throw OptionError("methods", "[]", "needs at least one method");
  if (seeds.empty()) throw OptionError("seeds", "[]", "needs at least one seed");
  for (const auto& a : architectures) {
    if (a.hidden < 1) throw OptionError("architectures.hidden", "0", "must be >= 1");
    if (a.input_delays < 1 || a.feedback_delays < 1) {
      throw OptionError("architectures.delays", "0", "must be >= 1");
    }
  }
  if (!(stable_bound > 0) || !std::isfinite(stable_bound)) {
    throw OptionError("stable_bound", shortest_double(stable_bound), "must be finite and > 0");
  }
  if (workers < 1 || workers > 64) {
    throw OptionError("workers", std::to_string(workers), "must be in [1, 64]");
  }
}

NarxJob load_narx_job(const fs::path& file, const std::vector<std::string>& overrides,
                      const std::string& profile) {
  ConfigDocument doc = ConfigDocument::load(file, profile);
  for (const auto& text : overrides) doc.apply(parse_override(text));
  const ConfigReader root = doc.root();
  if (root.get<std::string>("kind", "narx") != "narx") root.fail("kind", "must be narx");
  NarxJob job;
  job.source_file = file;
  job.name = read_experiment_name(root);
  job.description = root.get<std::string>("description", "");
  job.seed = root.get<std::uint64_t>("seed", job.seed);
  job.dataset = read_dataset_spec(root.section("dataset"));
  if (job.dataset.generator->name() != "following_error") {
    root.fail("dataset.generator", "must be following_error (the NARX study's data)");
  }
  if (!job.dataset.targets.empty()) root.fail("dataset.targets", "not used: see axes");
  job.axes = root.get<std::vector<std::string>>("axes", job.axes);
  if (job.axes.empty() || job.axes.size() > 2) root.fail("axes", "must be [x], [y] or [x, y]");
  for (const auto& a : job.axes) {
    if (a != "x" && a != "y") root.fail("axes", "each axis must be x or y");
  }
  if (job.axes.size() == 2 && job.axes[0] == job.axes[1]) root.fail("axes", "repeated axis");

  const ConfigReader n = root.section("narx");
  NarxOptions& o = job.narx;
  o.input_delays = n.get<std::size_t>("input_delays", o.input_delays);
  o.feedback_delays = n.get<std::size_t>("feedback_delays", o.feedback_delays);
  o.hidden = n.get<std::size_t>("hidden", o.hidden);
  if (n.has("activation")) {
    const auto name = n.get<std::string>("activation", "tanh");
    try {
      o.hidden_activation = parse_activation(name);
    } catch (const Error& e) {
      n.fail("activation", e.what());
    }
  }
  o.first_input_delay = n.get<std::size_t>("first_input_delay", o.first_input_delay);
  n.validate([&] { o.validate(); });

  const ConfigReader t = root.section("training");
  job.training.open_loop = read_trainbr_options(t.section("open_loop"), seed002_trainbr());
  job.training.closed_loop = read_trainbr_options(t.section("closed_loop"), seed002_trainbr());

  const ConfigReader s = root.section("study");
  NarxStudyOptions& st = job.study;
  if (s.has("methods")) {
    st.methods.clear();
    for (const auto& m : s.get<std::vector<std::string>>("methods", {})) {
      st.methods.push_back(parse_method(s, "methods", m));
    }
  }
  st.seeds = s.get<std::vector<std::uint64_t>>("seeds", st.seeds);
  if (s.has("architectures")) {
    const YAML::Node list = s.raw("architectures");
    if (!list.IsSequence()) s.fail("architectures", "expected a list of {hidden, delays}");
    for (const auto& item : list) {
      if (!item.IsMap() || item.size() != 2 || !item["hidden"] || !item["delays"]) {
        s.fail("architectures", "each entry must be {hidden: H, delays: D}");
      }
      NarxArchitecture a;
      try {
        const auto h = item["hidden"].as<long long>(), dl = item["delays"].as<long long>();
        if (h < 1) s.fail("architectures", "hidden = " + std::to_string(h) + ": must be >= 1");
        if (dl < 1) s.fail("architectures", "delays = " + std::to_string(dl) + ": must be >= 1");
        a.hidden = static_cast<std::size_t>(h);
        a.input_delays = a.feedback_delays = static_cast<std::size_t>(dl);
      } catch (const YAML::Exception&) {
        s.fail("architectures", "hidden and delays must be integers");
      }
      st.architectures.push_back(a);
    }
  }
  st.stable_bound = s.get<double>("stable_bound", st.stable_bound);
  st.workers = s.get<std::size_t>("workers", st.workers);
  s.validate([&] { st.validate(); });
  if (st.architectures.empty()) {
    st.architectures.push_back({o.hidden, o.input_delays, o.feedback_delays});
  }
  doc.check_all_consumed();
  const std::uint64_t dseed =
      job.dataset.seed ? *job.dataset.seed : derive_seed(job.seed, "generator");
  job.resolved_yaml = resolved_yaml(job, dseed);
  job.config_hash = hash_hex(job.resolved_yaml);
  return job;
}

fs::path narx_result_path(const NarxJob& job, const fs::path& results) {
  return results / job.name / (job.name + "-" + job.config_hash + ".h5");
}

NarxStudyResult run_narx_study(const NarxJob& job, const fs::path& datasets, std::ostream* log) {
  NarxStudyResult res;
  res.name = job.name;
  res.config_hash = job.config_hash;
  res.resolved_yaml = job.resolved_yaml;
  res.axes = job.axes;
  const std::uint64_t dseed =
      job.dataset.seed ? *job.dataset.seed : derive_seed(job.seed, "generator");
  auto t0 = std::chrono::steady_clock::now();
  CachedDataset cached = obtain_dataset(job.dataset, dseed, datasets, log);
  res.dataset_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  res.dataset_file = cached.path.string();
  res.dataset_hash = cached.content_hash;
  Prepared p;
  p.data = std::move(cached.dataset);
  check_narx_dataset(p.data, res.dataset_file);
  p.ranges = following_error_ranges(p.data);
  p.half = first_validation_sample(p.data);
  for (const auto& a : job.axes) p.axis_index.push_back(a == "x" ? 0 : 1);
  res.train_samples = p.half;
  res.validation_samples = p.data.num_samples() - p.half;

  // Zero predictor and the contour estimates on the validation half.
  const Dataset& d = p.data;
  const auto n = static_cast<Eigen::Index>(d.num_samples());
  const auto half = static_cast<Eigen::Index>(p.half);
  for (std::size_t a = 0; a < job.axes.size(); ++a) {
    const auto row = d.metadata.row(d.metadata_row(std::string("e_ref_") + job.axes[a]));
    const Eigen::VectorXd e = row.segment(half, n - half).transpose();
    res.zero_rms_um.push_back(std::sqrt(e.squaredNorm() / static_cast<double>(e.size())));
    res.zero_max_um.push_back(e.cwiseAbs().maxCoeff());
  }
  {
    const Eigen::VectorXd exact =
        d.metadata.row(d.metadata_row("contour_exact")).segment(half, n - half).transpose();
    res.exact_contour_mean_um = exact.mean();
    res.exact_contour_max_um = exact.maxCoeff();
    for (const char* m : {"taylor", "tangent", "osculating"}) {
      const Eigen::VectorXd est = d.metadata.row(d.metadata_row(std::string("contour_") + m))
                                      .segment(half, n - half)
                                      .transpose();
      const Eigen::ArrayXd diff = (est - exact).array().abs();
      res.estimates.push_back({m, diff.mean(), diff.maxCoeff()});
    }
  }

  // The grid of runs, trained by `workers` threads; each run's numbers depend
  // only on its own seed, so the order and the worker count do not matter.
  struct Task {
    NarxArchitecture arch;
    NarxMethod method;
    std::uint64_t seed;
  };
  std::vector<Task> tasks;
  for (const auto& arch : job.study.architectures) {
    for (NarxMethod m : job.study.methods) {
      for (std::uint64_t seed : job.study.seeds) tasks.push_back({arch, m, seed});
    }
  }
  res.runs.resize(tasks.size());
  RunSeries first_series;
  std::atomic<std::size_t> next{0};
  std::mutex log_mutex;
  std::exception_ptr failure;
  t0 = std::chrono::steady_clock::now();
  auto worker = [&] {
    for (std::size_t i; (i = next.fetch_add(1)) < tasks.size();) {
      try {
        const Task& task = tasks[i];
        res.runs[i] =
            train_one(job, p, task.arch, task.method, task.seed, i == 0 ? &first_series : nullptr);
        if (log) {
          const std::lock_guard lock(log_mutex);
          *log << "  [" << i + 1 << "/" << tasks.size() << "] " << to_string(task.method)
               << " H=" << task.arch.hidden << " D=" << task.arch.input_delays << "/"
               << task.arch.feedback_delays << " seed " << task.seed;
          for (std::size_t a = 0; a < job.axes.size(); ++a) {
            const NarxAxisScore& s = res.runs[i].axes[a];
            *log << "  " << job.axes[a] << ": rms " << table_number(s.rms_um) << " µm"
                 << (s.stable ? "" : " UNSTABLE") << " (" << s.open_epochs << "+" << s.closed_epochs
                 << " epochs, " << table_number(s.seconds, 3) << " s)";
          }
          *log << "  contour rms " << table_number(res.runs[i].contour_rms_um) << " µm\n";
          log->flush();
        }
      } catch (...) {
        const std::lock_guard lock(log_mutex);
        if (!failure) failure = std::current_exception();
        next = tasks.size();
      }
    }
  };
  const std::size_t nw = std::min(job.study.workers, tasks.size());
  std::vector<std::thread> threads;
  for (std::size_t w = 1; w < nw; ++w) threads.emplace_back(worker);
  worker();
  for (auto& t : threads) t.join();
  if (failure) std::rethrow_exception(failure);
  res.train_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  // Validation series of the first run, for the figures.
  const Eigen::Index m = n - half;
  res.series_names = {"time"};
  std::vector<Eigen::VectorXd> cols = {
      d.metadata.row(d.metadata_row("time")).segment(half, m).transpose()};
  for (std::size_t a = 0; a < job.axes.size(); ++a) {
    res.series_names.push_back("e_" + job.axes[a]);
    cols.push_back(
        d.metadata.row(d.metadata_row("e_ref_" + job.axes[a])).segment(half, m).transpose());
    res.series_names.push_back("e_hat_" + job.axes[a]);
    cols.push_back(first_series.predicted_um[a]);
  }
  res.series_names.push_back("contour_exact");
  cols.push_back(d.metadata.row(d.metadata_row("contour_exact")).segment(half, m).transpose());
  res.series_names.push_back("contour_hat");
  cols.push_back(first_series.contour_um);
  res.series.resize(static_cast<Eigen::Index>(cols.size()), m);
  for (std::size_t c = 0; c < cols.size(); ++c)
    res.series.row(static_cast<Eigen::Index>(c)) = cols[c].transpose();
  return res;
}

void write_narx_result(const fs::path& path, const NarxStudyResult& r) {
  AtomicOutput out(path);
  {
    H5File f = H5File::create(out.temp_path());
    f.set_attribute("/", "format", kFormat);
    f.set_attribute("/", "format_version", kFormatVersion);
    f.set_attribute("/", "name", r.name);
    f.set_attribute("/", "config_hash", r.config_hash);
    f.write_string("/config", r.resolved_yaml);
    f.create_group("/dataset");
    f.set_attribute("/dataset", "file", r.dataset_file);
    f.set_attribute("/dataset", "content_hash", r.dataset_hash);
    f.set_attribute("/dataset", "train_samples", static_cast<std::int64_t>(r.train_samples));
    f.set_attribute("/dataset", "validation_samples",
                    static_cast<std::int64_t>(r.validation_samples));
    f.set_attribute("/dataset", "seconds", r.dataset_seconds);
    f.write_strings("/axes", r.axes);
    f.write_vector("/zero_predictor/rms", r.zero_rms_um, "µm");
    f.write_vector("/zero_predictor/max", r.zero_max_um, "µm");
    f.create_group("/contour_estimates");
    f.set_attribute("/contour_estimates", "exact_mean", r.exact_contour_mean_um);
    f.set_attribute("/contour_estimates", "exact_max", r.exact_contour_max_um);
    std::vector<std::string> names;
    std::vector<double> mean, max;
    for (const auto& e : r.estimates) {
      names.push_back(e.method);
      mean.push_back(e.mean_um);
      max.push_back(e.max_um);
    }
    f.write_strings("/contour_estimates/method", names);
    f.write_vector("/contour_estimates/mean_abs_diff", mean, "µm");
    f.write_vector("/contour_estimates/max_abs_diff", max, "µm");
    std::vector<std::string> method;
    std::vector<std::uint64_t> seed, hidden, in_delays, fb_delays;
    std::vector<double> crms, cmax;
    for (const auto& run : r.runs) {
      method.push_back(to_string(run.method));
      seed.push_back(run.seed);
      hidden.push_back(run.architecture.hidden);
      in_delays.push_back(run.architecture.input_delays);
      fb_delays.push_back(run.architecture.feedback_delays);
      crms.push_back(run.contour_rms_um);
      cmax.push_back(run.contour_max_um);
    }
    f.write_strings("/runs/method", method);
    f.write_uint64s("/runs/seed", seed);
    f.write_uint64s("/runs/hidden", hidden);
    f.write_uint64s("/runs/input_delays", in_delays);
    f.write_uint64s("/runs/feedback_delays", fb_delays);
    f.write_vector("/runs/contour_rms", crms, "µm");
    f.write_vector("/runs/contour_max", cmax, "µm");
    for (std::size_t a = 0; a < r.axes.size(); ++a) {
      std::vector<double> rms, mx, secs;
      std::vector<std::int64_t> stable;
      std::vector<std::uint64_t> oe, ce;
      std::vector<std::string> term;
      for (const auto& run : r.runs) {
        const NarxAxisScore& s = run.axes[a];
        rms.push_back(s.rms_um);
        mx.push_back(s.max_um);
        secs.push_back(s.seconds);
        stable.push_back(s.stable ? 1 : 0);
        oe.push_back(s.open_epochs);
        ce.push_back(s.closed_epochs);
        term.push_back(s.termination);
      }
      const std::string g = "/runs/" + r.axes[a] + "/";
      f.write_vector(g + "rms", rms, "µm");
      f.write_vector(g + "max", mx, "µm");
      f.write_vector(g + "seconds", secs, "s");
      f.write_int64s(g + "stable", stable);
      f.write_uint64s(g + "open_epochs", oe);
      f.write_uint64s(g + "closed_epochs", ce);
      f.write_strings(g + "termination", term);
    }
    f.set_attribute("/runs", "seconds", r.train_seconds);
    f.write_matrix("/series", r.series, "mixed: see /series_names");
    f.write_strings("/series_names", r.series_names);
    f.set_attribute("/", "complete", std::int64_t{1});
    f.close();
  }
  out.commit();
}

NarxStudyResult read_narx_result(const fs::path& path) {
  const H5File f = H5File::open_read(path);
  if (!f.has_attribute("/", "format") || f.attribute_string("/", "format") != kFormat ||
      f.attribute_int("/", "format_version") != kFormatVersion ||
      !f.has_attribute("/", "complete") || f.attribute_int("/", "complete") != 1) {
    throw IoError(path.string() + ": not a complete " + kFormat + " v" +
                  std::to_string(kFormatVersion) + " file");
  }
  NarxStudyResult r;
  r.name = f.attribute_string("/", "name");
  r.config_hash = f.attribute_string("/", "config_hash");
  r.resolved_yaml = f.read_string("/config");
  r.dataset_file = f.attribute_string("/dataset", "file");
  r.dataset_hash = f.attribute_string("/dataset", "content_hash");
  r.train_samples = static_cast<std::size_t>(f.attribute_int("/dataset", "train_samples"));
  r.validation_samples =
      static_cast<std::size_t>(f.attribute_int("/dataset", "validation_samples"));
  r.dataset_seconds = f.attribute_double("/dataset", "seconds");
  r.axes = f.read_strings("/axes");
  r.zero_rms_um = f.read_vector("/zero_predictor/rms");
  r.zero_max_um = f.read_vector("/zero_predictor/max");
  r.exact_contour_mean_um = f.attribute_double("/contour_estimates", "exact_mean");
  r.exact_contour_max_um = f.attribute_double("/contour_estimates", "exact_max");
  const auto names = f.read_strings("/contour_estimates/method");
  const auto mean = f.read_vector("/contour_estimates/mean_abs_diff");
  const auto max = f.read_vector("/contour_estimates/max_abs_diff");
  for (std::size_t i = 0; i < names.size() && i < mean.size() && i < max.size(); ++i) {
    r.estimates.push_back({names[i], mean[i], max[i]});
  }
  const auto method = f.read_strings("/runs/method");
  const auto seed = f.read_uint64s("/runs/seed");
  const auto hidden = f.read_uint64s("/runs/hidden");
  const auto in_delays = f.read_uint64s("/runs/input_delays");
  const auto fb_delays = f.read_uint64s("/runs/feedback_delays");
  const auto crms = f.read_vector("/runs/contour_rms");
  const auto cmax = f.read_vector("/runs/contour_max");
  r.runs.resize(method.size());
  for (std::size_t i = 0; i < method.size(); ++i) {
    NarxRun& run = r.runs[i];
    for (const auto& [m, text] : kMethods) {
      if (method[i] == text) run.method = m;
    }
    run.seed = seed.at(i);
    run.architecture = {hidden.at(i), in_delays.at(i), fb_delays.at(i)};
    run.contour_rms_um = crms.at(i);
    run.contour_max_um = cmax.at(i);
  }
  for (const auto& axis : r.axes) {
    const std::string g = "/runs/" + axis + "/";
    const auto rms = f.read_vector(g + "rms");
    const auto mx = f.read_vector(g + "max");
    const auto secs = f.read_vector(g + "seconds");
    const auto stable = f.read_int64s(g + "stable");
    const auto oe = f.read_uint64s(g + "open_epochs");
    const auto ce = f.read_uint64s(g + "closed_epochs");
    const auto term = f.read_strings(g + "termination");
    for (std::size_t i = 0; i < r.runs.size(); ++i) {
      r.runs[i].axes.push_back(
          {rms.at(i), mx.at(i), stable.at(i) != 0, oe.at(i), ce.at(i), secs.at(i), term.at(i)});
    }
  }
  r.train_seconds = f.attribute_double("/runs", "seconds");
  r.series = f.read_matrix("/series");
  r.series_names = f.read_strings("/series_names");
  return r;
}

NarxJobOutcome run_narx_job(const NarxJob& job, const fs::path& results, const fs::path& datasets,
                            bool force, std::ostream* log) {
  NarxJobOutcome out;
  out.file = narx_result_path(job, results);
  std::error_code ec;
  if (!force && fs::exists(out.file, ec)) {
    try {
      out.result = read_narx_result(out.file);
      if (out.result.config_hash == job.config_hash) {
        out.reused = true;
        return out;
      }
    } catch (const IoError& e) {
      if (log)
        *log << "  " << out.file.string() << ": unreadable (" << e.what() << "), re-running\n";
    }
  }
  out.result = run_narx_study(job, datasets, log);
  write_narx_result(out.file, out.result);
  return out;
}

std::string narx_summary_line(const NarxStudyResult& r) {
  std::size_t stable = 0;
  double best = kNaN, contour = kNaN;
  for (const auto& run : r.runs) {
    bool all = true;
    for (const auto& s : run.axes) all = all && s.stable;
    stable += all ? 1 : 0;
    if (all && !(run.axes[0].rms_um >= best)) {
      best = run.axes[0].rms_um;
      contour = run.contour_rms_um;
    }
  }
  char line[200];
  std::snprintf(line, sizeof line,
                "%zu run(s), %zu stable; best %s RMS %.3g µm (zero predictor %.3g), contour RMS "
                "%.3g µm",
                r.runs.size(), stable, r.axes.empty() ? "?" : r.axes[0].c_str(), best,
                r.zero_rms_um.empty() ? kNaN : r.zero_rms_um[0], contour);
  return line;
}

}  // namespace cnclab
