#pragma once
// Text pieces the C and torch exports share: exact number literals, the
// identifier an export is named by, and the comment header that says which
// result it is.
#include <string>
#include <vector>

namespace cnclab {

struct DeployedModel;

// The arithmetic of a C export (`--precision`).
enum class CPrecision { float32, float64 };
// "float" / "double" (the option's values and the C type).
std::string to_string(CPrecision precision);
// ConfigError naming --precision unless "float" or "double".
CPrecision parse_precision(const std::string& text);

// What generated C code needs to write numbers and calls in its precision.
struct CCodeContext {
  std::string name;  // the export's identifier: NAME_step, NAME_state, ...
  CPrecision precision = CPrecision::float64;

  // The type of every number: "NAME_real" (typedef'd to float or double).
  std::string real() const { return name + "_real"; }
  // An exact literal of x in this precision: C99 hex-float text of x
  // ("0x1.8p+1"), or of x rounded to float with the suffix f ("0x1.8p+1f");
  // small whole numbers in decimal ("2.0", "2.0f"). x finite.
  std::string literal(double x) const;
  // A <math.h> function in this precision: "tanh" or "tanhf".
  std::string math(const std::string& function) const;
};

// C99 hex-float text of x that strtod reads back exactly ("%a": 0x1p-3,
// -0x1.5555555555555p-2, 0x0p+0). x finite.
std::string hex_double(double x);
// The same of float f, "%a" of the float widened (exact) with suffix f.
std::string hex_float(float f);

// A C and Python identifier from an experiment name: lower case, every
// character but [a-z0-9_] becomes '_', a leading digit gets "n_".
std::string export_identifier(const std::string& experiment_name);
// ConfigError naming --name unless `name` is a C identifier ([A-Za-z_][A-Za-z0-9_]*),
// at most 40 characters, and not a C99 keyword.
void check_export_identifier(const std::string& name);

// The lines that identify a model (result, experiment, identity, config
// hash, training dataset, trained when and by which cnclab, architecture,
// every metric of the result with its unit, the columns in and out), without
// comment markers: each export wraps them in its own comment syntax.
std::vector<std::string> model_description(const DeployedModel& model);

}  // namespace cnclab
