#include "cnclab/io/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>

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
  const fs::path dir = final_.parent_path().empty() ? fs::path(".") : final_.parent_path();
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw IoError(dir.string() + ": cannot create folder: " + ec.message());
  // Unique per process and call: pid plus a hash of the clock and address.
  const auto now = std::chrono::steady_clock::now().time_since_epoch().count();
  const std::string tag =
      Hasher()
          .add(static_cast<std::uint64_t>(now))
          .add(static_cast<std::uint64_t>(reinterpret_cast<std::uintptr_t>(this)))
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
}

AtomicOutput::~AtomicOutput() {
  if (!committed_) {
    std::error_code ec;
    fs::remove(temp_, ec);
  }
}

void AtomicOutput::commit() {
  fsync_path(temp_, false);
  if (std::rename(temp_.c_str(), final_.c_str()) != 0) {
    throw IoError(final_.string() + ": cannot rename " + temp_.string() +
                  " into place: " + std::strerror(errno));
  }
  committed_ = true;
  fsync_path(final_.parent_path().empty() ? fs::path(".") : final_.parent_path(), true);
}

bool is_partial_path(const fs::path& path) {
  const std::string name = path.filename().string();
  return !name.empty() && name.front() == '.' && name.find(kPartialMarker) != std::string::npos;
}

}  // namespace cnclab
