#include "cnclab/io/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <fstream>
#include <string_view>

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
  // ".<name>.partial-<pid>-<16 hex digits>", <name> non-empty.
  const std::string name = path.filename().string();
  const std::size_t marker = name.rfind(kPartialMarker);
  if (name.size() < 2 || name.front() != '.' || marker == std::string::npos || marker < 2) {
    return false;
  }
  const std::string_view rest = std::string_view(name).substr(marker + std::strlen(kPartialMarker));
  const std::size_t dash = rest.find('-');
  if (dash == 0 || dash == std::string_view::npos) return false;
  const auto is_digit = [](char c) { return c >= '0' && c <= '9'; };
  const auto is_hex = [&](char c) { return is_digit(c) || (c >= 'a' && c <= 'f'); };
  const std::string_view pid = rest.substr(0, dash), tag = rest.substr(dash + 1);
  return std::all_of(pid.begin(), pid.end(), is_digit) && tag.size() == 16 &&
         std::all_of(tag.begin(), tag.end(), is_hex);
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

}  // namespace cnclab
