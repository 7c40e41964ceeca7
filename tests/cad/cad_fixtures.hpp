#pragma once
// Step-error datasets of a surface given as YAML or as a CAD face, through
// the generator registry (the path an experiment takes).
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include "cnclab/core/config.hpp"
#include "cnclab/core/rng.hpp"
#include "cnclab/data/dataset.hpp"
#include "cnclab/data/generator.hpp"

namespace cnclab::testing {

inline constexpr double kDeg = std::numbers::pi / 180.0;  // one degree in radians
inline constexpr double kClosedFormTolUm = 1e-6;          // step error [µm] against a closed form

// A small tool path: `lines` x `points` CC points, R = `radius`, K = 3.
inline std::string step_error_config(const std::string& surface, std::size_t lines = 5,
                                     std::size_t points = 9, double radius = 5.0) {
  return "dataset:\n  generator: step_error\n  options:\n    surface: " + surface +
         "\n    lines: " + std::to_string(lines) +
         "\n    points_per_line: " + std::to_string(points) +
         "\n    tool_radius: " + std::to_string(radius) + "\n    curve_points: 3\n";
}

inline std::string cad_face(const std::filesystem::path& file, int face = 1) {
  return "{file: " + file.string() + ", face: " + std::to_string(face) + "}";
}

inline std::shared_ptr<const DatasetGenerator> step_error_generator(const std::string& config) {
  ConfigDocument doc = ConfigDocument::parse(config, "test.yaml");
  auto generator = read_generator(doc.root().section("dataset"));
  doc.check_all_consumed();
  return generator;
}

inline Dataset step_error_dataset(const std::string& config) {
  Rng unused(0);
  return step_error_generator(config)->generate(unused);
}

inline void write_file(const std::filesystem::path& file, const std::string& text) {
  std::ofstream(file, std::ios::binary) << text;
}

}  // namespace cnclab::testing
