#include "cnclab/sweep/slurm_submission.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <tuple>

#include "cnclab/core/error.hpp"
#include "cnclab/io/atomic_file.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

constexpr const char* kSubmissionPrefix = "submit-";

// "submit-007" -> 7; nullopt for other names.
std::optional<std::size_t> submission_number(const std::string& name) {
  const std::string prefix = kSubmissionPrefix;
  if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) {
    return std::nullopt;
  }
  const std::string digits = name.substr(prefix.size());
  if (digits.find_first_not_of("0123456789") != std::string::npos) return std::nullopt;
  return static_cast<std::size_t>(std::stoul(digits));
}

std::string submission_name(std::size_t number) {
  std::string digits = std::to_string(number);
  if (digits.size() < 3) digits.insert(0, 3 - digits.size(), '0');
  return kSubmissionPrefix + digits;
}

std::vector<std::vector<std::string>> read_task_lists(const fs::path& file) {
  std::ifstream in(file);
  if (!in) throw IoError(file.string() + ": cannot read the submission's task list");
  std::vector<std::vector<std::string>> tasks;
  std::string line;
  while (std::getline(in, line)) {
    std::vector<std::string> ids;
    std::istringstream words(line);
    std::string id;
    while (std::getline(words, id, ',')) {
      if (!id.empty()) ids.push_back(id);
    }
    tasks.push_back(std::move(ids));
  }
  return tasks;
}

}  // namespace

std::vector<std::vector<std::string>> split_into_tasks(const std::vector<std::string>& ids,
                                                       std::size_t tasks) {
  const std::size_t n = tasks == 0 ? ids.size() : std::min(tasks, ids.size());
  std::vector<std::vector<std::string>> lists(n);
  for (std::size_t i = 0; i < ids.size(); ++i) lists[i % n].push_back(ids[i]);
  return lists;
}

std::pair<fs::path, std::size_t> create_submission_folder(const fs::path& root) {
  std::error_code ec;
  fs::create_directories(root, ec);
  if (ec) throw IoError(root.string() + ": cannot create the folder: " + ec.message());
  std::size_t next = 1;
  for (const auto& entry : fs::directory_iterator(root, ec)) {
    if (const auto n = submission_number(entry.path().filename().string())) {
      next = std::max(next, *n + 1);
    }
  }
  // create_directory fails on an existing folder: two submitters never share one.
  fs::path folder;
  for (;; ++next) {
    folder = root / submission_name(next);
    if (fs::create_directory(folder, ec)) break;
    if (ec) throw IoError(folder.string() + ": cannot create the folder: " + ec.message());
  }
  fs::create_directories(folder / "logs", ec);
  return {folder, next};
}

SlurmSubmission create_submission(const fs::path& dir,
                                  std::vector<std::vector<std::string>> tasks) {
  SlurmSubmission s;
  std::tie(s.folder, s.number) = create_submission_folder(dir / "slurm");
  std::string text;
  for (const auto& ids : tasks) {
    for (std::size_t k = 0; k < ids.size(); ++k) text += (k ? "," : "") + ids[k];
    text += "\n";
  }
  write_text_atomically(s.folder / "tasks.txt", text);
  s.tasks = std::move(tasks);
  return s;
}

void record_jobs(SlurmSubmission& submission, const std::string& array_job,
                 const std::string& merge_job) {
  YAML::Emitter out;
  out << YAML::BeginMap << YAML::Key << "array_job" << YAML::Value << array_job << YAML::Key
      << "merge_job" << YAML::Value << merge_job << YAML::Key << "tasks" << YAML::Value
      << submission.tasks.size() << YAML::EndMap;
  write_text_atomically(submission.folder / "job.yaml", std::string(out.c_str()) + "\n");
  submission.array_job = array_job;
  submission.merge_job = merge_job;
}

std::vector<SlurmSubmission> read_submissions(const fs::path& dir) {
  std::vector<SlurmSubmission> subs;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir / "slurm", ec)) {
    const auto n = submission_number(entry.path().filename().string());
    const fs::path job = entry.path() / "job.yaml";
    if (!n || !fs::exists(job, ec)) continue;
    SlurmSubmission s;
    s.folder = entry.path();
    s.number = *n;
    try {
      const YAML::Node y = YAML::LoadFile(job.string());
      s.array_job = y["array_job"].as<std::string>();
      s.merge_job = y["merge_job"] ? y["merge_job"].as<std::string>() : "";
    } catch (const YAML::Exception& e) {
      throw IoError(job.string() + ": not a submission record (array_job, merge_job): " + e.what());
    }
    s.tasks = read_task_lists(entry.path() / "tasks.txt");
    subs.push_back(std::move(s));
  }
  std::sort(subs.begin(), subs.end(),
            [](const SlurmSubmission& a, const SlurmSubmission& b) { return a.number < b.number; });
  return subs;
}

std::map<std::string, std::vector<TrialPlacement>> trial_placements(
    const std::vector<SlurmSubmission>& submissions) {
  std::map<std::string, std::vector<TrialPlacement>> where;
  for (const auto& s : submissions) {
    for (std::size_t k = 0; k < s.tasks.size(); ++k) {
      for (const auto& id : s.tasks[k]) where[id].push_back({&s, k});
    }
  }
  return where;
}

}  // namespace cnclab
