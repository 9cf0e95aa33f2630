#include "io/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "core/error.h"

namespace hm {
namespace {

std::string temp_name_for(const std::filesystem::path& target) {
  static std::atomic<unsigned> counter{0};
  // Built by appends: GCC 12 warns falsely (-Wrestrict) on "." + std::string&&.
  std::string name = ".";
  name += target.filename().string();
  name += ".tmp.";
  name += std::to_string(::getpid());
  name += '.';
  name += std::to_string(counter++);
  return (target.parent_path() / name).string();
}

void sync_file(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd >= 0) {
    ::fsync(fd);
    ::close(fd);
  }
}

}  // namespace

void write_file_atomically(const std::string& path,
                           const std::function<void(std::ostream&)>& write) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  if (target.filename().empty()) throw IoError(path + ": not a file name");
  const fs::path folder = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  std::error_code ec;
  if (!fs::is_directory(folder, ec))
    throw IoError(path + ": folder " + folder.string() + " does not exist");
  const std::string temp =
      temp_name_for(target.parent_path().empty() ? fs::path(".") / target : target);
  try {
    {
      std::ofstream out(temp, std::ios::binary | std::ios::trunc);
      if (!out)
        throw IoError(path + ": cannot create a file in " + folder.string() + " (" +
                      std::strerror(errno) + ")");
      write(out);
      out.flush();
      if (!out) throw IoError(path + ": write failed (disk full?)");
    }
    sync_file(temp);
    if (std::rename(temp.c_str(), path.c_str()) != 0)
      throw IoError(path + ": cannot rename the finished file into place (" + std::strerror(errno) +
                    ")");
  } catch (...) {
    std::remove(temp.c_str());
    throw;
  }
}

}  // namespace hm
