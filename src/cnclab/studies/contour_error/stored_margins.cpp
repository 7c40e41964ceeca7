#include "cnclab/studies/contour_error/stored_margins.hpp"

#include <cstdint>
#include <vector>

#include "cnclab/core/error.hpp"
#include "cnclab/core/format.hpp"
#include "cnclab/io/atomic_file.hpp"
#include "cnclab/io/file_format.hpp"
#include "cnclab/io/h5.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

constexpr const char* kMarginsFormat = "cnclab-margins";
constexpr int kMarginsVersion = 1;

void write_residuals(H5File& f, const std::string& g, const ResidualSummary& r) {
  f.create_group(g);
  f.write_int(g + "/ticks", static_cast<std::int64_t>(r.ticks));
  f.write_double(g + "/rms", r.rms, "mm");
  f.write_double(g + "/underprediction_p99", r.underprediction_p99, "mm");
  f.write_double(g + "/underprediction_max", r.underprediction_max, "mm");
  f.write_double(g + "/correlation", r.correlation, "1");
}

ResidualSummary read_residuals(const H5File& f, const std::string& g) {
  ResidualSummary r;
  r.ticks = static_cast<std::size_t>(f.read_int(g + "/ticks"));
  r.rms = f.read_double(g + "/rms");
  r.underprediction_p99 = f.read_double(g + "/underprediction_p99");
  r.underprediction_max = f.read_double(g + "/underprediction_max");
  r.correlation = f.read_double(g + "/correlation");
  return r;
}

bool same_options(const MarginCalibrationOptions& a, const MarginCalibrationOptions& b) {
  return a.quantile == b.quantile && a.feed_bands == b.feed_bands && a.min_ticks == b.min_ticks &&
         a.reversal_window == b.reversal_window;
}

}  // namespace

fs::path stored_margins_path(const fs::path& predictor_result) {
  return predictor_result.parent_path() / (predictor_result.stem().string() + "-margins.h5");
}

void write_stored_margins(const fs::path& file, const StoredMargins& m) {
  const MarginCalibration& c = m.calibration;
  const bool window = m.options.reversal_window > 0.0;
  if (c.margins.margin.size() != c.margins.edges.size() + 1 ||
      c.band_ticks.size() != c.margins.margin.size() ||
      c.margins.reversal_window != m.options.reversal_window ||
      c.margins.after_reversal.size() != (window ? c.margins.margin.size() : 0) ||
      c.after_reversal_band_ticks.size() != c.margins.after_reversal.size()) {
    throw Error("margins for " + file.string() + ": " + std::to_string(c.margins.margin.size()) +
                " margins, " + std::to_string(c.band_ticks.size()) + " tick counts and " +
                std::to_string(c.margins.edges.size()) + " band edges (" +
                std::to_string(c.margins.after_reversal.size()) + " and " +
                std::to_string(c.after_reversal_band_ticks.size()) + " after a reversal, window " +
                shortest_double(c.margins.reversal_window) + " s, options' " +
                shortest_double(m.options.reversal_window) + " s) do not fit together");
  }
  AtomicOutput out(file);
  {
    H5File f = H5File::create(out.temp_path());
    write_format(f, kMarginsFormat, kMarginsVersion);
    f.write_string("predictor_result", m.predictor_result.string());
    f.write_string("predictor_identity", m.predictor_identity);
    f.write_string("dataset_hash", m.dataset_hash);
    f.write_string("split", "validation");
    f.write_double("quantile", m.options.quantile, "1");
    f.write_int("min_ticks", static_cast<std::int64_t>(m.options.min_ticks), "1");
    f.write_vector("feed_bands", c.margins.edges, "mm/s");
    f.write_vector("margins", c.margins.margin, "mm");
    std::vector<std::int64_t> ticks(c.band_ticks.begin(), c.band_ticks.end());
    f.write_int64s("band_ticks", ticks, "1");
    f.write_double("reversal_window", m.options.reversal_window, "s");
    if (window) {
      f.write_vector("after_reversal_margins", c.margins.after_reversal, "mm");
      std::vector<std::int64_t> after(c.after_reversal_band_ticks.begin(),
                                      c.after_reversal_band_ticks.end());
      f.write_int64s("after_reversal_band_ticks", after, "1");
    }
    write_residuals(f, "validation", c.validation);
    write_residuals(f, "slowed", c.slowed);
    write_provenance(f, "provenance", m.provenance);
    mark_complete(f);
    f.close();
  }
  out.commit();
}

std::optional<StoredMargins> read_stored_margins(const fs::path& file) {
  if (!fs::exists(file)) return std::nullopt;
  const H5File f = H5File::open_read(file);
  require_format(f, kMarginsFormat, kMarginsVersion);
  StoredMargins m;
  m.predictor_result = f.read_string("predictor_result");
  m.predictor_identity = f.read_string("predictor_identity");
  m.dataset_hash = f.read_string("dataset_hash");
  if (const std::string split = f.read_string("split"); split != "validation") {
    throw Error(file.string() + ": split is '" + split +
                "'; margins are calibrated on validation plans only");
  }
  m.options.quantile = f.read_double("quantile");
  m.options.min_ticks = static_cast<std::size_t>(f.read_int("min_ticks"));
  m.options.feed_bands = f.read_vector("feed_bands");
  MarginCalibration& c = m.calibration;
  c.margins.edges = m.options.feed_bands;
  c.margins.margin = f.read_vector("margins");
  for (const std::int64_t t : f.read_int64s("band_ticks")) {
    c.band_ticks.push_back(static_cast<std::size_t>(t));
  }
  // Files written before the reversal class have no window: one class.
  m.options.reversal_window = f.exists("reversal_window") ? f.read_double("reversal_window") : 0.0;
  if (m.options.reversal_window > 0.0) {
    c.margins.reversal_window = m.options.reversal_window;
    c.margins.after_reversal = f.read_vector("after_reversal_margins");
    for (const std::int64_t t : f.read_int64s("after_reversal_band_ticks")) {
      c.after_reversal_band_ticks.push_back(static_cast<std::size_t>(t));
    }
  }
  if (c.margins.margin.size() != c.margins.edges.size() + 1 ||
      c.band_ticks.size() != c.margins.margin.size() ||
      c.after_reversal_band_ticks.size() != c.margins.after_reversal.size()) {
    throw Error(file.string() + ": " + std::to_string(c.margins.margin.size()) + " margins and " +
                std::to_string(c.band_ticks.size()) + " tick counts (" +
                std::to_string(c.margins.after_reversal.size()) + " and " +
                std::to_string(c.after_reversal_band_ticks.size()) + " after a reversal) for " +
                std::to_string(c.margins.edges.size() + 1) + " feed bands");
  }
  try {
    m.options.validate();
    c.margins.validate();
  } catch (const OptionError& e) {
    throw Error(file.string() + ": " + e.what());
  }
  c.validation = read_residuals(f, "validation");
  c.slowed = read_residuals(f, "slowed");
  m.provenance = read_provenance(f, "provenance");
  return m;
}

StoredMargins predictor_margins(ContourPredictor& predictor, const Dataset& plans,
                                const std::string& dataset_hash, const fs::path& predictor_result,
                                const std::string& predictor_identity,
                                const MarginCalibrationOptions& options, std::ostream& note) {
  const fs::path file = stored_margins_path(predictor_result);
  if (std::optional<StoredMargins> stored = read_stored_margins(file)) {
    if (stored->predictor_identity == predictor_identity &&
        same_options(stored->options, options)) {
      note << "margins stored with the predictor: " << file.string() << "\n";
      return std::move(*stored);
    }
    note << "margins stored with the predictor (" << file.string() << ") are of "
         << (stored->predictor_identity == predictor_identity ? "other calibration options"
                                                              : "an earlier training")
         << "; calibrating again\n";
  } else {
    note << "the predictor's result has no stored margins yet; calibrating on its validation "
            "plans\n";
  }
  StoredMargins m;
  m.predictor_result = predictor_result;
  m.predictor_identity = predictor_identity;
  m.dataset_hash = dataset_hash;
  m.options = options;
  m.provenance = make_provenance(0);
  m.calibration = calibrate_margins(predictor, plans, options);
  predictor.reset();
  finish_provenance(m.provenance);
  write_stored_margins(file, m);
  note << "margins stored with the predictor: " << file.string() << " (written)\n";
  return m;
}

}  // namespace cnclab
