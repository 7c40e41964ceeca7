#pragma once
// Inverse-kinematics samples of the TTTRR machine (seed 004 Sec. 4.2): tool
// poses in the workpiece frame as inputs, the machine's joint values from the
// closed-form IK (kinematics/tttrr.hpp) as targets.
//
// Inputs (5): Px, Py, Pz [mm] and the orientation's first two components
// Oi, Oj [1] (Ok = +sqrt(1 - Oi^2 - Oj^2): tool pointing away from the
// table). Seed 004 names its five inputs only as "coordinates"; the two
// orientation components are our choice: they determine O and leave the
// network the real work (A = asin(|(Oi, Oj)|), C = atan2(Oi, Oj)), where
// angle inputs would make the A and C targets copies of an input.
// Targets (5): X, Y, Z [mm], A, C [rad] on the configured A branch.
//
// Modes: `grid` - values_per_input equally spaced values per input over its
// range, all combinations (5 per input: 5^5 = 3125, the paper's count), the
// last input varying fastest; `uniform` - independent uniform draws;
// `latin_hypercube` - per input, one draw in each of `samples` equal strata,
// strata paired across inputs by independent random permutations.
#include <cstddef>
#include <memory>
#include <string>

#include "cnclab/core/config.hpp"
#include "cnclab/core/fields.hpp"
#include "cnclab/data/generator.hpp"
#include "cnclab/kinematics/tttrr.hpp"

namespace cnclab {

enum class SamplingMode { grid, uniform, latin_hypercube };

struct IkSamplesOptions {
  SamplingMode mode = SamplingMode::grid;
  std::size_t values_per_input = 5;  // grid: values per input (seed 004: 5^5 = 3125 samples)
  std::size_t samples = 3125;        // uniform / latin_hypercube: sample count
  // Input ranges, inclusive. Defaults keep Oi > 0: no pose at the A = 0
  // singularity and none on C's +-180 deg cut (where the IK target C jumps by
  // a full turn and no continuous network can follow).
  JointRange px{-50.0, 50.0}, py{-50.0, 50.0}, pz{0.0, 50.0};  // mm
  JointRange oi{0.1, 0.6}, oj{-0.5, 0.5};                      // 1
  ABranch branch = ABranch::positive;  // sign of A in the targets (Eq. 5's +-)
  TttrrOptions machine;

  // Counts >= 1 (grid: >= 2 values, at most 1e8 samples), ranges finite with
  // min <= max (min < max for grids with more than one value), Oi^2 + Oj^2
  // <= 1 at every corner of the orientation box, machine valid.
  void validate() const;
  std::size_t num_samples() const;
};

// Throws ConfigError naming the sample and pose when a pose is unreachable
// (joint limits): the ranges are then inconsistent with the machine.
Dataset generate_ik_samples(const IkSamplesOptions& options, Rng& rng);

class IkSamplesGenerator : public DatasetGenerator {
 public:
  explicit IkSamplesGenerator(IkSamplesOptions options);  // validates
  std::string name() const override { return "ik_samples"; }
  int version() const override { return 1; }
  DatasetShape shape() const override { return {options_.num_samples(), 5, 5}; }
  std::string options_yaml() const override;
  Dataset generate(Rng& rng) const override { return generate_ik_samples(options_, rng); }
  const IkSamplesOptions& options() const { return options_; }

 private:
  IkSamplesOptions options_;
};

// options: {mode, values_per_input, samples, ranges: {px, py, pz: [min, max]
// mm, oi, oj: [min, max]}, a_branch: positive|negative, machine: {...}
// (kinematics/tttrr_config.hpp)}
// dataset.options of `ik_samples`: {mode, values_per_input | samples, ranges, a_branch, machine}.
const FieldList<IkSamplesOptions>& ik_samples_fields();

std::shared_ptr<const DatasetGenerator> read_ik_samples(const ConfigReader& options);

}  // namespace cnclab
