// batch_command.cpp - `facet batch`: jobs read and checked up front, then rendered by one renderer, with a report.
#include "batch_command.hpp"

#include <unistd.h>

#include <algorithm>
#include <bit>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <thread>
#include <memory>
#include <unordered_map>
#include <unordered_set>

#include <nlohmann/json.hpp>

#include "facet/error.hpp"
#include "facet/warnings.hpp"
#include "render_command.hpp"

namespace facet::cli {
namespace {

using Json = nlohmann::json;

// A JSON value as the text of a flag's value: strings as they are, numbers as JSON writes them, lists joined by
// commas; nullopt for anything else (objects, null, nested lists).
std::optional<std::string> flag_text(const Json& value) {
  if (value.is_string()) return value.get<std::string>();
  if (value.is_number()) return value.dump();
  if (!value.is_array()) return std::nullopt;
  std::string joined;
  for (const Json& item : value) {
    if (!item.is_number() && !item.is_string()) return std::nullopt;
    if (!joined.empty()) joined += ',';
    joined += item.is_string() ? item.get<std::string>() : item.dump();
  }
  return joined;
}

// `facet render`'s arguments for one JSON object; throws std::invalid_argument naming the key at fault.
std::vector<std::string> render_arguments(const Json& object, const std::string& default_output) {
  if (!object.is_object()) throw std::invalid_argument("expected a JSON object");
  const auto model = object.find("model");
  if (model == object.end() || !model->is_string()) throw std::invalid_argument("\"model\" (a string) is missing");
  std::vector<std::string> argv = {"facet", "render", model->get<std::string>()};
  for (const auto& [key, value] : object.items()) {
    if (key == "model") continue;
    if (value.is_boolean()) {
      if (value.get<bool>()) argv.push_back("--" + key);
      continue;
    }
    const std::optional<std::string> text = flag_text(value);
    if (!text) throw std::invalid_argument("\"" + key + "\": expected a string, number, boolean or list");
    argv.push_back("--" + key);
    argv.push_back(*text);
  }
  if (!object.contains("output") && !default_output.empty()) {
    argv.push_back("--output");
    argv.push_back(default_output);
  }
  return argv;
}

// The job the arguments describe, parsed by `facet render`'s own flags; CLI11's and the flags' errors become
// std::invalid_argument.
RenderJob job_of(const std::vector<std::string>& argv, std::size_t n) {
  // A parser of its own for each job: one kept and cleared between jobs grows with every parse (CLI11 keeps some
  // of each parse's state), and a long batch's memory must stay flat.
  struct Parser {
    CLI::App app;
    RenderArgs args;
    Parser() { add_render_command(app, args); }
  } parser;
  std::vector<const char*> pointers;
  for (const std::string& a : argv) pointers.push_back(a.c_str());
  try {
    parser.app.parse(static_cast<int>(pointers.size()), pointers.data());
    return render_jobs(parser.args, n).front();
  } catch (const CLI::Error& e) {
    throw std::invalid_argument(e.what());
  } catch (const UsageError& e) {
    throw std::invalid_argument(e.what());
  }
}

bool outputs_exist(const OutputSpec& outputs) {
  std::error_code ignored;
  for (const std::filesystem::path& p : output_paths(outputs))
    if (!std::filesystem::exists(p, ignored)) return false;
  return true;
}

std::size_t parse_count(const std::string& text, const std::string& what) {
  std::size_t used = 0;
  unsigned long value = 0;
  try {
    value = std::stoul(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size()) throw UsageError(what + ": expected a whole number, got \"" + text + "\"");
  return value;
}

// Progress on stderr: a line rewritten in place on a terminal, a plain line every 5 seconds otherwise.
class Progress {
 public:
  Progress(std::size_t total, bool quiet) : total_(total), quiet_(quiet), terminal_(::isatty(2) != 0) {}
  void update(std::size_t done, bool last) {
    if (quiet_) return;
    const double elapsed = seconds_since(start_);
    if (!terminal_ && !last && seconds_since(printed_) < 5.0) return;
    printed_ = Clock::now();
    const double rate = elapsed > 0.0 ? static_cast<double>(done) / elapsed : 0.0;
    const double eta = rate > 0.0 ? static_cast<double>(total_ - done) / rate : 0.0;
    std::fprintf(stderr, "%sfacet batch: %zu/%zu jobs, %.1f/s, %.0f s left%s", terminal_ ? "\r" : "", done, total_,
                 rate, eta, terminal_ && !last ? "" : "\n");
    std::fflush(stderr);
  }

 private:
  using Clock = std::chrono::steady_clock;
  static double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }
  std::size_t total_;
  bool quiet_, terminal_;
  Clock::time_point start_ = Clock::now(), printed_ = Clock::now();
};

// The signal that asked the batch to stop (SIGINT, SIGTERM), 0 while none has. Jobs in flight finish, so every
// output is complete and renamed into place and no temporary file is left; the rest wait for a rerun.
volatile std::sig_atomic_t stop_signal = 0;

void request_stop(int signal) { stop_signal = signal; }

}  // namespace

CLI::App* add_batch_command(CLI::App& app, BatchArgs& args) {
  CLI::App* batch = app.add_subcommand("batch", "Render every job of a file in one process");
  batch
      ->add_option("jobs", args.jobs,
                   "JSON lines of render flags ({\"model\": ..., \"output\": ..., \"resolution\": [256, 256]}), "
                   "or one model path per line")
      ->required()
      ->type_name("JOBS");
  batch->add_option("-o,--output", args.output, "Output template of jobs that name none, e.g. 'thumbs/{stem}.png'")
      ->type_name("TEMPLATE");
  batch->add_option("--report", args.report, "Write one JSON line per job: line, model, status, seconds, error")
      ->type_name("FILE.jsonl");
  batch->add_option("--shard", args.shard, "Render the jobs whose index % N is I, or 'auto' (Slurm, Kubernetes)")
      ->type_name("I/N");
  batch->add_option("--shards", args.shards,
                    "The shard count for --shard auto: needed with Kubernetes indexed jobs; with Slurm, makes the "
                    "array task id the shard (so one task can be submitted again alone)")
      ->type_name("N");
  batch->add_flag("--force", args.force, "Render jobs whose outputs exist too");
  batch->add_flag("--quiet", args.quiet, "No progress on stderr");
  batch
      ->add_option("--threads", args.threads,
                   "0: one job per core at a time (default); N: one job at a time on N threads")
      ->type_name("N");
  return batch;
}

namespace {

// The job of one line's text.
RenderJob parse_job_text(const BatchJob& job, const std::string& text, const BatchArgs& args) {
  try {
    std::vector<std::string> argv;
    if (job.json) {
      const Json object = Json::parse(text, nullptr, false);
      if (object.is_discarded()) throw std::invalid_argument("not valid JSON");
      argv = render_arguments(object, args.output);
    } else {
      std::string model = text.substr(text.find_first_not_of(" \t"));
      while (!model.empty() && (model.back() == '\r' || model.back() == ' ' || model.back() == '\t')) model.pop_back();
      argv = {"facet", "render", model, "--output", args.output};
    }
    return job_of(argv, job.index);
  } catch (const std::invalid_argument& e) {
    throw InputError(args.jobs, "line " + std::to_string(job.line) + ": " + e.what());
  }
}

}  // namespace

RenderJob parse_batch_job(const BatchJob& job, const BatchArgs& args) { return parse_job_text(job, job.text, args); }

JobLines::JobLines(const BatchArgs& args) : args_(args) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(args.jobs, ec)) throw InputError(args.jobs, "no such file");
  in_.open(args.jobs, std::ios::binary);
  if (!in_) throw InputError(args.jobs, "cannot open file");
}

bool JobLines::next(BatchJob& job) {
  while (std::getline(in_, job.text)) {
    ++line_;
    if (!job.text.empty() && job.text.back() == '\r') job.text.pop_back();
    const std::size_t first = job.text.find_first_not_of(" \t\r");
    if (first == std::string::npos || job.text[first] == '#') continue;
    if (!json_) {
      json_ = job.text[first] == '{';
      if (!*json_ && args_.output.empty()) throw UsageError("--output: a list of models needs an output template");
    }
    job.line = line_;
    job.index = index_++;
    job.json = *json_;
    return true;
  }
  return false;
}

namespace {

// The output names a batch's jobs write, in a Bloom filter of a bit per byte of the jobs file (a job line takes
// tens of bytes), between 8 KiB and 8 MiB: whether a name may have been written before is known in memory that no
// longer grows past a few million jobs. A name it reports is confirmed by a second pass over those names alone. Four
// bits a name: at a million outputs about ten names are confirmed needlessly; at ten million, a few hundred thousand.
class OutputNames {
 public:
  explicit OutputNames(std::uintmax_t file_bytes)
      : words_(std::bit_ceil(std::clamp<std::uintmax_t>(file_bytes, kLeastBits, kMostBits)) / 64),
        bits_(static_cast<std::uint64_t*>(std::calloc(words_, sizeof(std::uint64_t))), &std::free) {
    if (!bits_) throw std::bad_alloc();
  }
  // Adds the name's hash; false when it certainly was not added before.
  bool add(std::size_t hash) {
    const std::uint64_t step = ((static_cast<std::uint64_t>(hash) >> 32 | static_cast<std::uint64_t>(hash) << 32) *
                                0x9e3779b97f4a7c15u) | 1u;
    bool seen = true;
    for (std::uint64_t k = 0, bit = hash; k < 4; ++k, bit += step) {
      std::uint64_t& word = bits_[(bit / 64) % words_];
      const std::uint64_t mask = std::uint64_t{1} << (bit % 64);
      seen = seen && (word & mask) != 0;
      word |= mask;
    }
    return seen;
  }

 private:
  static constexpr std::uintmax_t kLeastBits = std::uintmax_t{1} << 16, kMostBits = std::uintmax_t{1} << 26;
  std::size_t words_;
  std::unique_ptr<std::uint64_t[], void (*)(void*)> bits_;
};

std::string normalised(const std::filesystem::path& path) { return path.lexically_normal().string(); }

}  // namespace

std::size_t check_batch_jobs(const BatchArgs& args) {
  std::error_code ignored;
  const std::uintmax_t bytes = std::filesystem::file_size(args.jobs, ignored);
  OutputNames names(ignored ? 0 : bytes);
  std::unordered_set<std::size_t> maybe_twice;  // hashes of names the filter may have seen before
  JobLines lines(args);
  BatchJob job;
  std::size_t count = 0;
  while (lines.next(job)) {
    ++count;
    std::unordered_set<std::string> own;  // one job naming a file twice is render()'s to refuse
    for (const std::filesystem::path& path : output_paths(parse_batch_job(job, args).outputs)) {
      const std::string name = normalised(path);
      const std::size_t hash = std::hash<std::string>{}(name);
      if (own.insert(name).second && names.add(hash)) maybe_twice.insert(hash);
    }
  }
  if (maybe_twice.empty()) return count;
  // The names the filter flagged, read again with the lines that write them.
  std::unordered_map<std::string, std::size_t> writer;
  JobLines again(args);
  while (again.next(job))
    for (const std::filesystem::path& path : output_paths(parse_batch_job(job, args).outputs)) {
      const std::string name = normalised(path);
      if (!maybe_twice.contains(std::hash<std::string>{}(name))) continue;
      const auto [it, first] = writer.emplace(name, job.line);
      if (!first && it->second != job.line)
        throw UsageError("lines " + std::to_string(it->second) + " and " + std::to_string(job.line) +
                         " would both write " + path.string());
    }
  return count;
}

Shard shard_of(const BatchArgs& args) {
  std::size_t index = 0, shards = 1;
  if (args.shard == "auto") {
    const char* slurm_id = std::getenv("SLURM_ARRAY_TASK_ID");
    const char* slurm_count = std::getenv("SLURM_ARRAY_TASK_COUNT");
    const char* k8s_index = std::getenv("JOB_COMPLETION_INDEX");
    if (slurm_id && slurm_count) {
      const std::size_t id = parse_count(slurm_id, "SLURM_ARRAY_TASK_ID");
      if (args.shards >= 1) {
        // The task id is the shard: one task submitted again alone (sbatch --array=2) renders its own share.
        index = id;
        shards = static_cast<std::size_t>(args.shards);
      } else {
        const char* slurm_min = std::getenv("SLURM_ARRAY_TASK_MIN");
        const std::size_t min = slurm_min ? parse_count(slurm_min, "SLURM_ARRAY_TASK_MIN") : 0;
        if (id < min) throw UsageError("--shard auto: SLURM_ARRAY_TASK_ID is below SLURM_ARRAY_TASK_MIN");
        index = id - min;
        shards = parse_count(slurm_count, "SLURM_ARRAY_TASK_COUNT");
      }
    } else if (k8s_index) {
      if (args.shards < 1) throw UsageError("--shard auto: Kubernetes' JOB_COMPLETION_INDEX needs --shards N");
      index = parse_count(k8s_index, "JOB_COMPLETION_INDEX");
      shards = static_cast<std::size_t>(args.shards);
    } else {
      throw UsageError(
          "--shard auto: neither Slurm's SLURM_ARRAY_TASK_ID and SLURM_ARRAY_TASK_COUNT nor "
          "Kubernetes' JOB_COMPLETION_INDEX is set");
    }
  } else if (!args.shard.empty()) {
    const std::size_t slash = args.shard.find('/');
    if (slash == std::string::npos) throw UsageError("--shard: expected I/N or auto, got \"" + args.shard + "\"");
    index = parse_count(args.shard.substr(0, slash), "--shard");
    shards = parse_count(args.shard.substr(slash + 1), "--shard");
  }
  if (shards < 1 || index >= shards)
    throw UsageError("--shard: shard " + std::to_string(index) + " of " + std::to_string(shards) + " does not exist");
  return Shard{index, shards};
}

int run_batch(const BatchArgs& args) {
  const Shard shard = shard_of(args);
  const std::size_t total = shard.size_of(check_batch_jobs(args));
  std::ofstream report;
  if (!args.report.empty()) {
    report.open(args.report, std::ios::trunc);
    if (!report) throw std::runtime_error(args.report + ": cannot create file");
  }
  // A run killed outright (SIGKILL, power loss) may have left a temporary file beside an output; this run
  // renders that output again, so the leftover goes.
  // In groups, so that the outputs of a long batch are never all in memory at once.
  {
    JobLines lines(args);
    BatchJob job;
    std::vector<OutputSpec> outputs;
    for (bool more = true; more;) {
      more = lines.next(job);
      if (more && shard.has(job.index)) outputs.push_back(parse_batch_job(job, args).outputs);
      if (outputs.size() == 256 || (!more && !outputs.empty())) {
        remove_stale_temporaries(outputs);
        outputs.clear();
      }
    }
  }
  const bool terminal = ::isatty(2) != 0;
  Progress progress(total, args.quiet);
  std::mutex lock;  // guards the report, the progress and the counts
  int failed = 0;
  std::size_t done = 0;
  JobLines lines(args);
  std::mutex reading;  // guards `lines`
  // The next job of this shard, or false at the end of the file.
  const auto next_job = [&](BatchJob& job) {
    const std::lock_guard<std::mutex> hold(reading);
    while (lines.next(job))
      if (shard.has(job.index)) return true;
    return false;
  };

  // Small models leave a renderer's threads idle between draws (loading, encoding), so with --threads 0 each core
  // takes jobs of its own with a one-thread renderer; --threads N gives one renderer N threads.
  const auto work = [&](int threads) {
    Renderer renderer(threads);
    BatchJob line;
    while (stop_signal == 0 && next_job(line)) {
      const RenderJob job = parse_batch_job(line, args);
      Json entry = {{"line", line.line}, {"model", job.model.string()}};
      const auto start = std::chrono::steady_clock::now();
      std::string error;
      WarningCapture warnings;  // kept for the report, and printed below unless --quiet
      if (!args.force && outputs_exist(job.outputs)) {
        entry["status"] = "skipped";
      } else {
        try {
          // Batches write into folder trees (thumbs/{stem}.png): the folders are made as needed.
          for (const std::filesystem::path& path : output_paths(job.outputs))
            if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
          render(job, renderer);
          entry["status"] = "ok";
        } catch (const std::exception& e) {
          error = e.what();
          entry["status"] = "failed";
          entry["error"] = error;
        }
      }
      entry["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      if (!warnings.messages().empty()) entry["warnings"] = warnings.messages();
      const std::lock_guard<std::mutex> hold(lock);
      // On a terminal the progress line is open: a message starts a line of its own.
      const char* newline = !args.quiet && terminal ? "\n" : "";
      if (!args.quiet)
        for (const std::string& warning : warnings.messages())
          std::fprintf(stderr, "%sfacet: warning: %s\n", newline, warning.c_str());
      if (!error.empty()) {
        std::fprintf(stderr, "%sfacet: error: %s\n", newline, error.c_str());
        ++failed;
      }
      if (report.is_open()) report << entry.dump() << '\n' << std::flush;
      ++done;
      progress.update(done, done == total);
    }
  };
  stop_signal = 0;
  std::signal(SIGINT, request_stop);
  std::signal(SIGTERM, request_stop);
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  const std::size_t workers = args.threads == 0 ? std::min<std::size_t>(cores, total) : 1;
  if (workers <= 1) {
    work(args.threads);
  } else {
    std::vector<std::jthread> pool;
    for (std::size_t w = 0; w < workers; ++w) pool.emplace_back(work, 1);
  }
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
  if (report.is_open() && !report) throw std::runtime_error(args.report + ": cannot write file");
  if (stop_signal != 0) {
    std::fprintf(stderr, "facet: batch stopped by signal %d after %zu of %zu jobs; run it again to finish\n",
                 static_cast<int>(stop_signal), done, total);
    return 128 + stop_signal;  // as a shell reports a process the signal ended
  }
  return failed == 0 ? 0 : 1;
}

}  // namespace facet::cli
