#pragma once
// The simulated machine's config keys, declared once (core/fields.hpp): the
// reader, the emitter (hence the dataset identity of following_error), the
// schema and the docs of `machine:` (configs/machines/*.yaml) come from here.
#include "cnclab/core/fields.hpp"
#include "cnclab/motion/feed_drive.hpp"
#include "cnclab/motion/machine.hpp"

namespace cnclab {

// timing: controller_period, velocity_loop_period, integration_step.
const FieldList<DriveTiming>& drive_timing_fields();
// One feed drive (axes.x, axes.y): mechanics, friction, transmission
// errors, control gains and measurement (feed_drive.hpp has the model).
const FieldList<FeedDriveOptions>& feed_drive_fields();
// machine: name, timing, axes.{x, y}.
const FieldList<MachineOptions>& machine_fields();

}  // namespace cnclab
