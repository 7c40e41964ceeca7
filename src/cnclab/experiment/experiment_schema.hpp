#pragma once
// `cnclab schema`: a JSON Schema (draft 2020-12) of experiment files,
// generated from the field declarations (core/fields.hpp) of every section,
// the model types (model_spec.hpp), the trainers, the dataset generators
// (data/generator.hpp) and the registered job kinds (job_kinds.hpp).
//
// It describes one file as it is written and as the reader sees it after
// `include:` is merged (`cnclab validate FILE` prints that). The keys a file
// must have (dataset, model, trainer, a section's type, ...) are required
// only of a file without `include:`, whose includes may supply them (JSON
// Schema if/then); in either, unknown keys fail where the reader is strict.
// A section whose type or generator comes from an include has each key
// checked against every type's keys. An absent model.type means mlp in both:
// a file whose include sets `model.type: narx` and that sets narx keys names
// the type again.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cnclab/core/field_info.hpp"

namespace cnclab {

// The schema of a self-contained `kind: train` file (the default kind), as
// `experiment_file_schema` holds a file without include: to it. `sweep_block`,
// `slurm_block`: the declared keys of its `sweep:` and `slurm:` blocks
// (sweep/sweep_fields.hpp, sweep/slurm_fields.hpp; the sweep module sits
// above this one); empty: an open object.
nlohmann::json train_file_schema(const std::vector<FieldInfo>& sweep_block = {},
                                 const std::vector<FieldInfo>& slurm_block = {});

// The whole document schema: `kind` picks the train schema or a job kind's
// (its JobKind::schema, or an open object saying its keys are not declared
// yet). `kind` non-empty: that kind's schema alone, as a document. Throws
// ConfigError for an unknown kind.
nlohmann::json experiment_file_schema(const std::string& kind = "",
                                      const std::vector<FieldInfo>& sweep_block = {},
                                      const std::vector<FieldInfo>& slurm_block = {});

}  // namespace cnclab
