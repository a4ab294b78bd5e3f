// Running a batch on the scheduler a cluster already has: a Slurm job array of N shards, each task
// running `frugal batch MANIFEST --shard array/N --resume` (its index from SLURM_ARRAY_TASK_ID), and
// a job that depends on the array and merges. Kubernetes Indexed Jobs hand each pod its index as
// JOB_COMPLETION_INDEX, read the same way (docs/batch.md has an example Job).
#pragma once

#include <string>
#include <vector>

#include <frugal/Result.h>

#include "batch/Shards.h"

namespace frugal::batch {

// The shard index of this array task: SLURM_ARRAY_TASK_ID (less SLURM_ARRAY_TASK_MIN when set) or
// JOB_COMPLETION_INDEX, for `--shard array/N`. Errors: neither is set; not a number; not below N.
Result<int> arrayTaskIndex(int count);

struct SlurmScripts {
    std::string shards;  // the array job's script (#SBATCH --array=0-(N-1))
    std::string merge;   // the merge job's script
};

// The scripts for `frugal` (an absolute path) running `manifest` in `count` shards into `out`
// (absolute; the cluster's nodes must see all three at these paths). Their logs go to out/slurm/.
SlurmScripts slurmScripts(const std::string& frugal, const std::string& manifest, const std::string& out, int count);

// Words of a shell-like option string ("--partition=gpu -t 10"): split at spaces, with '...' and
// "..." quoting. Error: an unclosed quote.
Result<std::vector<std::string>> splitWords(const std::string& text);

// `word` as a shell reads it back: as it is when it holds nothing special, else single-quoted.
std::string shellWord(const std::string& word);

// Runs `argv` (no shell; argv[0] looked up on PATH) and gives what it wrote, standard output and
// error together. Error: "<program>: not found (is it on PATH?)", or "<program> exited N: <the first
// line it wrote>".
Result<std::string> runProgram(const std::vector<std::string>& argv);

}  // namespace frugal::batch
