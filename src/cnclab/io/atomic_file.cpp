#include "cnclab/io/atomic_file.hpp"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <chrono>
#include <cstring>
#include <fstream>
#include <limits>
#include <ostream>
#include <string_view>
#include <utility>

#include "cnclab/core/error.hpp"
#include "cnclab/core/hash.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

constexpr const char* kPartialMarker = ".partial-";

void fsync_path(const fs::path& path, bool directory) {
  const int fd = ::open(path.c_str(), directory ? (O_RDONLY | O_DIRECTORY) : O_RDONLY);
  if (fd < 0) throw IoError(path.string() + ": cannot open for fsync: " + std::strerror(errno));
  const int rc = ::fsync(fd);
  const int err = errno;
  ::close(fd);
  if (rc != 0) throw IoError(path.string() + ": fsync failed: " + std::strerror(err));
}

}  // namespace

AtomicOutput::AtomicOutput(fs::path final_path) : final_(std::move(final_path)) {
  if (final_.filename().empty()) throw IoError(final_.string() + ": not a file name");
  const fs::path dir = final_.parent_path().empty() ? fs::path(".") : final_.parent_path();
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw IoError(dir.string() + ": cannot create folder: " + ec.message());
  // Unique per process and call: pid plus a hash of the clock and this
  // object's address; a name that exists anyway (stale temporary of a
  // process with a recycled pid) is skipped.
  const auto now = std::chrono::steady_clock::now().time_since_epoch().count();
  for (std::uint64_t salt = 0;; ++salt) {
    const std::string tag =
        Hasher()
            .add(static_cast<std::uint64_t>(now))
            .add(static_cast<std::uint64_t>(reinterpret_cast<std::uintptr_t>(this)))
            .add(salt)
            .hex();
    // Built by appending: GCC 12 warns falsely (-Wrestrict, PR105329) on
    // `"literal" + std::string` chains.
    std::string name = ".";
    name += final_.filename().string();
    name += kPartialMarker;
    name += partial_host_name();
    name += "-";
    name += std::to_string(::getpid());
    name += "-";
    name += tag;
    temp_ = dir / name;
    if (!fs::exists(temp_, ec)) break;
  }
}

AtomicOutput::~AtomicOutput() {
  if (!committed_) {
    std::error_code ec;
    fs::remove(temp_, ec);
  }
}

void AtomicOutput::commit() {
  if (committed_) throw IoError(final_.string() + ": already committed");
  std::error_code ec;
  if (!fs::is_regular_file(temp_, ec)) {
    throw IoError(final_.string() + ": nothing to commit (" + temp_.string() + " was not written)");
  }
  fsync_path(temp_, false);
  if (std::rename(temp_.c_str(), final_.c_str()) != 0) {
    throw IoError(final_.string() + ": cannot rename " + temp_.string() +
                  " into place: " + std::strerror(errno));
  }
  committed_ = true;
  fsync_path(final_.parent_path().empty() ? fs::path(".") : final_.parent_path(), true);
}

bool is_partial_path(const fs::path& path) {
  return partial_writer(path).has_value();
}

std::optional<PartialWriter> partial_writer(const fs::path& path) {
  // ".<name>.partial-[<host>-]<pid>-<16 hex digits>", <name> non-empty.
  const std::string name = path.filename().string();
  const std::size_t marker = name.rfind(kPartialMarker);
  if (name.size() < 2 || name.front() != '.' || marker == std::string::npos || marker < 2) {
    return std::nullopt;
  }
  std::string_view rest = std::string_view(name).substr(marker + std::strlen(kPartialMarker));
  constexpr std::size_t kTag = 16;
  if (rest.size() < kTag + 2 || rest[rest.size() - kTag - 1] != '-') return std::nullopt;
  const std::string_view tag = rest.substr(rest.size() - kTag);
  rest.remove_suffix(kTag + 1);  // "[<host>-]<pid>"
  const std::size_t dash = rest.rfind('-');
  const std::string_view pid = dash == std::string_view::npos ? rest : rest.substr(dash + 1);
  const std::string_view host = dash == std::string_view::npos ? "" : rest.substr(0, dash);
  const auto is_digit = [](char c) { return c >= '0' && c <= '9'; };
  const auto is_hex = [&](char c) { return is_digit(c) || (c >= 'a' && c <= 'f'); };
  const auto is_host = [&](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_';
  };
  PartialWriter writer;
  if (!std::all_of(tag.begin(), tag.end(), is_hex) || pid.empty() ||
      !std::all_of(pid.begin(), pid.end(), is_digit) ||
      (dash != std::string_view::npos &&
       (host.empty() || !std::all_of(host.begin(), host.end(), is_host)))) {
    return std::nullopt;
  }
  const auto [end, ec] = std::from_chars(pid.data(), pid.data() + pid.size(), writer.pid);
  if (ec != std::errc() || end != pid.data() + pid.size()) return std::nullopt;
  writer.host = std::string(host);
  return writer;
}

std::string partial_host_name() {
  char buffer[256] = {};
  if (::gethostname(buffer, sizeof buffer - 1) != 0) return "localhost";
  std::string host(buffer);
  host.erase(std::min(host.find('.'), host.size()));
  for (char& c : host) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-') c = '_';
  }
  return host.empty() ? "localhost" : host;
}

PartialCleanup remove_stale_partials(const std::vector<fs::path>& folders,
                                     const std::string& host) {
  // Collected first, removed after: no removal while a folder is iterated.
  std::vector<std::pair<fs::path, PartialWriter>> partials;
  for (const auto& folder : folders) {
    std::error_code ec;
    if (!fs::is_directory(folder, ec)) continue;
    fs::recursive_directory_iterator it(folder, fs::directory_options::skip_permission_denied, ec);
    for (; !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
      std::error_code type_ec;
      if (!it->is_regular_file(type_ec)) continue;
      if (auto writer = partial_writer(it->path())) partials.emplace_back(it->path(), *writer);
    }
  }
  // A folder inside another one lists its files twice.
  const auto key = [](const fs::path& p) {
    std::error_code ec;
    return fs::absolute(p, ec).lexically_normal();
  };
  std::sort(partials.begin(), partials.end(),
            [&](const auto& a, const auto& b) { return key(a.first) < key(b.first); });
  partials.erase(
      std::unique(partials.begin(), partials.end(),
                  [&](const auto& a, const auto& b) { return key(a.first) == key(b.first); }),
      partials.end());

  PartialCleanup out;
  for (const auto& [path, writer] : partials) {
    // pid 0 and -1 would address a process group or every process.
    const bool checkable =
        writer.host == host && writer.pid > 0 && writer.pid <= std::numeric_limits<pid_t>::max();
    if (!checkable) {
      out.unknown.push_back(path);
      continue;
    }
    // Alive, or alive under another user (EPERM): its writer may still write.
    if (::kill(static_cast<pid_t>(writer.pid), 0) == 0 || errno != ESRCH) continue;
    std::error_code ec;
    if (fs::remove(path, ec)) {
      out.removed.push_back(path);
      out.removed_pids.push_back(writer.pid);
    }
  }
  std::sort(out.removed_pids.begin(), out.removed_pids.end());
  out.removed_pids.erase(std::unique(out.removed_pids.begin(), out.removed_pids.end()),
                         out.removed_pids.end());
  return out;
}

std::string PartialCleanup::summary() const {
  constexpr std::size_t kNamed = 3;  // paths named in the line; the rest counted
  const auto paths = [](const std::vector<fs::path>& files) {
    std::string text;
    for (std::size_t i = 0; i < files.size() && i < kNamed; ++i) {
      text += (i ? ", " : "") + files[i].string();
    }
    if (files.size() > kNamed) text += " and " + std::to_string(files.size() - kNamed) + " more";
    return text;
  };
  const auto count = [](std::size_t n) {
    return std::to_string(n) + (n == 1 ? " partial file" : " partial files");
  };
  std::string line;
  if (!removed.empty()) {
    std::string pids;
    for (const long long pid : removed_pids)
      pids += (pids.empty() ? "" : ", ") + std::to_string(pid);
    line = "removed " + count(removed.size()) + " of interrupted writes (writer " +
           (removed_pids.size() == 1 ? "pid " : "pids ") + pids +
           " no longer running): " + paths(removed);
  }
  if (!unknown.empty()) {
    line += (line.empty() ? "" : "; ") + std::string("kept ") + count(unknown.size()) +
            " whose writer cannot be checked here (written on another host, or by an older "
            "cnclab): " +
            paths(unknown) + "; remove them once nothing writes there";
  }
  return line;
}

void clean_stale_partials(const std::vector<fs::path>& folders, std::ostream& log) {
  const std::string line = remove_stale_partials(folders).summary();
  if (!line.empty()) log << line << "\n";
}

void write_text_atomically(const std::filesystem::path& path, const std::string& text) {
  AtomicOutput out(path);
  {
    std::ofstream f(out.temp_path(), std::ios::binary);
    f << text;
    f.flush();
    if (!f) throw IoError(path.string() + ": write failed (" + out.temp_path().string() + ")");
  }
  out.commit();
}

void copy_file_atomically(const fs::path& from, const fs::path& to) {
  std::error_code ec;
  // rename(2) does nothing when both names already link the same file,
  // which would leave the temporary behind.
  if (fs::equivalent(from, to, ec)) return;
  ec.clear();
  AtomicOutput out(to);
  fs::create_hard_link(from, out.temp_path(), ec);
  if (ec) {
    ec.clear();
    fs::copy_file(from, out.temp_path(), fs::copy_options::overwrite_existing, ec);
    if (ec) {
      throw IoError(to.string() + ": cannot copy " + from.string() + " (" + ec.message() + ")");
    }
  }
  out.commit();
}

}  // namespace cnclab
