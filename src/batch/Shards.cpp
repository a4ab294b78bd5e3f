#include "batch/Shards.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <numeric>

#include <nlohmann/json.hpp>

namespace frugal::batch {

namespace {

constexpr std::uint64_t kFnvOffset = 14695981039346656037ull;  // FNV-1a's 64-bit offset basis

std::uint64_t fnvStep(std::uint64_t h, const void* data, std::size_t size) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i) {
        h ^= p[i];
        h *= 1099511628211ull;
    }
    return h;
}

std::string hex(std::uint64_t h) {
    char buf[17];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
    return buf;
}

}  // namespace

std::string fnv1a(const void* data, std::size_t size) { return hex(fnvStep(kFnvOffset, data, size)); }

Result<Shard> parseShard(const std::string& text) {
    long long i = -1, n = -1;
    char slash = 0, extra = 0;
    const int got = std::sscanf(text.c_str(), "%lld%c%lld%c", &i, &slash, &n, &extra);
    if (got != 3 || slash != '/' || n < 1 || n > 100000 || i < 0)
        return Error{"--shard " + text + ": expected I/N, shard I of N (0 <= I < N <= 100000)", ErrorKind::BadInput};
    if (i >= n)
        return Error{"--shard " + text + ": I must be below N (0 to " + std::to_string(n - 1) + ")", ErrorKind::BadInput};
    return Shard{int(i), int(n)};
}

std::vector<int> assignShards(const std::vector<double>& costs, int shards) {
    std::vector<std::size_t> alone(costs.size());
    std::iota(alone.begin(), alone.end(), 0);
    return assignShards(costs, alone, shards);
}

std::vector<std::size_t> groupsOf(const Manifest& manifest) {
    // Union-find whose root is the group's first job (a reader's writer comes before it).
    std::vector<std::size_t> first(manifest.jobs.size());
    std::iota(first.begin(), first.end(), 0);
    const auto root = [&first](std::size_t i) {
        while (first[i] != i) i = first[i] = first[first[i]];
        return i;
    };
    for (std::size_t i = 0; i < manifest.jobs.size(); ++i)
        for (const ProducedInput& input : manifest.jobs[i].reads) {
            const std::size_t a = root(i), b = root(input.job);
            first[std::max(a, b)] = std::min(a, b);
        }
    for (std::size_t i = 0; i < first.size(); ++i) first[i] = root(i);
    return first;
}

std::vector<int> assignShards(const std::vector<double>& costs, const std::vector<std::size_t>& groupOf, int shards) {
    // The groups in the order of their first jobs, each with its cost and its number of jobs.
    std::map<std::size_t, std::pair<double, std::size_t>> groups;
    for (std::size_t job = 0; job < costs.size(); ++job) {
        auto& [cost, jobs] = groups[groupOf[job]];
        cost += costs[job];
        ++jobs;
    }
    std::vector<std::size_t> order;
    for (const auto& entry : groups) order.push_back(entry.first);
    std::stable_sort(order.begin(), order.end(),
                     [&groups](std::size_t a, std::size_t b) { return groups[a].first > groups[b].first; });
    // Least cost first, then fewest jobs (jobs of no cost, done ones in a plan, still spread), then
    // the lowest shard.
    std::vector<std::pair<double, std::size_t>> load(std::size_t(std::max(shards, 1)), {0.0, 0});
    std::map<std::size_t, int> shardOfGroup;
    for (const std::size_t group : order) {
        const auto least = std::min_element(load.begin(), load.end());  // the first of equals
        shardOfGroup[group] = int(least - load.begin());
        least->first += groups[group].first;
        least->second += groups[group].second;
    }
    std::vector<int> shardOf(costs.size(), 0);
    for (std::size_t job = 0; job < costs.size(); ++job) shardOf[job] = shardOfGroup[groupOf[job]];
    return shardOf;
}

std::vector<double> estimateCosts(const Manifest& manifest, const std::map<std::string, std::uint64_t>& triangles) {
    std::vector<double> costs;
    for (const Job& job : manifest.jobs) {
        // A scene with no triangles still costs its frames' clears and writes.
        const std::uint64_t t = std::max<std::uint64_t>(triangles.at(job.scene), 1);
        costs.push_back(double(t) * double(job.frames) * double(job.pixels));
    }
    return costs;
}

std::vector<double> correctedCosts(const Manifest& manifest, const std::vector<double>& estimates,
                                   const std::vector<std::optional<double>>& doneSeconds) {
    const auto median = [](std::vector<double> v) {
        std::sort(v.begin(), v.end());
        return v.empty() ? 0.0 : v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
    };
    std::map<Command, std::vector<double>> rates;
    std::vector<double> all;
    for (std::size_t i = 0; i < manifest.jobs.size(); ++i)
        if (doneSeconds[i] && estimates[i] > 0) {
            rates[manifest.jobs[i].command].push_back(*doneSeconds[i] / estimates[i]);
            all.push_back(*doneSeconds[i] / estimates[i]);
        }
    if (all.empty()) return estimates;
    const double overall = median(all);
    std::vector<double> costs;
    for (std::size_t i = 0; i < manifest.jobs.size(); ++i) {
        if (doneSeconds[i]) {
            costs.push_back(0.0);
            continue;
        }
        const auto own = rates.find(manifest.jobs[i].command);
        costs.push_back(estimates[i] * (own != rates.end() ? median(own->second) : overall));
    }
    return costs;
}

std::string planJson(const Plan& plan) {
    const nlohmann::json doc = {{"frugal_batch_plan", 1}, {"manifest", plan.manifest}, {"shards", plan.count},
                                {"shard_of", plan.shardOf}, {"costs", plan.costs}};
    return doc.dump() + "\n";
}

std::optional<Plan> parsePlan(const std::string& text) {
    const nlohmann::json doc = nlohmann::json::parse(text, nullptr, false);
    if (!doc.is_object() || doc.value("frugal_batch_plan", 0) != 1 || !doc.contains("manifest") ||
        !doc["manifest"].is_string() || !doc.contains("shards") || !doc["shards"].is_number_integer() ||
        !doc.contains("shard_of") || !doc["shard_of"].is_array() || !doc.contains("costs") || !doc["costs"].is_array())
        return std::nullopt;
    Plan plan;
    plan.manifest = doc["manifest"];
    plan.count = doc["shards"];
    for (const nlohmann::json& s : doc["shard_of"]) {
        if (!s.is_number_integer() || s.get<int>() < 0 || s.get<int>() >= plan.count) return std::nullopt;
        plan.shardOf.push_back(s.get<int>());
    }
    for (const nlohmann::json& c : doc["costs"]) {
        if (!c.is_number()) return std::nullopt;
        plan.costs.push_back(c.get<double>());
    }
    return plan;
}

std::string manifestHash(const Manifest& manifest) {
    std::uint64_t h = kFnvOffset;
    for (const Job& job : manifest.jobs) {
        h = fnvStep(h, job.canonical.data(), job.canonical.size() + 1);
        h = fnvStep(h, job.settingsText.data(), job.settingsText.size() + 1);
    }
    return hex(h);
}

Result<InputsHash> inputsHash(const Job& job, const std::string& version, const std::string& out) {
    std::uint64_t h = kFnvOffset;
    const auto add = [&h](const std::string& s) { h = fnvStep(h, s.data(), s.size() + 1); };  // with its NUL
    add(job.canonical);
    add(job.settingsText);
    add(version);
    std::vector<char> buffer(1 << 16);
    // The file's bytes into `into`, from FNV-1a's start.
    const auto digest = [&buffer](const std::string& path, std::uint64_t& into) {
        std::ifstream in(path, std::ios::binary);
        if (!in) return false;
        while (in.read(buffer.data(), std::streamsize(buffer.size())) || in.gcount() > 0)
            into = fnvStep(into, buffer.data(), std::size_t(in.gcount()));
        return true;
    };
    for (const std::string& path : job.inputFiles) {
        if (!digest(path, h))
            return Error{path + ": cannot read the file (an input of job '" + job.id + "')", ErrorKind::Io};
        add(path);
    }
    // The files of earlier jobs: their digests, by their path in OUT (OUT may move).
    InputsHash result;
    for (const ProducedInput& input : job.reads) {
        std::uint64_t file = kFnvOffset;
        const std::string path = (std::filesystem::path(out) / input.path).string();
        if (!digest(path, file))
            return Error{path + ": cannot read the file (job '" + job.id + "' reads it; job '" +
                             input.path.substr(0, input.path.find('/')) + "' writes it)",
                         ErrorKind::Io};
        result.reads[input.path] = hex(file);
        add(input.path);
        add(hex(file));
    }
    result.hash = hex(h);
    return result;
}

std::string doneJson(const DoneRecord& r) {
    nlohmann::json doc = {{"id", r.id}, {"inputs", r.inputs}, {"version", r.version}, {"seconds", r.seconds}};
    if (!r.reads.empty()) doc["reads"] = r.reads;
    return doc.dump(2) + "\n";
}

std::optional<DoneRecord> parseDone(const std::string& text) {
    const nlohmann::json doc = nlohmann::json::parse(text, nullptr, false);
    if (!doc.is_object() || !doc.contains("id") || !doc["id"].is_string() || !doc.contains("inputs") ||
        !doc["inputs"].is_string() || !doc.contains("version") || !doc["version"].is_string() ||
        !doc.contains("seconds") || !doc["seconds"].is_number())
        return std::nullopt;
    DoneRecord record{doc["id"], doc["inputs"], doc["version"], doc["seconds"].get<double>(), {}};
    if (doc.contains("reads")) {
        if (!doc["reads"].is_object()) return std::nullopt;
        for (const auto& [path, digest] : doc["reads"].items()) {
            if (!digest.is_string()) return std::nullopt;
            record.reads[path] = digest.get<std::string>();
        }
    }
    return record;
}

}  // namespace frugal::batch
