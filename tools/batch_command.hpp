// batch_command.hpp - `facet batch JOBS`: many renders in one process, from JSON lines or a list of models.
#pragma once

#include <cstddef>
#include <cstdint>
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
  int shards = 0;      // the shard count for --shard auto under Kubernetes indexed jobs
  bool force = false;  // render jobs whose outputs all exist too
  bool quiet = false;  // no progress
  int threads = 0;     // 0: one job per core at a time; N: jobs one after another on an N-thread renderer
};

// Adds the `batch` subcommand, filling `args` when it is parsed.
CLI::App* add_batch_command(CLI::App& app, BatchArgs& args);

// One job of a jobs file: where its line lies in the file. A parsed RenderJob takes about 2 KB and the line itself
// a few hundred bytes, so a batch keeps only this and reads and parses a job's line again when it runs: memory stays
// flat however many jobs the file holds. The file must not change while the batch runs.
struct BatchJob {
  std::size_t line = 0;      // 1-based line number in the jobs file
  std::size_t index = 0;     // the job's index among the file's jobs: {n} in output names
  bool json = false;         // a JSON object of flags, or a model path
  std::uint64_t offset = 0;  // of the line's first byte in the file
  std::uint32_t length = 0;  // of the line, without its newline
};

// The RenderJob of one job of the jobs file, as read_batch_jobs checked it. Throws InputError(jobs file,
// "line N: ...") as read_batch_jobs does, or if the file can no longer be read.
RenderJob parse_batch_job(const BatchJob& job, const BatchArgs& args);

// Every job of the file, in order, checked before anything is rendered. Each JSON line is an object whose keys are
// `facet render`'s long flag names ("model", "output", "resolution", "camera-azimuth-angle", "output-depth", ...):
// a string or number is the flag's value, a list its comma-separated values, true a bare flag, false none. Output
// names expand {model}, {stem} and {n} (the job's index in the file). Throws InputError(jobs file, "line N: ...")
// for a line that is not JSON or not an object, an unknown key, a value of the wrong type or a missing model, and
// UsageError for a list without --output or two jobs that would write one file.
std::vector<BatchJob> read_batch_jobs(const BatchArgs& args);

// The share of `count` jobs this process renders: their indices. Throws UsageError for a malformed --shard, or
// --shard auto without Slurm's array variables or Kubernetes' JOB_COMPLETION_INDEX and --shards.
std::vector<std::size_t> shard_of(const BatchArgs& args, std::size_t count);

// Renders this shard's jobs, skipping those whose outputs exist (unless --force): with threads 0, one job per core
// at a time, each core with a renderer of its own; else one after another. A failed job is reported and the
// batch goes on. SIGINT or SIGTERM stops it once the jobs in flight are written, returning 128 + the signal.
// Returns 1 if any job failed, else 0.
int run_batch(const BatchArgs& args);

}  // namespace facet::cli
