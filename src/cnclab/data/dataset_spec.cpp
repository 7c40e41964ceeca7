#include "cnclab/data/dataset_spec.hpp"

#include "cnclab/data/generator_registry.hpp"

namespace cnclab {
namespace {

FieldInfo generator_info() {
  FieldInfo i;
  i.key = "generator";
  i.doc = "the dataset generator (required; fragments in configs/datasets/)";
  i.kind = FieldKind::string;
  std::vector<std::string> names;
  for (const auto& g : known_generators()) names.push_back(g.name);
  i.rule = Rule::one_of(names);
  i.required = true;
  return i;
}

FieldInfo options_info() {
  FieldInfo i;
  i.key = "options";
  i.doc = "the generator's options (keys per generator; defaults filled in)";
  i.kind = FieldKind::any;
  return i;
}

}  // namespace

const FieldList<DatasetSpec>& dataset_fields() {
  using D = DatasetSpec;
  static const auto fields =
      FieldList<D>()
          // read_generator reads `generator` and its `options` together: the
          // options' keys depend on the generator.
          .custom(
              generator_info(),
              [](const ConfigReader& r, D& s) { s.generator = read_generator(r); },
              [](const D& s) {
                return s.generator ? YAML::Node(s.generator->name()) : YAML::Node();
              })
          .field("seed", &D::seed, "generator seed; absent: derived from the experiment seed")
          .field("targets", &D::targets,
                 "the generator's targets the model learns, in this order, e.g. [X] (one "
                 "network per output); empty = all")
          .omit_default()
          .custom(
              options_info(), [](const ConfigReader&, D&) {},  // read with `generator`
              [](const D& s) {
                return s.generator ? YAML::Load(s.generator->options_yaml()) : YAML::Node();
              });
  return fields;
}

DatasetSpec read_dataset_spec(const ConfigReader& r) {
  DatasetSpec spec;
  dataset_fields().read(r, spec);
  return spec;
}

}  // namespace cnclab
