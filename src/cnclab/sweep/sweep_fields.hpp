#pragma once
// The keys of a sweep, declared once (core/fields.hpp): the `sweep:` block of
// an experiment file (or of a `kind: sweep` file) and the `kind: sweep` file's
// own keys. The readers, the emitter of a `kind: sweep` job (its result
// identity) and `cnclab schema` come from here.
#include <vector>

#include "cnclab/core/fields.hpp"
#include "cnclab/sweep/sweep_job.hpp"
#include "cnclab/sweep/sweep_spec.hpp"

namespace cnclab {

// method, trials, seed, repeats, objective {metric, mode}, parameters.
const FieldList<SweepSpec>& sweep_fields();

// A `kind: sweep` file after kind, name and description: experiment,
// overrides, jobs, sweep. The reader needs job.source_file set (experiment
// is resolved against its folder).
const FieldList<SweepJob>& sweep_job_fields();

// Every key of a `kind: sweep` file, for its schema.
std::vector<FieldInfo> sweep_file_fields();

}  // namespace cnclab
