#include "cnclab/experiment/experiment_graph.hpp"

#include <algorithm>
#include <functional>
#include <map>

#include "cnclab/core/error.hpp"
#include "cnclab/data/dataset_cache.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

fs::path key_of(const fs::path& file) {
  std::error_code ec;
  const fs::path canonical = fs::weakly_canonical(file, ec);
  return ec ? file.lexically_normal() : canonical;
}

}  // namespace

std::vector<GraphNode> load_graph(const std::vector<fs::path>& files, const std::string& profile) {
  // Load everything reachable.
  std::vector<GraphNode> nodes;
  std::map<fs::path, std::size_t> index;
  std::vector<std::vector<fs::path>> needs;
  const std::function<std::size_t(const fs::path&, bool)> add = [&](const fs::path& file,
                                                                    bool requested) {
    const fs::path key = key_of(file);
    if (const auto it = index.find(key); it != index.end()) {
      nodes[it->second].requested = nodes[it->second].requested || requested;
      return it->second;
    }
    const std::size_t i = nodes.size();
    index[key] = i;
    nodes.push_back({file, std::nullopt, "", false, {}, requested});
    needs.emplace_back();
    try {
      nodes[i].experiment =
          load_experiment(file, std::vector<std::string>{}, std::nullopt, profile);
      needs[i] = upstream_files(nodes[i].experiment->spec);
    } catch (const ConfigError& e) {
      nodes[i].load_error = e.what();
      nodes[i].config_error = true;
    } catch (const Error& e) {
      nodes[i].load_error = e.what();
    }
    for (const auto& up : std::vector<fs::path>(needs[i])) {
      const std::size_t j = add(up, false);
      nodes[i].upstream.push_back(j);
    }
    return i;
  };
  for (const auto& f : files) add(f, true);

  // Depth-first topological order; a grey node met again closes a cycle.
  enum class Mark { white, grey, black };
  std::vector<Mark> mark(nodes.size(), Mark::white);
  std::vector<std::size_t> order, stack;
  const std::function<void(std::size_t)> visit = [&](std::size_t i) {
    if (mark[i] == Mark::black) return;
    if (mark[i] == Mark::grey) {
      std::string cycle;
      const auto from = std::find(stack.begin(), stack.end(), i);
      for (auto it = from; it != stack.end(); ++it) cycle += nodes[*it].file.string() + " -> ";
      throw ConfigError("experiment graph has a cycle: " + cycle + nodes[i].file.string());
    }
    mark[i] = Mark::grey;
    stack.push_back(i);
    for (std::size_t j : nodes[i].upstream) visit(j);
    stack.pop_back();
    mark[i] = Mark::black;
    order.push_back(i);
  };
  for (std::size_t i = 0; i < nodes.size(); ++i) visit(i);

  std::vector<std::size_t> position(nodes.size());
  for (std::size_t k = 0; k < order.size(); ++k) position[order[k]] = k;
  std::vector<GraphNode> sorted;
  for (std::size_t i : order) {
    GraphNode n = nodes[i];
    for (auto& j : n.upstream) j = position[j];
    sorted.push_back(std::move(n));
  }
  return sorted;
}

std::string staleness(const std::vector<UpstreamRef>& recorded,
                      const std::vector<CurrentUpstream>& upstream) {
  std::vector<std::string> identities;
  for (const auto& u : recorded) identities.push_back(u.identity);
  for (const auto& u : upstream) {
    if (std::find(identities.begin(), identities.end(), u.identity) == identities.end()) {
      return "upstream " + u.name + " changed";
    }
  }
  if (identities.size() != upstream.size()) return "its upstream experiments changed";
  return "";
}

CurrentResult current_result(const LoadedExperiment& exp,
                             const std::vector<CurrentUpstream>& upstream,
                             const ResultStore& store) {
  try {
    std::optional<StoredResult> stored = store.existing(result_key(exp));
    if (!stored) return {std::nullopt, "no result for this resolved config yet"};
    std::string why = staleness(stored->record.upstream, upstream);
    const fs::path dataset = dataset_cache_file(exp.spec.dataset, generator_seed(exp.spec), "");
    if (why.empty() && fs::path(stored->record.dataset_file).filename() != dataset.filename()) {
      why = "dataset generator changed (" + dataset.filename().string() + ")";
    }
    if (!why.empty()) return {std::nullopt, why};
    return {std::move(stored->record), ""};
  } catch (const OutdatedResult& e) {
    return {std::nullopt, std::string("older result (") + e.what() + ")"};
  } catch (const IoError& e) {
    return {std::nullopt, std::string("result unreadable (") + e.what() + ")"};
  }
}

}  // namespace cnclab
