#pragma once
// How far a float export's outputs can lie from the double ones: a running
// error bound (Higham, Accuracy and Stability of Numerical Algorithms, 2nd
// ed., Secs. 2.2 and 3.1). Every value the exported code computes carries
// a bound E on its absolute error, carried through the very operations, in
// the very order, of the C code (c_export.hpp):
//   stored constant c       E = u |c|       (rounded once to float)
//   input x                 E = u |x|       (the caller's double rounded to float)
//   a + b, a - b            E = Ea + Eb + u (|a + b| + Ea + Eb)
//   a b                     E = |a| Eb + |b| Ea + Ea Eb + u (|a b| + ...)
//   a / b  (|b| > Eb)       E = (Ea + |a / b| Eb) / (|b| - Eb) + u (|a / b| + ...)
//   tanh z                  E = Ez max|tanh'| over [z - Ez, z + Ez] + m 2u |tanh z|
//   exp z                   E = exp(z) (exp(Ez) - 1) + m 2u exp(z)
//   relu z                  E = Ez
// with u = 2^-24 + 2^-53 (float's unit roundoff plus double's, so the bound
// holds against the double computation, not only the exact one) and m the
// math library's accuracy in ulps (glibc documents tanhf and expf within 2;
// 4 is assumed). Each rounding's bound uses the computed value's magnitude
// |v| + E. The bound is rigorous for round-to-nearest arithmetic (a fused
// multiply-add only lowers the error); a narx network's bound is carried
// tick by tick through its fed-back outputs, so it shows how a closed loop
// amplifies rounding.
#include <Eigen/Core>

#include "cnclab/deploy/deployed_model.hpp"

namespace cnclab {

struct FloatBoundOptions {
  double unit_roundoff = 0x1p-24 + 0x1p-53;  // u (see above)
  double math_ulps = 4.0;                    // m: tanhf, expf accuracy in ulps
};

// Per output (rows) and sample (columns): the bound on |float - double| of
// the float export's outputs for the inputs `x` (model.num_inputs() x
// samples, in the export's input units: the dataset's for an mlp; the
// physical ones for a narx model that has them, its ticks from standstill).
Eigen::MatrixXd float_error_bound(const DeployedModel& model, const Eigen::MatrixXd& x,
                                  const FloatBoundOptions& options = {});

}  // namespace cnclab
