// batch_command.hpp - `facet batch JOBS`: many renders in one process, from JSON lines or a list of models.
#pragma once

#include <cstddef>
#include <cstdint>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "facet/render_job.hpp"

namespace facet::cli {

struct BatchArgs {
  std::string jobs;    // JSON lines (one object of render flags per line) or one model path per line
  std::string output;  // the output template of jobs that name none (a list of models needs one)
  std::string report;  // JSON lines, one per job: line, model, status, seconds, error
  std::string shard;   // "I/N" (this process renders the jobs with index % N == I) or "auto"
  int shards = 0;      // --shard auto's shard count: Kubernetes needs it; under Slurm the task id is then the shard
  bool force = false;  // render jobs whose outputs all exist too
  bool quiet = false;  // no progress
  int threads = 0;     // 0: one job per core at a time; N: jobs one after another on an N-thread renderer
};

// Adds the `batch` subcommand, filling `args` when it is parsed.
CLI::App* add_batch_command(CLI::App& app, BatchArgs& args);

// One job of a jobs file. A batch holds no list of its jobs: it reads the file line by line, once to check every
// job and again to render its share, so memory stays flat however many jobs the file holds (a parsed RenderJob
// takes about 2 KB). The file must not change while the batch runs.
struct BatchJob {
  std::size_t line = 0;   // 1-based line number in the jobs file
  std::size_t index = 0;  // the job's index among the file's jobs: {n} in output names
  bool json = false;      // a JSON object of flags, or a model path
  std::string text;       // the line
};

// The jobs file's job lines in order (blank lines and # comments skipped), read as they are asked for.
class JobLines {
 public:
  // Throws InputError for a missing or unreadable file.
  explicit JobLines(const BatchArgs& args);
  // The next job, or false at the end. Throws UsageError for a list of models without --output.
  bool next(BatchJob& job);

 private:
  const BatchArgs& args_;
  std::ifstream in_;
  std::size_t line_ = 0, index_ = 0;
  std::optional<bool> json_;  // decided by the first job line: a JSON object, or a model path
};

// The RenderJob of one job line. Throws InputError(jobs file, "line N: ...") for a line that is not JSON or not an
// object, an unknown key, a value of the wrong type or a missing model.
RenderJob parse_batch_job(const BatchJob& job, const BatchArgs& args);

// Checks every job of the file before anything is rendered, and returns how many there are. Each JSON line is an
// object whose keys are `facet render`'s long flag names ("model", "output", "resolution",
// "camera-azimuth-angle", "output-depth", ...): a string or number is the flag's value, a list its comma-separated
// values, true a bare flag, false none. Output names expand {model}, {stem} and {n} (the job's index in the file).
// Throws as parse_batch_job does, and UsageError for a list without --output or two jobs that would write one file.
std::size_t check_batch_jobs(const BatchArgs& args);

// The jobs one process renders: those whose index modulo `count` is `index`.
struct Shard {
  std::size_t index = 0, count = 1;
  bool has(std::size_t job) const { return job % count == index; }
  std::size_t size_of(std::size_t jobs) const { return jobs > index ? (jobs - index + count - 1) / count : 0; }
};

// This process's shard. Throws UsageError for a malformed --shard, or --shard auto without Slurm's array variables
// or Kubernetes' JOB_COMPLETION_INDEX and --shards.
Shard shard_of(const BatchArgs& args);

// Renders this shard's jobs, skipping those whose outputs exist (unless --force): with threads 0, one job per core
// at a time, each core with a renderer of its own; else one after another. A failed job is reported and the
// batch goes on. SIGINT or SIGTERM stops it once the jobs in flight are written, returning 128 + the signal.
// Returns 1 if any job failed, else 0.
int run_batch(const BatchArgs& args);

}  // namespace facet::cli
