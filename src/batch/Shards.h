// Which jobs of a manifest shard I of N runs, and what each job's finished run leaves behind.
//
// Shards: every shard computes the same assignment from the manifest alone, so N processes started
// anywhere, in any order, split the jobs without talking to each other. A job's estimated cost is
// triangles × frames × pixels; jobs go, costliest first (ties: manifest order), to the shard with the
// least cost so far (ties: the fewest jobs, then the lowest shard), which keeps the shards within
// one job of each other. Jobs linked by a file one writes and another reads (Job::reads) form a
// group that goes whole to one shard, at the sum of its jobs' costs, and runs there in manifest
// order: the writer first.
//
// Records, in OUT/<id>/: done.json when a job finished (its inputs' hash, the digests of the files
// it read of earlier jobs, frugal's version, the seconds it took); failed.json with its error line
// when it failed; running.json while it runs.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <frugal/Result.h>

#include "batch/Manifest.h"

namespace frugal::batch {

// "I/N" with 0 <= I < N <= 100000. Error: "--shard 4/4: I must be below N (0 to 3)".
struct Shard {
    int index = 0, count = 1;
};
Result<Shard> parseShard(const std::string& text);

// Costs by job (any unit, compared only among themselves) -> the shard of each job.
std::vector<int> assignShards(const std::vector<double>& costs, int shards);

// Per job, the index of the first job of its group: the jobs linked, directly or through others, by
// the files one reads of another (Job::reads). A job that reads none and is read by none is alone.
std::vector<std::size_t> groupsOf(const Manifest& manifest);

// The same split with groups (`groupOf`, from groupsOf): each group is sent whole where
// assignShards would send one job of its jobs' summed cost, its first job's place breaking ties.
std::vector<int> assignShards(const std::vector<double>& costs, const std::vector<std::size_t>& groupOf, int shards);

// triangles × frames × pixels; `triangles` has every job's scene.
std::vector<double> estimateCosts(const Manifest& manifest, const std::map<std::string, std::uint64_t>& triangles);

// The estimates corrected by what finished jobs measured (`doneSeconds`: per job, its seconds when
// it is done with the inputs of now): a job done costs 0, as it will be skipped; the others' costs
// become estimated seconds, their estimate times the median seconds per unit of estimate of the
// finished jobs of their command (of all finished jobs when their command has none). With no job
// finished, the estimates as they are.
std::vector<double> correctedCosts(const Manifest& manifest, const std::vector<double>& estimates,
                                   const std::vector<std::optional<double>>& doneSeconds);

// A split written once (OUT/plan.json, by `--slurm` or `--plan`) that every shard then reads instead
// of computing its own: the only way corrected costs, which depend on what is done when they are
// computed, still give every shard the same split.
struct Plan {
    std::string manifest;    // manifestHash of the manifest it splits
    int count = 0;           // N
    std::vector<int> shardOf;
    std::vector<double> costs;  // the costs it was made from
};
std::string planJson(const Plan& plan);
std::optional<Plan> parsePlan(const std::string& text);
// FNV-1a over the jobs' ids and keys, in order: a plan is for this manifest and no other.
std::string manifestHash(const Manifest& manifest);

// 64-bit FNV-1a of the job's keys, the contents of the files it reads (those of the manifest's
// folder and those earlier jobs wrote into `out`), its inline settings and the version of frugal
// that runs it, as 16 hex digits: a job is redone when any of these changed. `reads` has the
// digest of each file it reads of an earlier job, by its path in `out` ("bunny-report/settings.json").
// Error: an input file that cannot be read.
struct InputsHash {
    std::string hash;
    std::map<std::string, std::string> reads;
};
Result<InputsHash> inputsHash(const Job& job, const std::string& version, const std::string& out);

struct DoneRecord {
    std::string id, inputs, version;
    double seconds = 0.0;
    std::map<std::string, std::string> reads;  // the digests of the files it read of earlier jobs
};
std::string doneJson(const DoneRecord& record);
// The record in `text`, or nothing when it is not one (a torn or foreign file counts as not done).
std::optional<DoneRecord> parseDone(const std::string& text);

// 64-bit FNV-1a of bytes, as 16 hex digits.
std::string fnv1a(const void* data, std::size_t size);

}  // namespace frugal::batch
