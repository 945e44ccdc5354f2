// file_util.cpp - whole-file reading of regular files only, for the model readers and the image decoders.
#include "core/file_util.hpp"

#include <cctype>
#include <cerrno>
#include <climits>
#include <cstdio>
#include <memory>
#include <system_error>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "facet/error.hpp"

namespace facet {

std::string errno_text(int err) { return std::generic_category().message(err); }

std::string lower_extension(const std::filesystem::path& path) {
  std::string extension = path.extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return extension;
}

namespace {

template <class Bytes>
Bytes read_regular_file_as(const std::filesystem::path& path, std::uintmax_t max_bytes, const std::string& source) {
  // Non-blocking, so that opening a FIFO returns at once instead of waiting for a writer; it is refused below.
  int fd;
  do fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  while (fd < 0 && errno == EINTR);
  if (fd < 0) throw InputError(source, errno == ENOENT ? "no such file" : "cannot open: " + errno_text(errno));
  const std::unique_ptr<int, void (*)(int*)> closer(&fd, [](int* f) { ::close(*f); });
  struct stat st;
  if (::fstat(fd, &st) != 0) throw InputError(source, "cannot read: " + errno_text(errno));
  // A directory, device (/dev/zero), FIFO or socket is never read.
  if (!S_ISREG(st.st_mode)) throw InputError(source, "not a regular file");
  const auto size = static_cast<std::uintmax_t>(st.st_size);
  if (size == 0) throw InputError(source, "file is empty");
  if (size > max_bytes)
    throw InputError(source,
                     "file is too large (" + std::to_string(size) + " bytes, limit " + std::to_string(max_bytes) + ")");
  Bytes bytes(static_cast<std::size_t>(size), 0);
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::read(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw InputError(source, "cannot read: " + errno_text(errno));
    if (n == 0) break;  // the file shrank meanwhile
    done += static_cast<std::size_t>(n);
  }
  bytes.resize(done);
  if (bytes.empty()) throw InputError(source, "file is empty");
  return bytes;
}

}  // namespace

FileBytes read_regular_file(const std::filesystem::path& path, std::uintmax_t max_bytes, const std::string& source) {
  return read_regular_file_as<FileBytes>(path, max_bytes, source);
}

std::vector<unsigned char> read_image_file(const std::filesystem::path& path) {
  // stb_image takes the length as an int.
  return read_regular_file_as<std::vector<unsigned char>>(path, INT_MAX, path.string());
}

}  // namespace facet
