#pragma once
// A trained network as C99 for a controller: NAME.h and NAME.c.
//
// - Every weight, bias and normalisation constant is a `static const` array
//   of exact hex-float literals (the trained doubles; in float, each rounded
//   once to float).
// - No dynamic memory and no global state: the only globals are those
//   constants; a narx model's delay lines live in the caller's NAME_state.
// - Only <math.h> (isfinite, tanh/exp and the extension's sqrt/fabs).
// - API (NAME_real is double or float, `--precision`):
//     mlp:  int NAME_predict(const NAME_real in[NAME_INPUTS], NAME_real out[NAME_OUTPUTS]);
//     narx: void NAME_init(NAME_state *s);   standstill, as NarxPredictor::reset
//           int NAME_step(NAME_state *s, const NAME_real in[NAME_NETWORKS],
//                         NAME_real out[NAME_NETWORKS]);
//   in the columns' own units (the physical ones where the model has them;
//   model_description lists them), the normalisation inside. They return 0,
//   or -1 when an input is NaN or infinite, leaving `out` and the state
//   unchanged (NarxPredictor's contract).
// - The arithmetic follows nn/mlp.cpp and nn/narx.cpp term by term, so the
//   double export agrees with `cnclab predict` to rounding (the order of a
//   dot product's sum; the tests hold it to 1e-12).
#include <string>
#include <vector>

#include "cnclab/deploy/code_text.hpp"
#include "cnclab/deploy/deployed_model.hpp"

namespace cnclab {

struct CExport {
  std::string header;  // NAME.h
  std::string source;  // NAME.c
};

// `notes`: more lines for the comment header (the float bound's statement).
CExport c_export(const DeployedModel& model, const CCodeContext& context,
                 const std::vector<std::string>& notes = {});

// NAME in upper case, for the macros (NAME_INPUTS, ...).
std::string macro_prefix(const std::string& name);

}  // namespace cnclab
