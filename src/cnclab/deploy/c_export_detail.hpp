#pragma once
// Pieces the C export's mlp and narx writers share (c_export.cpp,
// c_export_narx.cpp); not part of the module's interface.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "cnclab/deploy/c_export.hpp"
#include "cnclab/deploy/sequence_extension.hpp"
#include "cnclab/nn/activation.hpp"

namespace cnclab::c_export_detail {

// `static const NAME_real NAME_<name>[d0][d1]... = {...};` of `values` in
// row-major order of `dims`, kLiteralsPerLine literals a line.
class ArrayWriter {
 public:
  explicit ArrayWriter(const CCodeContext& c) : c_(c) {}
  std::string operator()(const std::string& name, const std::vector<std::size_t>& dims,
                         const std::vector<double>& values) const;

 private:
  std::string nested(const std::vector<std::size_t>& dims, std::size_t level,
                     const std::vector<double>& values, std::size_t& next, int indent) const;
  const CCodeContext& c_;
};

std::vector<double> values_of(const Eigen::VectorXd& v);

// f(z) of nn/activation.cpp as a C expression of the expression `z`.
std::string activation(Activation f, const std::string& z, const CCodeContext& c);

// NAME.h up to its typedef of NAME_real: the comment header (the model's
// description, the extension's, the precision, `notes`, the usage lines
// `use`) and the include guard's opening.
std::string header_top(const DeployedModel& m, const CCodeContext& c,
                       const std::vector<std::string>& notes, const ExtraCode& extra,
                       const std::vector<std::string>& use);

// The first lines of NAME.c: what it is and its includes.
std::string source_top(const CCodeContext& c);

// The narx model's NAME.h and NAME.c (c_export_narx.cpp).
CExport narx_export(const DeployedModel& m, const CCodeContext& c,
                    const std::vector<std::string>& notes);

}  // namespace cnclab::c_export_detail
