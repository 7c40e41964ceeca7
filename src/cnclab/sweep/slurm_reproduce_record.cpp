#include "cnclab/sweep/slurm_reproduce_record.hpp"

#include <yaml-cpp/yaml.h>

#include "cnclab/core/error.hpp"
#include "cnclab/io/atomic_file.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

constexpr const char* kReproduceRecordFile = "jobs.yaml";

std::string reproduce_record_text(const YAML::Node& node, const char* key) {
  return node[key] ? node[key].as<std::string>() : std::string();
}

}  // namespace

fs::path reproduce_slurm_dir(const fs::path& results_dir) {
  return results_dir / "reproduce-slurm";
}

std::string reproduce_file_key(const fs::path& file) {
  return fs::absolute(file).lexically_normal().string();
}

ReproduceRecord read_reproduce_record(const fs::path& results_dir) {
  const fs::path file = reproduce_slurm_dir(results_dir) / kReproduceRecordFile;
  std::error_code ec;
  if (!fs::exists(file, ec)) return {};
  ReproduceRecord record;
  try {
    const YAML::Node root = YAML::LoadFile(file.string());
    for (const auto& item : root["jobs"]) {
      ReproduceJobEntry e;
      e.name = reproduce_record_text(item, "name");
      e.output = reproduce_record_text(item, "output");
      e.job = item["job"].as<std::string>();
      e.array = reproduce_record_text(item, "array");
      e.script = reproduce_record_text(item, "script");
      record[item["file"].as<std::string>()] = e;
    }
  } catch (const YAML::Exception& e) {
    throw IoError(file.string() +
                  ": not a reproduce --slurm record (jobs: [{file, job, ...}]): " + e.what());
  }
  return record;
}

void write_reproduce_record(const fs::path& results_dir, const ReproduceRecord& record) {
  YAML::Emitter out;
  out << YAML::BeginMap << YAML::Key << "jobs" << YAML::Value << YAML::BeginSeq;
  for (const auto& [file, e] : record) {
    out << YAML::BeginMap << YAML::Key << "file" << YAML::Value << file;
    out << YAML::Key << "name" << YAML::Value << e.name;
    out << YAML::Key << "output" << YAML::Value << e.output;
    out << YAML::Key << "job" << YAML::Value << e.job;
    out << YAML::Key << "array" << YAML::Value << e.array;
    out << YAML::Key << "script" << YAML::Value << e.script << YAML::EndMap;
  }
  out << YAML::EndSeq << YAML::EndMap;
  const fs::path dir = reproduce_slurm_dir(results_dir);
  std::error_code ec;
  fs::create_directories(dir, ec);
  write_text_atomically(dir / kReproduceRecordFile, std::string(out.c_str()) + "\n");
}

}  // namespace cnclab
