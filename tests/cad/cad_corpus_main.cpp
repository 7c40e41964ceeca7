// cnclab_cad_corpus_check FILE...: every face of each STEP/IGES file through
// the step-error dataset path, checked against OCCT (cad_corpus_check.hpp),
// with unreachable: refuse (the default) and unreachable: clip. Prints per
// file the CAD system, faces, curved faces, the curved faces that give a
// dataset under each policy and the refusals by reason; then the totals.
// Exit 1 when any dataset disagrees with the independent check or any
// refusal lacks the face or line, 2 on bad usage. Run by
// scripts/check_cad_corpus.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "cad/cad_corpus_check.hpp"

namespace {

using cnclab::testing::FaceCheck;
using cnclab::testing::FileCheck;

struct Tally {
  std::size_t faces = 0, curved = 0, curved_usable = 0, samples = 0, disagreements = 0;
  double max_deviation_um = 0, max_step_error_um = 0;
  std::map<std::string, std::size_t> refusals;
};

Tally tally(const std::vector<FaceCheck>& faces) {
  Tally t;
  for (const FaceCheck& f : faces) {
    ++t.faces;
    t.curved += f.curved;
    if (f.outcome == "dataset") {
      t.curved_usable += f.curved;
      t.samples += f.samples;
      t.max_deviation_um = std::max(t.max_deviation_um, f.max_deviation_um);
      t.max_step_error_um = std::max(t.max_step_error_um, f.max_step_error_um);
    } else {
      ++t.refusals[f.outcome];
    }
    t.disagreements += !f.disagreement.empty();
  }
  return t;
}

std::string share(std::size_t part, std::size_t whole) {
  char text[64];
  std::snprintf(text, sizeof text, "%zu (%.0f %%)", part,
                whole ? 100.0 * static_cast<double>(part) / static_cast<double>(whole) : 0.0);
  return text;
}

std::string reasons(const Tally& t) {
  std::string out;
  for (const auto& [reason, count] : t.refusals) {
    out.append(out.empty() ? "" : ", ").append(reason).append(" ").append(std::to_string(count));
  }
  return out.empty() ? "none" : out;
}

void add(Tally& total, const Tally& t) {
  total.faces += t.faces;
  total.curved += t.curved;
  total.curved_usable += t.curved_usable;
  total.samples += t.samples;
  total.disagreements += t.disagreements;
  total.max_deviation_um = std::max(total.max_deviation_um, t.max_deviation_um);
  total.max_step_error_um = std::max(total.max_step_error_um, t.max_step_error_um);
  for (const auto& [reason, count] : t.refusals) total.refusals[reason] += count;
}

[[noreturn]] void usage(const char* problem) {
  std::fprintf(stderr,
               "cnclab_cad_corpus_check: %s\nusage: cnclab_cad_corpus_check [--path LxM] "
               "[--tool-radius R] [--samples N] [--verbose] FILE...\n",
               problem);
  std::exit(2);
}

}  // namespace

int main(int argc, char** argv) {
  cnclab::testing::CorpusOptions o;
  bool verbose = false;
  std::vector<std::filesystem::path> files;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool has_value = i + 1 < argc;
    if (a == "--path" && has_value) {
      if (std::sscanf(argv[++i], "%zux%zu", &o.lines, &o.points_per_line) != 2) usage("bad --path");
    } else if (a == "--tool-radius" && has_value) {
      o.tool_radius = std::atof(argv[++i]);
    } else if (a == "--samples" && has_value) {
      o.checked_samples = static_cast<std::size_t>(std::atol(argv[++i]));
    } else if (a == "--verbose") {
      verbose = true;
    } else if (a.starts_with("--")) {
      usage(("unknown option " + a).c_str());
    } else {
      files.emplace_back(a);
    }
  }
  if (files.empty()) usage("no files");
  std::printf(
      "path %zu x %zu, R = %g mm, tool axis +z, max normal angle 85 deg, %zu samples "
      "per dataset checked against OCCT\n",
      o.lines, o.points_per_line, o.tool_radius, o.checked_samples);
  Tally total_refuse, total_clip;
  std::size_t unreadable = 0;
  for (const auto& file : files) {
    const FileCheck c = cnclab::testing::check_cad_file(file, o);
    std::printf("\n%s\n", file.filename().c_str());
    if (!c.read_error.empty()) {
      std::printf("  not read: %s\n", c.read_error.c_str());
      ++unreadable;
      continue;
    }
    const Tally r = tally(c.refuse), k = tally(c.clip);
    std::printf("  CAD system: %s; unit %s; %zu faces, %zu curved\n",
                c.writer.empty() ? "(not given)" : c.writer.c_str(), c.unit.c_str(), r.faces,
                r.curved);
    std::printf(
        "  curved faces usable: %s as is (unreachable: refuse), %s with unreachable: clip\n",
        share(r.curved_usable, r.curved).c_str(), share(k.curved_usable, k.curved).c_str());
    std::printf("  refusals as is: %s\n  refusals with clip: %s\n", reasons(r).c_str(),
                reasons(k).c_str());
    std::printf(
        "  samples %zu (clip), largest step error %.4g um (R = %g mm), largest deviation "
        "from the dense check %.2g um, disagreements %zu\n",
        k.samples, k.max_step_error_um, o.tool_radius, k.max_deviation_um,
        r.disagreements + k.disagreements);
    for (const auto* faces : {&c.refuse, &c.clip}) {
      for (const FaceCheck& f : *faces) {
        if (!f.disagreement.empty()) {
          std::printf("  DISAGREES face %d (%s): %s\n", f.face, f.type.c_str(),
                      f.disagreement.c_str());
        } else if (verbose && faces == &c.clip && f.outcome != "dataset") {
          std::printf("  face %d (%s): %s\n", f.face, f.type.c_str(), f.message.c_str());
        }
      }
    }
    add(total_refuse, r);
    add(total_clip, k);
  }
  std::printf(
      "\ntotal: %zu files (%zu not read), %zu faces, %zu curved; curved usable %s as is, "
      "%s with clip; %zu samples, largest step error %.4g um, largest deviation %.2g um, "
      "disagreements %zu\n",
      files.size(), unreadable, total_refuse.faces, total_refuse.curved,
      share(total_refuse.curved_usable, total_refuse.curved).c_str(),
      share(total_clip.curved_usable, total_clip.curved).c_str(), total_clip.samples,
      total_clip.max_step_error_um, total_clip.max_deviation_um,
      total_refuse.disagreements + total_clip.disagreements);
  std::printf("refusals as is: %s\nrefusals with clip: %s\n", reasons(total_refuse).c_str(),
              reasons(total_clip).c_str());
  return total_refuse.disagreements + total_clip.disagreements > 0 ? 1 : 0;
}
