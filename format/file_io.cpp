#include "format/file_io.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <system_error>

namespace srcodec {

namespace fs = std::filesystem;

Status check_output_path(const std::string& path) {
  const fs::path target(path);
  if (target.filename().empty()) return invalid_argument(path + ": output path names no file");
  std::error_code ec;
  if (fs::is_directory(target, ec)) return invalid_argument(path + ": output path is a directory");
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  if (!fs::is_directory(dir, ec)) return not_found(path + ": output folder '" + dir.string() + "' does not exist");
  return ok_status();
}

Status write_file_atomically(const std::string& path, const std::string& bytes) {
  SRCODEC_RETURN_IF_ERROR(check_output_path(path));
  const fs::path target(path);
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");

  const std::string tmp = (dir / ("." + target.filename().string() + ".tmp" + std::to_string(::getpid()))).string();
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  if (!f) return io_error(path + ": cannot create a file in '" + dir.string() + "': " + std::strerror(errno));
  const bool written = std::fwrite(bytes.data(), 1, bytes.size(), f) == bytes.size();
  const bool flushed = std::fflush(f) == 0;
  const bool closed = std::fclose(f) == 0;
  if (!written || !flushed || !closed) {
    const std::string why = std::strerror(errno);
    std::remove(tmp.c_str());
    return io_error(path + ": write failed: " + why);
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    const std::string why = std::strerror(errno);
    std::remove(tmp.c_str());
    return io_error(path + ": cannot move the finished file into place: " + why);
  }
  return ok_status();
}

StatusOr<std::string> read_file_bytes(const std::string& path, uint64_t max_bytes) {
  std::error_code ec;
  if (!fs::exists(path, ec)) return not_found(path + ": no such file");
  if (!fs::is_regular_file(path, ec)) return io_error(path + ": not a regular file");
  const auto size = fs::file_size(path, ec);
  if (ec) return io_error(path + ": cannot read: " + ec.message());
  if (size > max_bytes) return invalid_argument(path + ": file is larger than " + std::to_string(max_bytes) + " bytes");
  std::ifstream in(path, std::ios::binary);
  if (!in) return io_error(path + ": cannot open for reading");
  std::string bytes(size, '\0');
  in.read(bytes.data(), static_cast<std::streamsize>(size));
  if (static_cast<size_t>(in.gcount()) != size) return io_error(path + ": short read");
  return bytes;
}

}  // namespace srcodec
