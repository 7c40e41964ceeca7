#include "cnclab/nn/scaling.hpp"

#include "cnclab/core/enum_names.hpp"
#include "cnclab/nn/zscore.hpp"

namespace cnclab {
namespace {

constexpr EnumName<Scaling> kScalingNames[] = {
    {Scaling::zscore, "zscore"}, {Scaling::minmax, "minmax"}, {Scaling::none, "none"}};

}  // namespace

std::string to_string(Scaling s) {
  return enum_name(kScalingNames, s);
}

bool parse_scaling(const std::string& text, Scaling& s) {
  const auto parsed = enum_value(kScalingNames, text);
  if (parsed) s = *parsed;
  return parsed.has_value();
}

ScalingRecord ScalingRecord::fit(Scaling method, const Eigen::MatrixXd& train,
                                 const std::array<double, 2>& range) {
  ScalingRecord r;
  r.method = method;
  if (method == Scaling::zscore) {
    ZScoreNormaliser z;
    z.fit(train);
    r.mean = z.mean();
    r.std = z.std();
  } else if (method == Scaling::minmax) {
    MinMaxNormaliser m(range[0], range[1]);
    m.fit(train);
    r.min = m.x_min();
    r.max = m.x_max();
    r.y_min = range[0];
    r.y_max = range[1];
  }
  return r;
}

// `map` applied to the record's normaliser (transform or inverse_transform);
// the data unchanged for Scaling::none.
template <class Map>
Eigen::MatrixXd ScalingRecord::apply(const Eigen::MatrixXd& data, Map map) const {
  switch (method) {
    case Scaling::zscore:
      return map(ZScoreNormaliser(mean, std), data);
    case Scaling::minmax:
      return map(MinMaxNormaliser(min, max, y_min, y_max), data);
    case Scaling::none:
      break;
  }
  return data;
}

Eigen::MatrixXd ScalingRecord::transform(const Eigen::MatrixXd& data) const {
  return apply(data, [](const auto& n, const Eigen::MatrixXd& d) { return n.transform(d); });
}

Eigen::MatrixXd ScalingRecord::inverse_transform(const Eigen::MatrixXd& scaled) const {
  return apply(scaled,
               [](const auto& n, const Eigen::MatrixXd& d) { return n.inverse_transform(d); });
}

}  // namespace cnclab
