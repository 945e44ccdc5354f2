// output_file.cpp - outputs written whole into regular files, or in place into devices, FIFOs and standard output.
#include "job/io/output_file.hpp"

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/file_util.hpp"

namespace facet {

namespace {

[[noreturn]] void write_failed(const std::filesystem::path& path, const std::string& reason) {
  throw std::runtime_error(path.string() + ": " + reason);
}

// Links into /proc/PID/fd (and /dev/fd, which is one) name files some process holds open: a shell's redirection
// of standard output, say. Replacing the file behind them would leave that process writing to the old one.
bool names_open_descriptor(const std::filesystem::path& path) {
  const std::string p = path.lexically_normal().string();
  return p.starts_with("/proc/") || p.starts_with("/dev/fd/");
}

// A name in the same folder as path (so the final rename cannot cross file systems), unique per process and call,
// hidden so that a crash mid-write leaves nothing that looks like the real output.
std::filesystem::path temporary_name(const std::filesystem::path& path) {
  static std::atomic<unsigned> counter{0};
  // Appended piecewise: GCC 12 reports a false -Wrestrict for "." + std::string.
  std::string name(1, '.');
  name += path.filename().string();
  name += '.';
  name += std::to_string(::getpid());
  name += '.';
  name += std::to_string(counter.fetch_add(1));
  name += ".tmp";
  return path.parent_path() / name;
}

// Writes bytes to a temporary file and renames it over path: readers see either the old file or the whole new one.
void write_file_atomically(const std::filesystem::path& path, std::span<const std::uint8_t> bytes) {
  if (!path.has_filename()) write_failed(path, "not a file name");
  const std::filesystem::path temp = temporary_name(path);
  // "x": never reuse an existing file, should a stale temporary with this name exist.
  std::FILE* file = std::fopen(temp.c_str(), "wbx");
  if (!file) write_failed(path, "cannot create file: " + errno_text(errno));
  bool ok = std::fwrite(bytes.data(), 1, bytes.size(), file) == bytes.size();
  int err = ok ? 0 : errno;
  if (std::fclose(file) != 0 && ok) {  // the buffered tail is written here, so this can fail too (disk full)
    ok = false;
    err = errno;
  }
  std::error_code ec;
  if (!ok) {
    std::filesystem::remove(temp, ec);
    write_failed(path, "cannot write file: " + errno_text(err));
  }
  std::filesystem::rename(temp, path, ec);
  if (ec) {
    std::error_code ignored;
    std::filesystem::remove(temp, ignored);
    write_failed(path, "cannot replace file: " + ec.message());
  }
}

// Every byte to an open descriptor, through short writes and interruptions.
void write_all(int fd, const std::filesystem::path& path, std::span<const std::uint8_t> bytes) {
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) write_failed(path, "cannot write: " + errno_text(n < 0 ? errno : EIO));
    done += static_cast<std::size_t>(n);
  }
}

// Opens the existing device, FIFO or descriptor link (never creating anything) and writes into it, truncating it
// first where that means anything (as `cp` does), so a /dev/stdout redirected to a file ends up holding the bytes.
void write_stream(const std::filesystem::path& path, std::span<const std::uint8_t> bytes) {
  if (path == "-") return write_all(STDOUT_FILENO, "standard output", bytes);
  int fd;
  do fd = ::open(path.c_str(), O_WRONLY | O_TRUNC | O_NOCTTY | O_CLOEXEC);
  while (fd < 0 && errno == EINTR);
  if (fd < 0) write_failed(path, "cannot open: " + errno_text(errno));
  try {
    write_all(fd, path, bytes);
  } catch (...) {
    ::close(fd);
    throw;
  }
  if (::close(fd) != 0 && errno != EINTR) write_failed(path, "cannot write: " + errno_text(errno));
}

}  // namespace

OutputTarget output_target(const std::filesystem::path& path) {
  using Kind = OutputTarget::Kind;
  if (path == "-") return {Kind::stream, path};
  if (path.empty() || !path.has_filename()) write_failed(path, "not a file name");
  std::filesystem::path current = path;
  for (int hop = 0; hop < 40; ++hop) {  // Linux's own limit on links followed in one lookup
    if (names_open_descriptor(current)) return {Kind::stream, path};
    struct stat st;
    // Absent (or not reachable, which creating it will report): a new regular file.
    if (::lstat(current.c_str(), &st) != 0) return {Kind::file, current};
    if (S_ISDIR(st.st_mode)) write_failed(path, "is a directory");
    if (S_ISREG(st.st_mode)) return {Kind::file, current};
    if (!S_ISLNK(st.st_mode)) return {Kind::stream, path};  // a device, FIFO or socket: written, never replaced
    std::error_code ec;
    std::filesystem::path target = std::filesystem::read_symlink(current, ec);
    if (ec) write_failed(path, "cannot read link: " + ec.message());
    current = target.is_absolute() ? target : current.parent_path() / target;
  }
  write_failed(path, "too many levels of symbolic links");
}

OutputTarget write_output(const std::filesystem::path& path, std::span<const std::uint8_t> bytes) {
  const OutputTarget target = output_target(path);
  if (target.kind == OutputTarget::Kind::stream) write_stream(target.path, bytes);
  else write_file_atomically(target.path, bytes);
  return target;
}

namespace {

// What temporary_name() made this name from: the output's file name and the writer's PID, if name is
// ".<output>.<pid>.<n>.tmp"; nothing otherwise. Output names may hold dots, so the fields are taken from the end.
std::optional<std::pair<std::string, pid_t>> parse_temporary(std::string_view name) {
  if (!name.starts_with('.') || !name.ends_with(".tmp")) return std::nullopt;
  const std::size_t counter_dot = name.rfind('.', name.size() - 5);
  if (counter_dot == std::string_view::npos || counter_dot < 2) return std::nullopt;
  const std::size_t pid_dot = name.rfind('.', counter_dot - 1);
  if (pid_dot == std::string_view::npos || pid_dot < 2) return std::nullopt;
  const auto all_digits = [](std::string_view digits) {
    return !digits.empty() && digits.size() <= 9 && digits.find_first_not_of("0123456789") == std::string_view::npos;
  };
  const std::string_view pid = name.substr(pid_dot + 1, counter_dot - pid_dot - 1);
  if (!all_digits(pid) || !all_digits(name.substr(counter_dot + 1, name.size() - 4 - counter_dot - 1)))
    return std::nullopt;
  return std::pair{std::string(name.substr(1, pid_dot - 1)), static_cast<pid_t>(std::stol(std::string(pid)))};
}

bool process_running(pid_t pid) { return ::kill(pid, 0) == 0 || errno == EPERM; }

}  // namespace

std::size_t remove_stale_temporaries(std::span<const std::filesystem::path> outputs) {
  std::map<std::filesystem::path, std::set<std::string>> names_by_folder;
  for (const std::filesystem::path& path : outputs) {
    try {
      const OutputTarget target = output_target(path);
      if (target.kind != OutputTarget::Kind::file) continue;
      const std::filesystem::path folder = target.path.parent_path();
      names_by_folder[folder.empty() ? "." : folder].insert(target.path.filename().string());
    } catch (const std::exception&) {
      // Not a place write_output could have written: nothing to tidy.
    }
  }
  std::size_t removed = 0;
  for (const auto& [folder, names] : names_by_folder) {
    std::error_code ec;
    for (auto it = std::filesystem::directory_iterator(folder, ec); !ec && it != std::filesystem::directory_iterator();
         it.increment(ec)) {
      const std::string name = it->path().filename().string();
      std::error_code kind_error;
      if (!name.starts_with('.') || !it->is_regular_file(kind_error)) continue;
      const auto temporary = parse_temporary(name);
      if (!temporary || !names.contains(temporary->first)) continue;
      if (temporary->second <= 0 || process_running(temporary->second)) continue;
      std::error_code ignored;
      if (std::filesystem::remove(it->path(), ignored)) ++removed;
    }
  }
  return removed;
}

void discard_output(const std::filesystem::path& path) {
  try {
    const OutputTarget target = output_target(path);
    std::error_code ignored;
    if (target.kind == OutputTarget::Kind::file) std::filesystem::remove(target.path, ignored);
  } catch (const std::exception&) {
    // Nothing was created there that could be removed.
  }
}

}  // namespace facet
