// output_file.hpp - writing an output's bytes whole, without ever destroying what its name points at.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>

namespace facet {

// Where writing an output's bytes puts them.
struct OutputTarget {
  enum class Kind {
    file,    // a regular file, created or replaced whole through a temporary file renamed into place
    stream,  // written in place, in order: standard output ("-"), a device, a FIFO, or a /proc/self/fd link
  };
  Kind kind = Kind::file;
  // file: the regular file that ends up holding the bytes (a symlink's final target); stream: the name opened.
  std::filesystem::path path;
};

// Decides, without writing, where write_output(path, ...) puts its bytes. A name whose symlinks pass through /proc
// or /dev/fd (such as /dev/stdout) is a stream even when it ends at a regular file: that file is open in some
// process, which would not see a replacement. Throws std::runtime_error("<path>: <reason>") for a directory, a
// symlink loop or an empty name.
OutputTarget output_target(const std::filesystem::path& path);

// Writes bytes to path as output_target() says. A regular file is never left partly written: a failure leaves the
// old file (or none) and no temporary file. Throws std::runtime_error("<path>: <reason>") when the target cannot be
// created, opened or written (a full disk or /dev/full included).
OutputTarget write_output(const std::filesystem::path& path, std::span<const std::uint8_t> bytes);

// Removes the temporary files that write_output left for these outputs when its process was killed outright
// (SIGKILL, a crash, power loss) between creating and renaming one: hidden files named ".NAME.PID.N.tmp" next to an
// output NAME whose process PID is no longer running on this machine. Each folder is listed once. Returns how many
// were removed; errors are ignored, as the sweep only tidies.
std::size_t remove_stale_temporaries(std::span<const std::filesystem::path> outputs);

// Removes what write_output(path, ...) created when it made a regular file, after a later output failed; never a
// device, FIFO or stream. Errors are ignored: this runs while another error is being reported.
void discard_output(const std::filesystem::path& path);

}  // namespace facet
