// Every model kind end to end through the binary, each checked against
// something the code under test does not compute itself:
// - `cnclab predict` on the result's own split equals the predictions the
//   training run stored (to 1e-12), and seed 002's contour RMS metric;
// - the C export, compiled by gcc (-std=c99 -Wall -Wextra -Werror -pedantic)
//   and by clang, equals `cnclab predict` on a CSV of raw inputs to 1e-12 in
//   double, and within the stated running error bound in float; a NaN input
//   is refused without touching the state; the object has no writable data
//   and calls nothing but <math.h>; it compiles for a Cortex-M4;
// - the torch export, run by PyTorch, equals it to 1e-12 in float64.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <regex>
#include <sstream>

#include "cnclab/data/dataset_file.hpp"
#include "cnclab/deploy/c_export.hpp"
#include "cnclab/deploy/code_text.hpp"
#include "cnclab/deploy/csv_table.hpp"
#include "cnclab/deploy/float_bound.hpp"
#include "cnclab/deploy/prediction_input.hpp"
#include "cnclab/experiment/result_file.hpp"
#include "cnclab/io/h5.hpp"
#include "cnclab/studies/contour_error/contour_deployment.hpp"
#include "common/temp_dir.hpp"
#include "deploy/deploy_fixtures.hpp"

namespace cnclab {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;

constexpr double kDoubleTolerance = 1e-12;  // relative to max(1, |value|)

bool close(double a, double b, double tol = kDoubleTolerance) {
  return std::abs(a - b) <= tol * std::max(1.0, std::abs(b));
}

void register_study_once() {
  static const bool done = (register_contour_deployment(), true);
  (void)done;
}

struct KindCase {
  std::string label;       // the test's name
  std::string experiment;  // `cnclab run` arguments
  std::string split;       // the result's stored prediction: test (mlp) or validation (narx)
};

std::ostream& operator<<(std::ostream& out, const KindCase& c) {
  return out << c.label;
}

// A C main reading rows of inputs (and, with `contour`, R, C', C'') and
// printing the export's outputs (and the contour estimate) in hex, or
// "error" for a refused row.
std::string harness(const std::string& name, bool narx, bool contour) {
  const std::string M = macro_prefix(name), R = name + "_real";
  std::ostringstream s;
  s << "#include <stdio.h>\n#include \"" << name << ".h\"\nint main(void)\n{\n";
  if (!narx) {
    s << "  " << R << " in[" << M << "_INPUTS], out[" << M << "_OUTPUTS];\n  double x;\n  int i;\n"
      << "  for (;;) {\n    for (i = 0; i < " << M << "_INPUTS; ++i) {\n"
      << "      if (scanf(\"%lf\", &x) != 1) return 0;\n      in[i] = (" << R << ")x;\n    }\n"
      << "    if (" << name << "_predict(in, out) != 0) {\n      printf(\"error\\n\");\n"
      << "      continue;\n    }\n    for (i = 0; i < " << M << "_OUTPUTS; ++i) printf(\"%a \", "
      << "(double)out[i]);\n    printf(\"\\n\");\n  }\n}\n";
    return s.str();
  }
  const int n = contour ? 8 : 2;
  s << "  " << name << "_state st;\n  " << R << " v[8], out[" << M << "_NETWORKS], c = 0;\n"
    << "  double x;\n  int i;\n  " << name << "_init(&st);\n  for (;;) {\n"
    << "    for (i = 0; i < " << n << "; ++i) {\n      if (scanf(\"%lf\", &x) != 1) return 0;\n"
    << "      v[i] = (" << R << ")x;\n    }\n    if (" << name << "_step(&st, v, out) != 0) {\n"
    << "      printf(\"error\\n\");\n      continue;\n    }\n";
  if (contour) {
    s << "    if (" << name << "_contour_error(v + 2, v + 4, v + 6, out, &c) != 0) c = -1;\n";
  }
  s << "    for (i = 0; i < " << M << "_NETWORKS; ++i) printf(\"%a \", (double)out[i]);\n"
    << (contour ? "    printf(\"%a\", (double)c);\n" : "") << "    printf(\"\\n\");\n  }\n}\n";
  return s.str();
}

// `column` of a written prediction (.h5).
Eigen::VectorXd h5_column(const fs::path& file, const std::string& column) {
  const H5File f = H5File::open_read(file);
  const auto v = f.read_vector("/predictions/" + column);
  return Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
}

const NamedColumn& find_column(const std::vector<NamedColumn>& columns, const std::string& name) {
  for (const auto& c : columns) {
    if (c.name == name) return c;
  }
  throw Error("no column " + name);
}

// "name: B = value unit" lines of the float export's header.
std::map<std::string, double> stated_bounds(const std::string& header) {
  std::map<std::string, double> out;
  const std::regex line(R"(\* +([A-Za-z0-9_]+): B = ([0-9.eE+-]+))");
  for (std::sregex_iterator it(header.begin(), header.end(), line), end; it != end; ++it) {
    out[(*it)[1]] = std::stod((*it)[2]);
  }
  return out;
}

class DeployKind : public ::testing::TestWithParam<KindCase> {};

TEST_P(DeployKind, PredictExportsAndTheirCompilersAgree) {
  register_study_once();
  const KindCase& kc = GetParam();
  TempDir dir;
  const auto sh = [&](const std::string& cmd) { return testing::run_shell(dir.path(), cmd); };
  const std::string result = testing::train(dir.path(), kc.experiment);
  ASSERT_FALSE(result.empty());
  const RunRecord rec = read_result(dir / result);
  const bool narx = rec.narx.has_value();

  // 1. The result's own split: the stored predictions.
  auto r = testing::cnclab(dir.path(), "predict " + result + " " + rec.dataset_file + " --split " +
                                           kc.split + " -o own.h5 --data-dir data -q");
  ASSERT_EQ(r.code, 0) << r.err << r.out;
  const Eigen::MatrixXd& stored = narx ? rec.narx->predictions : rec.test_predictions;
  for (std::size_t k = 0; k < rec.target_names.size(); ++k) {
    const Eigen::VectorXd got =
        h5_column(dir / "own.h5", rec.target_names[k] + (narx ? ".closed_loop" : ".predicted"));
    ASSERT_EQ(got.size(), stored.cols());
    for (Eigen::Index s = 0; s < got.size(); ++s) {
      ASSERT_TRUE(close(got[s], stored(static_cast<Eigen::Index>(k), s)))
          << rec.target_names[k] << " sample " << s << ": " << got[s] << " vs "
          << stored(static_cast<Eigen::Index>(k), s);
    }
  }
  if (narx) {  // seed 002's contour RMS, the metric's own definition
    const std::regex rms(R"(contour_error\.closed_loop - measured: RMS ([0-9.eE+-]+))");
    std::smatch m;
    ASSERT_TRUE(std::regex_search(r.out, m, rms)) << r.out;
    // The metric by the end of its name: "contour_rms" or a per-split "<split>.contour_rms".
    const auto metric = std::find_if(rec.metrics.begin(), rec.metrics.end(), [](const auto& kv) {
      return kv.first == "contour_rms" || kv.first.ends_with(".contour_rms");
    });
    ASSERT_NE(metric, rec.metrics.end());
    EXPECT_TRUE(close(std::stod(m[1]), metric->second, 1e-9)) << m[1] << " vs " << metric->second;
  }

  // 2. A CSV of raw inputs (the export's columns; from standstill for narx).
  const DeployedModel model = load_deployed_model(dir / result, {dir / "data", nullptr});
  const PredictionInput data =
      dataset_input(read_dataset(dir / rec.dataset_file), InputKind::dataset_file, "data");
  const std::vector<std::size_t>& part = narx ? rec.split.validation : rec.split.test;
  std::vector<std::string> names = model.export_input_names();
  if (narx) {
    for (const char* c : {"ref_x", "ref_y", "d1_x", "d1_y", "d2_x", "d2_y"}) names.push_back(c);
  }
  std::vector<NamedColumn> raw;
  Eigen::MatrixXd x(static_cast<Eigen::Index>(model.num_inputs()),
                    static_cast<Eigen::Index>(part.size()));
  for (std::size_t j = 0; j < names.size(); ++j) {
    const NamedColumn* c = data.find(names[j]);
    ASSERT_NE(c, nullptr) << names[j];
    NamedColumn col{c->name, c->unit, Eigen::VectorXd(static_cast<Eigen::Index>(part.size()))};
    for (std::size_t s = 0; s < part.size(); ++s) {
      col.values[static_cast<Eigen::Index>(s)] = c->values[static_cast<Eigen::Index>(part[s])];
    }
    if (j < model.num_inputs()) x.row(static_cast<Eigen::Index>(j)) = col.values.transpose();
    raw.push_back(std::move(col));
  }
  std::ofstream(dir / "raw.csv") << csv_text({"raw inputs"}, raw);
  r = testing::cnclab(dir.path(), "predict " + result + " raw.csv -o raw_pred.csv -q");
  ASSERT_EQ(r.code, 0) << r.err << r.out;
  const auto predicted = read_csv_table(dir / "raw_pred.csv");
  std::vector<Eigen::VectorXd> expected;  // per output column of the export (+ contour)
  for (const auto& name : model.export_output_names()) {
    expected.push_back(
        find_column(predicted, name + (narx ? ".closed_loop" : ".predicted")).values);
  }
  if (narx) expected.push_back(find_column(predicted, "contour_error.closed_loop").values);

  // 3. The C export, double: gcc and clang, a NaN row refused in between.
  const std::string name = export_identifier(rec.experiment);
  const Eigen::Index rows = static_cast<Eigen::Index>(part.size()), nan_row = rows / 3;
  {
    std::ofstream in(dir / "in.txt");
    for (Eigen::Index s = 0; s < rows; ++s) {
      if (s == nan_row) {
        for (std::size_t j = 0; j < raw.size(); ++j) in << "nan ";
        in << "\n";
      }
      for (const auto& c : raw) in << hex_double(c.values[s]) << " ";
      in << "\n";
    }
  }
  std::ofstream(dir / "harness.c") << harness(name, narx, narx);
  const auto check_c = [&](const std::string& out_dir, const std::string& compiler, bool is_float) {
    const std::string binary = out_dir + "/" + compiler + ".run";
    const auto c = sh(compiler + " -std=c99 -Wall -Wextra -Werror -pedantic -O2 -I" + out_dir +
                      " harness.c " + out_dir + "/" + name + ".c -lm -o " + binary);
    ASSERT_EQ(c.code, 0) << compiler << ":\n" << c.err << c.out;
    const auto run = sh(binary + " < in.txt");
    ASSERT_EQ(run.code, 0) << run.err;
    std::istringstream lines(run.out);
    std::vector<std::string> text;
    for (std::string l; std::getline(lines, l);) text.push_back(l);
    ASSERT_EQ(text.size(), static_cast<std::size_t>(rows + 1));
    EXPECT_EQ(text[static_cast<std::size_t>(nan_row)], "error");
    text.erase(text.begin() + nan_row);
    Eigen::MatrixXd bound;
    if (is_float) bound = float_error_bound(model, x);
    const auto stated = is_float ? stated_bounds(testing::slurp(dir / out_dir / (name + ".h")))
                                 : std::map<std::string, double>{};
    const auto out_names = model.export_output_names();
    for (Eigen::Index s = 0; s < rows; ++s) {
      std::istringstream cells(text[static_cast<std::size_t>(s)]);
      for (std::size_t k = 0; k < expected.size(); ++k) {
        std::string cell;
        cells >> cell;
        const double got = std::strtod(cell.c_str(), nullptr), want = expected[k][s];
        if (!is_float) {
          ASSERT_TRUE(close(got, want))
              << compiler << " column " << k << " row " << s << ": " << got << " vs " << want;
        } else if (k < out_names.size()) {
          const auto i = static_cast<Eigen::Index>(k);
          ASSERT_LE(std::abs(got - want), bound(i, s)) << "float column " << k << " row " << s;
          ASSERT_LE(std::abs(got - want), stated.at(out_names[k])) << out_names[k];
        }
      }
    }
  };
  r = testing::cnclab(dir.path(), "export " + result + " --format c -o c64 --data-dir data -q");
  ASSERT_EQ(r.code, 0) << r.err << r.out;
  const std::string source = testing::slurp(dir / "c64" / (name + ".c"));
  EXPECT_EQ(source.find("malloc"), std::string::npos);
  const std::regex include(R"(#include [<"]([^>"]+)[>"])");
  for (std::sregex_iterator it(source.begin(), source.end(), include), end; it != end; ++it) {
    EXPECT_TRUE((*it)[1] == "math.h" || (*it)[1] == name + ".h") << (*it)[1];
  }
  const CCodeContext c64{name, CPrecision::float64};
  const Eigen::VectorXd& first = narx ? model.networks[0].parameters : model.parameters;
  for (Eigen::Index i = 0; i < first.size(); ++i) {  // exact literals of the weights
    ASSERT_NE(source.find(c64.literal(first[i])), std::string::npos) << first[i];
  }
  check_c("c64", "gcc", false);
  if (testing::have("clang --version")) {
    check_c("c64", "clang", false);
  } else {
    ADD_FAILURE() << "clang is not installed (scripts/setup installs it for the tests)";
  }
  // The object: read-only data and code only, calls into <math.h> only.
  const auto nm = sh("gcc -std=c99 -O2 -c c64/" + name + ".c -o c64/obj.o && nm c64/obj.o");
  ASSERT_EQ(nm.code, 0) << nm.err;
  std::istringstream symbols(nm.out);
  for (std::string line; std::getline(symbols, line);) {
    const std::string type = line.size() > 17 ? line.substr(17, 1) : line.substr(0, 1);
    const std::string symbol = line.substr(line.rfind(' ') + 1);
    EXPECT_TRUE(type != "D" && type != "d" && type != "B" && type != "b" && type != "C")
        << "writable global: " << line;
    if (line.find(" U ") != std::string::npos) {
      EXPECT_TRUE(std::regex_match(symbol, std::regex("(tanh|exp|sqrt|fabs)f?"))) << line;
    }
  }

  // 4. Float: within the bound.
  r = testing::cnclab(
      dir.path(), "export " + result + " --format c --precision float -o c32 --data-dir data -q");
  ASSERT_EQ(r.code, 0) << r.err << r.out;
  EXPECT_NE(r.out.find(": B = "), std::string::npos) << r.out;
  check_c("c32", "gcc", true);

  // 5. A controller: Cortex-M4 with its single-precision FPU.
  if (testing::have("arm-none-eabi-gcc --version")) {
    for (const char* precision : {"c64", "c32"}) {
      const auto arm = sh(std::string("arm-none-eabi-gcc -mcpu=cortex-m4 -mfloat-abi=hard -O2 "
                                      "-std=c99 -Wall -Wextra -Werror -pedantic -c ") +
                          precision + "/" + name + ".c -o " + precision +
                          "/arm.o && "
                          "arm-none-eabi-size -A " +
                          precision + "/arm.o");
      ASSERT_EQ(arm.code, 0) << arm.err << arm.out;
      std::cout << kc.label << " " << precision << " Cortex-M4 sections:\n" << arm.out;
    }
  } else {
    ADD_FAILURE() << "arm-none-eabi-gcc is not installed (scripts/setup installs it for the tests)";
  }

  // 6. PyTorch, float64.
  if (!testing::have("/usr/bin/python3 -c 'import torch'")) {
    GTEST_SKIP() << "python3-torch is not installed: the torch export is not checked "
                    "(scripts/setup installs it for the tests)";
  }
  r = testing::cnclab(dir.path(), "export " + result + " --format torch -o py --data-dir data -q");
  ASSERT_EQ(r.code, 0) << r.err << r.out;
  const auto torch =
      sh("/usr/bin/python3 " CNCLAB_SOURCE_DIR "/tests/deploy/torch_export_check.py py/" + name +
         ".py " + name + " raw.csv raw_pred.csv");
  EXPECT_EQ(torch.code, 0) << torch.out << torch.err;
}

// A path config (seed 002's dataset config, another path): planned,
// simulated and predicted in one command, the network fed the new path's
// physical velocities through the training ranges (its dataset scales them
// over other ranges), so it predicts what a CSV of those velocities does.
TEST(DeployNarx, ANewPathConfigIsPredictedThroughTheTrainingRanges) {
  register_study_once();
  TempDir dir;
  const std::string result = testing::train(dir.path(), testing::kNarx);
  ASSERT_FALSE(result.empty());
  const std::string config = CNCLAB_SOURCE_DIR
      "/experiments/contour_error/narx.yaml dataset.options.path.control_points=12 "
      "dataset.options.runs=2 dataset.options.samples=900 dataset.seed=77";
  auto r = testing::cnclab(dir.path(), "predict " + result + " " + config +
                                           " --initial rest -o path.h5 --data-dir data -q");
  ASSERT_EQ(r.code, 0) << r.err << r.out;
  EXPECT_NE(r.out.find("inputs: the physical columns v_ref_x [mm/s], v_ref_y [mm/s]"),
            std::string::npos)
      << r.out;
  const H5File f = H5File::open_read(dir / "path.h5");
  EXPECT_EQ(f.attribute_string("/provenance", "input_kind"), "dataset config");
  const auto names = f.read_strings("/columns");
  for (const char* c : {"contour_error.closed_loop", "contour_error.open_loop",
                        "contour_error.measured", "e_ref_x.open_loop", "e_ref_y.measured"}) {
    EXPECT_NE(std::find(names.begin(), names.end(), c), names.end()) << c;
  }
  // The new path's dataset (now in the cache) as a CSV of its velocities and
  // geometry: the same predictions.
  std::filesystem::path generated;
  for (const auto& e : std::filesystem::directory_iterator(dir / "data")) {
    if (!e.is_regular_file()) continue;  // narx-stages/: the trained stages
    const Dataset d = read_dataset(e.path());
    if (d.num_samples() == 900) generated = e.path();
  }
  ASSERT_FALSE(generated.empty());
  const Dataset d = read_dataset(generated);
  const DeployedModel model = load_deployed_model(dir / result, {dir / "data", nullptr});
  const PredictionInput in = dataset_input(d, InputKind::dataset_file, "new path");
  const double own_scaled = in.find("v_x")->values[100];
  EXPECT_NE(own_scaled, model.physical_inputs[0].to_dataset(in.find("v_ref_x")->values[100]))
      << "the two paths' velocity ranges should differ for this test to mean anything";
  std::vector<NamedColumn> csv;
  for (const char* c : {"v_ref_x", "v_ref_y", "ref_x", "ref_y", "d1_x", "d1_y", "d2_x", "d2_y"}) {
    csv.push_back(*in.find(c));
  }
  std::ofstream(dir / "path.csv") << csv_text({}, csv);
  r = testing::cnclab(dir.path(), "predict " + result + " path.csv -o csv.h5 -q");
  ASSERT_EQ(r.code, 0) << r.err << r.out;
  for (const char* c :
       {"e_ref_x.closed_loop", "e_ref_y.closed_loop", "contour_error.closed_loop"}) {
    EXPECT_EQ(h5_column(dir / "path.h5", c), h5_column(dir / "csv.h5", c)) << c;
  }
}

INSTANTIATE_TEST_SUITE_P(EveryModelKind, DeployKind,
                         ::testing::Values(KindCase{"StepErrorMlp", testing::kStepErrorMlp, "test"},
                                           KindCase{"IkMlp", testing::kIkMlp, "test"},
                                           KindCase{"Narx", testing::kNarx, "validation"}),
                         [](const ::testing::TestParamInfo<KindCase>& info) {
                           return info.param.label;
                         });

}  // namespace
}  // namespace cnclab
