// main.cpp - entry point of the facet command-line tool: subcommand dispatch and the one-line error contract.
#include <malloc.h>
#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <new>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include <CLI/CLI.hpp>

#include "batch_command.hpp"
#include "bench_command.hpp"
#include "cli_options.hpp"
#include "demo_command.hpp"
#include "facet/error.hpp"
#include "facet/version.hpp"
#include "info_command.hpp"
#include "render_command.hpp"
#include "thumbnail_command.hpp"
#include "view_command.hpp"

namespace {

// Exit statuses: 1 for bad input (a model that cannot be used, an output that cannot be written), 2 for bad usage.
constexpr int kInputError = 1;
constexpr int kUsageError = 2;

// Prints "facet: error: <message>" as exactly one line, whatever the message holds.
int fail(std::string message, int status) {
  for (char& c : message)
    if (c == '\n' || c == '\r') c = ' ';
  while (!message.empty() && message.back() == ' ') message.pop_back();
  std::fprintf(stderr, "facet: error: %s\n", message.c_str());
  return status;
}

// Puts the heap's next `reserve` bytes on transparent huge pages (for `facet render`). Loading and preparing a model
// fills fresh heap memory (the file, arrays of positions, corners, indices), and on a virtual machine each fresh
// 4 KiB page is a fault that can cost 10 us: a 200k-triangle OBJ touched 20,000 of them, most of its loading time.
// With 2 MiB pages that memory takes a fault per 2 MiB. glibc does this itself only when asked through
// GLIBC_TUNABLES; here the heap is grown once by a block larger than anything it holds and the new range is advised.
// Only address space is reserved: pages are touched, and counted, as they are used.
void heap_on_huge_pages(std::size_t reserve) {
  constexpr std::uintptr_t kHugePage = std::uintptr_t{2} << 20;
  mallopt(M_TOP_PAD, static_cast<int>(reserve));
  const auto before = reinterpret_cast<std::uintptr_t>(sbrk(0));
  // The heap grows by this block and the pad, and keeps them (trim threshold above). Through a volatile pointer,
  // or the compiler drops the unused allocation.
  void* volatile block = std::malloc(kHugePage);
  std::free(block);
  const auto after = reinterpret_cast<std::uintptr_t>(sbrk(0));
  const std::uintptr_t start = (before + kHugePage - 1) & ~(kHugePage - 1);
  // Only a hint: without transparent huge pages the heap keeps ordinary pages.
  if (after > start) ::madvise(reinterpret_cast<void*>(start), after - start, MADV_HUGEPAGE);
  mallopt(M_TOP_PAD, 0);
}

// The heap a render of these models may use: a model's preparation holds about eight times its file's size at its
// peak (an 870k-triangle ASCII PLY: a 32 MB file, 130 MiB), and 64 MiB covers the small ones with their images. At
// most 448 MiB, below the trim threshold, or free() would hand the reserve straight back.
std::size_t render_heap_bytes(const std::vector<std::string>& models) {
  std::uintmax_t largest = 0;
  for (const std::string& model : models) {
    std::error_code error;
    const std::uintmax_t bytes = std::filesystem::file_size(model, error);
    if (!error) largest = std::max(largest, bytes);
  }
  constexpr std::uintmax_t kLeast = std::uintmax_t{64} << 20, kMost = std::uintmax_t{448} << 20;
  return static_cast<std::size_t>(std::clamp(8 * largest, kLeast, kMost));
}

}  // namespace

int main(int argc, char** argv) {
  // Each render allocates textures, mipmaps, framebuffers and model arrays of a few hundred kilobytes to some
  // megabytes. glibc serves blocks over 128 KiB with fresh pages from mmap and unmaps them on free, so the next job
  // of a batch faults and zeroes them all again: 100 thumbnails of a textured OBJ took 3.2 s that way, 1.35 s with
  // freed memory kept for reuse (up to 512 MiB free at the top of the heap; only blocks over 256 MiB are mapped).
  mallopt(M_MMAP_THRESHOLD, 256 << 20);
  mallopt(M_TRIM_THRESHOLD, 512 << 20);
  // The library's messages name a setting by the flag that sets it.
  facet::spell_settings([](std::string_view name) {
    std::string flag = "--" + std::string(name);
    std::replace(flag.begin(), flag.end(), '_', '-');
    return flag;
  });
  CLI::App app{"facet: a CPU 3D rendering pipeline", "facet"};
  app.set_version_flag("--version", std::string("facet ") + facet::kVersion);
  facet::cli::RenderArgs render_args;
  facet::cli::DemoArgs demo_args;
  facet::cli::InfoArgs info_args;
  facet::cli::BenchArgs bench_args;
  facet::cli::BatchArgs batch_args;
  facet::cli::ViewArgs view_args;
  facet::cli::ThumbnailArgs thumbnail_args;
  CLI::App* render = facet::cli::add_render_command(app, render_args);
  CLI::App* demo = facet::cli::add_demo_command(app, demo_args);
  CLI::App* info = facet::cli::add_info_command(app, info_args);
  CLI::App* bench = facet::cli::add_bench_command(app, bench_args);
  CLI::App* batch = facet::cli::add_batch_command(app, batch_args);
  CLI::App* view = facet::cli::add_view_command(app, view_args);
  CLI::App* thumbnail = facet::cli::add_thumbnail_command(app, thumbnail_args);

  // CLI11 would list every argument as unexpected; name the command instead.
  if (const std::string_view command = argc >= 2 ? argv[1] : "-";
      (command.empty() || command[0] != '-') && command != "render" && command != "demo" && command != "info" &&
      command != "bench" && command != "batch" && command != "view" && command != "thumbnail")
    return fail(std::string("unknown command '") + argv[1] +
                    "': use render, batch, view, thumbnail, demo, info or bench",
                kUsageError);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    return fail(e.what(), kUsageError);
  }

  try {
    // A single render meets all its memory fresh; a batch reuses one heap from job to job, and keeps the small
    // pages that let its peak follow what it holds.
    if (render->parsed()) {
      heap_on_huge_pages(render_heap_bytes(render_args.models));
      return facet::cli::run_render(render_args);
    }
    if (demo->parsed()) return facet::cli::run_demo(demo_args);
    if (info->parsed()) return facet::cli::run_info(info_args);
    if (bench->parsed()) return facet::cli::run_bench(bench_args);
    if (batch->parsed()) return facet::cli::run_batch(batch_args);
    if (view->parsed()) return facet::cli::run_view(view_args);
    if (thumbnail->parsed()) return facet::cli::run_thumbnail(thumbnail_args);
    return fail("no command given: use render, batch, view, thumbnail, demo, info or bench (see facet --help)",
                kUsageError);
  } catch (const facet::InputError& e) {
    return fail(e.what(), kInputError);
  } catch (const facet::cli::UsageError& e) {
    return fail(e.what(), kUsageError);
  } catch (const std::invalid_argument& e) {
    // The camera and projection functions refuse degenerate parameters (eye == target, near >= far, ...).
    return fail(e.what(), kUsageError);
  } catch (const std::bad_alloc&) {
    return fail("out of memory", kInputError);
  } catch (const std::exception& e) {
    // Writing the outputs: write_png / write_npy say "<path>: <reason>".
    return fail(e.what(), kInputError);
  }
}
