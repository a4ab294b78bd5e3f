// `frugal batch`: the jobs of a manifest (batch/Manifest.h), shard I of N of them, each run as the
// command line would run it, its outputs in OUT/<id>/; `batch status` and `batch merge` read OUT.
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <map>
#include <ostream>
#include <sstream>

#include <nlohmann/json.hpp>

#include <frugal/Files.h>
#include <frugal/Interrupt.h>
#include <frugal/Renderer.h>
#include <frugal/Scene.h>
#include <frugal/Version.h>

#include "app/Cli.h"
#include "app/Command.h"
#include "app/Commands.h"
#include "base/Format.h"
#include "batch/Manifest.h"
#include "batch/Shards.h"
#include "batch/Slurm.h"

namespace frugal {

namespace fs = std::filesystem;
using Json = nlohmann::json;
using namespace batch;

const char* batchHelp() {
    return R"(usage: frugal batch MANIFEST [--shard I/N] [--out DIR] [--resume] [-q]
       frugal batch MANIFEST --slurm N [--sbatch-args "..."] [--dry-run] [--out DIR]
       frugal batch MANIFEST --plan N [--out DIR]
       frugal batch status DIR
       frugal batch merge DIR

Runs the jobs of MANIFEST (a JSON list of render, cull-report, reuse-bench and report jobs on
scenes; docs/batch.md), or with --shard I/N the part of them that shard I of N takes: every shard
computes the same split from the manifest alone, balanced by an estimated cost (triangles x frames
x pixels), so N processes started anywhere divide the jobs without talking to each other. Each
job's files go to DIR/<id>/; when it finishes, DIR/<id>/done.json records its inputs' hash (the
job's keys, the files it reads, frugal's version) and its time; a job that fails leaves
DIR/<id>/failed.json with its error line, and the others still run. The manifest is checked in
full (keys, kinds, ids, files, scenes loaded) before any job runs.

A render may take the settings an earlier job writes: "settings": "bunny-report/settings.json",
when a job has the id bunny-report, is DIR/bunny-report/settings.json (a report's; or a render's
whose settings are an object), and "./bunny-report/settings.json" a file beside MANIFEST. The
check refuses a reference to a later job, to the job itself or to a file the job does not write.
Jobs linked so run in one shard, in manifest order; done.json keeps the digest of each such file
read, and --resume redoes a job whose file changed (its writer redone with another result).

--plan N (which --slurm runs itself) writes DIR/plan.json: a split into N shards from the costs
corrected by what DIR holds done (each command's seconds per unit of estimated cost; a job done
costs nothing), which every shard of N then follows instead of its own.

With --slurm N it submits the batch to Slurm instead: a job array of N tasks, each running its
shard (--shard array/N --resume, the index from SLURM_ARRAY_TASK_ID), and a merge job that starts
when the array has ended; the scripts and logs are in DIR/slurm/. MANIFEST, DIR and this binary
must be at the same paths on the nodes (a shared file system).

  status DIR   jobs done, running, failed (with their error lines) and left; the time left
  merge DIR    DIR/merged.json: every job in manifest order with its inputs' hash and its files
               (a render's images with their hash), identical whatever the shards; the jobs' CSV
               tables joined, a row each led by its job's id (DIR/merged-cull-report.csv, ...);
               DIR/times.csv: each job's seconds. Fails when a job is not done.
)";
}

namespace {

constexpr const char* kDone = "done.json";
constexpr const char* kFailed = "failed.json";
constexpr const char* kRunning = "running.json";
constexpr const char* kJobList = "batch.json";
constexpr const char* kPlan = "plan.json";


// The last "error: ..." line of a command's stderr, or its last line.
std::string errorLine(const std::string& err) {
    std::string last, lastError;
    std::istringstream in(err);
    for (std::string line; std::getline(in, line);) {
        if (line.empty()) continue;
        last = line;
        if (line.rfind("error: ", 0) == 0) lastError = line;
    }
    return oneLine(lastError.empty() ? last : lastError, 400);
}

// OUT/<id>/done.json, when it is one.
std::optional<DoneRecord> doneRecord(const fs::path& jobDir) {
    const std::optional<std::string> text = readFile((jobDir / kDone).string());
    return text ? parseDone(*text) : std::nullopt;
}

// Whether `record` is of the job as it is now: its inputs' hash and this version of frugal.
bool current(const DoneRecord& record, const std::string& hash) {
    return record.inputs == hash && record.version == version();
}

std::string hostName() {
    char name[256] = {};
    return gethostname(name, sizeof name - 1) == 0 ? name : "unknown";
}

// DIR/batch.json: the job list status and merge read (ids, commands, what each writes, cost).
std::string jobListJson(const Manifest& manifest, const std::vector<double>& costs) {
    Json jobs = Json::array();
    for (std::size_t i = 0; i < manifest.jobs.size(); ++i) {
        const Job& job = manifest.jobs[i];
        jobs.push_back({{"id", job.id}, {"command", toString(job.command)}, {"cost", costs[i]}});
    }
    return Json{{"frugal_batch", 1}, {"manifest", fs::absolute(manifest.path).lexically_normal().string()},
                {"jobs", jobs}}
               .dump(2) +
           "\n";
}

// The estimated costs, each scene loaded once for its triangles; a scene that does not load fails
// the manifest, at the line of the first job that names it.
Result<std::vector<double>> costsOf(const Manifest& manifest) {
    std::map<std::string, std::uint64_t> triangles;
    for (const Job& job : manifest.jobs) {
        if (triangles.count(job.scene)) continue;
        Result<Scene> loaded = loadScene(job.scene);
        if (!loaded)
            return Error{"manifest " + manifest.path + " line " + std::to_string(job.line) + ": scene: " + loaded.error().message,
                         ErrorKind::BadInput};
        triangles[job.scene] = loaded->triangleCount();
    }
    return estimateCosts(manifest, triangles);
}

// Per job, the files of it that later jobs read, by their path in OUT ("<id>/settings.json").
std::vector<std::vector<std::string>> filesReadOf(const Manifest& manifest) {
    std::vector<std::vector<std::string>> read(manifest.jobs.size());
    for (const Job& job : manifest.jobs)
        for (const ProducedInput& input : job.reads) read[input.job].push_back(input.path);
    return read;
}

// Whether every file of a job that later jobs read is in OUT: a job done whose file is gone runs
// again with --resume, to write it.
bool keptIn(const std::string& out, const std::vector<std::string>& files) {
    std::error_code ec;
    return std::all_of(files.begin(), files.end(),
                       [&](const std::string& f) { return fs::is_regular_file(fs::path(out) / f, ec); });
}

// Per job, its seconds when OUT/<id>/done.json is there with the inputs of now, and a job that
// writes what it reads is done too (else that job runs again first, and may write another file).
Result<std::vector<std::optional<double>>> doneSecondsOf(const Manifest& manifest, const std::string& out) {
    const std::vector<std::vector<std::string>> read = filesReadOf(manifest);
    std::vector<std::optional<double>> seconds;
    for (std::size_t i = 0; i < manifest.jobs.size(); ++i) {
        const Job& job = manifest.jobs[i];
        const std::optional<DoneRecord> record = doneRecord(fs::path(out) / job.id);
        const auto writerDone = [&seconds](const ProducedInput& input) { return seconds[input.job].has_value(); };
        const bool writersDone = std::all_of(job.reads.begin(), job.reads.end(), writerDone);
        // A record of another version: no hash to make.
        if (!record || record->version != version() || !writersDone || !keptIn(out, read[i])) {
            seconds.emplace_back();
            continue;
        }
        Result<InputsHash> hash = inputsHash(job, version(), out);
        if (!hash) return hash.error();
        seconds.push_back(current(*record, hash->hash) ? std::optional<double>(record->seconds) : std::nullopt);
    }
    return seconds;
}

// OUT/plan.json for `count` shards, from the estimates corrected by what OUT holds done.
Result<Plan> writePlan(const Manifest& manifest, const std::vector<double>& estimates, const std::string& out,
                       int count) {
    Result<std::vector<std::optional<double>>> done = doneSecondsOf(manifest, out);
    if (!done) return done.error();
    Plan plan;
    plan.manifest = manifestHash(manifest);
    plan.count = count;
    plan.costs = correctedCosts(manifest, estimates, *done);
    plan.shardOf = assignShards(plan.costs, groupsOf(manifest), count);
    if (Result<bool> w = writeFile((fs::path(out) / kPlan).string(), planJson(plan)); !w)
        return w.error();
    return plan;
}

// The split a shard follows: OUT/plan.json when it is for this manifest and this N (and keeps each
// group of jobs in one shard), else its own from the manifest alone (the same in every shard).
std::vector<int> splitOf(const Manifest& manifest, const std::vector<double>& estimates, const std::string& out,
                         int count, std::string& from) {
    const std::vector<std::size_t> groups = groupsOf(manifest);
    if (const std::optional<std::string> text = readFile((fs::path(out) / kPlan).string()))
        if (const std::optional<Plan> plan = parsePlan(*text);
            plan && plan->manifest == manifestHash(manifest) && plan->count == count &&
            plan->shardOf.size() == manifest.jobs.size()) {
            bool whole = true;
            for (std::size_t i = 0; i < groups.size(); ++i)
                whole = whole && plan->shardOf[i] == plan->shardOf[groups[i]];
            if (whole) {
                from = " (split by " + (fs::path(out) / kPlan).string() + ")";
                return plan->shardOf;
            }
        }
    from = "";
    return assignShards(estimates, groups, count);
}

struct RunOptions {
    std::string manifest;
    std::string out = "batch-out";
    Shard shard;
    bool resume = false;
    bool quiet = false;
    int slurm = 0;  // shards to submit as a Slurm array; 0: run here
    int plan = 0;   // shards to write OUT/plan.json for; 0: none
    std::string sbatchArgs;
    bool dryRun = false;
};

// Runs one job into DIR/<id>/: "" when done, else its error line. Only an interrupt stops the batch.
std::string runJob(const Job& job, const InputsHash& inputs, const RunOptions& o, double& seconds) {
    const fs::path dir = fs::path(o.out) / job.id;
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) return "error: " + dir.string() + ": cannot make the folder (" + ec.message() + ")";
    fs::remove(dir / kDone, ec);
    fs::remove(dir / kFailed, ec);
    const Json running = {{"host", hostName()}, {"pid", long(getpid())}, {"shard", std::to_string(o.shard.index) + "/" +
                                                                              std::to_string(o.shard.count)}};
    if (Result<bool> w = writeFile((dir / kRunning).string(), running.dump() + "\n"); !w)
        return "error: " + w.error().message;
    if (!job.settingsText.empty())
        if (Result<bool> w = writeFile((dir / "settings.json").string(), job.settingsText); !w)
            return "error: " + w.error().message;

    std::ostringstream out, err;
    const std::vector<std::string> line = commandLine(job, o.out);
    const auto start = std::chrono::steady_clock::now();
    const int status = runCli(line, out, err);
    seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    // What the command printed, after the command line that ran it (for people; merge lists it unhashed).
    std::string log = "$ frugal";
    for (const std::string& word : line) log += " " + shellWord(word);
    log += "\n" + out.str() + err.str();
    (void)writeFile((dir / "log.txt").string(), log);
    std::string problem;
    if (status == kExitOk) {
        const DoneRecord record{job.id, inputs.hash, version(), seconds, inputs.reads};
        if (Result<bool> w = writeFile((dir / kDone).string(), doneJson(record)); !w)
            problem = "error: " + w.error().message;
    } else {
        problem = errorLine(err.str());
        if (problem.empty()) problem = "error: " + std::string(toString(job.command)) + " exited " + std::to_string(status);
        const Json failed = {{"id", job.id}, {"status", status}, {"error", problem}};
        (void)writeFile((dir / kFailed).string(), failed.dump(2) + "\n");
    }
    fs::remove(dir / kRunning, ec);
    return problem;
}

// Records `job` as failed with `problem` without running it (it cannot: an input is missing).
void recordNotRun(const Job& job, const std::string& problem, const RunOptions& o) {
    const fs::path dir = fs::path(o.out) / job.id;
    std::error_code ec;
    fs::create_directories(dir, ec);
    fs::remove(dir / kDone, ec);
    const Json failed = {{"id", job.id}, {"status", kExitError}, {"error", problem}};
    (void)writeFile((dir / kFailed).string(), failed.dump(2) + "\n");
}

// The manifest checked and its jobs' estimated costs.
struct Checked {
    Manifest manifest;
    std::vector<double> costs;
};
Result<Checked> check(const std::string& manifestPath) {
    Result<Manifest> manifest = readManifest(manifestPath);
    if (!manifest) return manifest.error();
    // A job runs in this process: a research command (reuse-bench) needs frugal-lab.
    for (std::size_t i = 0; i < manifest->jobs.size(); ++i) {
        const Job& job = manifest->jobs[i];
        const std::string name = batch::toString(job.command);
        if (!hasCommand(name))
            return Error{"manifest " + manifestPath + " line " + std::to_string(job.line) + ": job " + std::to_string(i) +
                         " '" + job.id + "': command: '" + name + "' is not a command of " + programName() +
                         " (a research command: run this manifest with frugal-lab batch)"};
    }
    Result<std::vector<double>> costs = costsOf(*manifest);
    if (!costs) return costs.error();
    return Checked{std::move(*manifest), std::move(*costs)};
}

// The same, then `out` made, with its job list (every shard writes the same one: the last rename
// wins, each whole).
Result<Checked> checkInto(const std::string& manifestPath, const std::string& out) {
    Result<Checked> checked = check(manifestPath);
    if (!checked) return checked;
    std::error_code ec;
    fs::create_directories(out, ec);
    if (ec) return Error{out + ": cannot make the folder (" + ec.message() + ")", ErrorKind::Io};
    const std::string list = jobListJson(checked->manifest, checked->costs);
    if (Result<bool> w = writeFile((fs::path(out) / kJobList).string(), list); !w) return w.error();
    return checked;
}

// `--plan N`: OUT/plan.json, and what each shard is to run.
int planBatch(const RunOptions& o, std::ostream& out, std::ostream& err) {
    Result<Checked> checked = checkInto(o.manifest, o.out);
    if (!checked) return fail(err, checked.error());
    const Manifest* manifest = &checked->manifest;
    Result<Plan> plan = writePlan(*manifest, checked->costs, o.out, o.plan);
    if (!plan) return fail(err, plan.error());
    std::vector<int> jobs(std::size_t(o.plan), 0), left(std::size_t(o.plan), 0);
    std::vector<double> load(std::size_t(o.plan), 0.0);
    for (std::size_t i = 0; i < plan->shardOf.size(); ++i) {
        const std::size_t s = std::size_t(plan->shardOf[i]);
        ++jobs[s];
        left[s] += plan->costs[i] > 0;
        load[s] += plan->costs[i];
    }
    out << "plan: " << o.out << "/" << kPlan << ", " << o.plan << " shards of " << manifest->jobs.size() << " jobs\n";
    for (int s = 0; s < o.plan; ++s)
        out << "  shard " << s << ": " << jobs[std::size_t(s)] << (jobs[std::size_t(s)] == 1 ? " job, " : " jobs, ")
            << left[std::size_t(s)] << " to run, cost " << fmt(load[std::size_t(s)]) << "\n";
    return kExitOk;
}

int runBatch(const RunOptions& o, std::ostream& out, std::ostream& err) {
    Result<Checked> checked = checkInto(o.manifest, o.out);
    if (!checked) return fail(err, checked.error());
    const Manifest* manifest = &checked->manifest;
    std::string splitFrom;
    const std::vector<int> shardOf = splitOf(*manifest, checked->costs, o.out, o.shard.count, splitFrom);

    // In manifest order: a job that writes what another reads runs first (both are in this shard).
    std::vector<std::size_t> mine;
    for (std::size_t i = 0; i < manifest->jobs.size(); ++i)
        if (shardOf[i] == o.shard.index) mine.push_back(i);
    const std::vector<std::vector<std::string>> read = filesReadOf(*manifest);
    std::vector<bool> failedHere(manifest->jobs.size(), false);
    int done = 0, skipped = 0, failed = 0;
    const std::string shardName = std::to_string(o.shard.index) + "/" + std::to_string(o.shard.count);
    if (!o.quiet)
        err << "batch: shard " << shardName << ": " << mine.size() << " of " << manifest->jobs.size() << " jobs"
            << splitFrom << "\n";
    for (std::size_t k = 0; k < mine.size(); ++k) {
        const Job& job = manifest->jobs[mine[k]];
        const std::string progress = "[" + std::to_string(k + 1) + "/" + std::to_string(mine.size()) + "] " + job.id;
        // A job cannot run when a job whose file it reads failed here, or an input cannot be read.
        std::string problem;
        for (const ProducedInput& input : job.reads)
            if (problem.empty() && failedHere[input.job])
                problem = "error: " + input.path + ": job '" + manifest->jobs[input.job].id +
                          "' failed, so this job, which reads it, did not run";
        Result<InputsHash> hash =
            problem.empty() ? inputsHash(job, version(), o.out) : Result<InputsHash>(InputsHash{});
        if (problem.empty() && !hash) problem = "error: " + hash.error().message;
        if (!problem.empty()) {
            recordNotRun(job, problem, o);
            failedHere[mine[k]] = true;
            ++failed;
            err << progress << ": failed: " << problem << "\n";
            continue;
        }
        if (o.resume) {
            if (const std::optional<DoneRecord> record = doneRecord(fs::path(o.out) / job.id);
                record && current(*record, hash->hash) && keptIn(o.out, read[mine[k]])) {
                ++skipped;
                if (!o.quiet) err << progress << ": done before, skipped\n";
                continue;
            }
        }
        double seconds = 0;
        problem = runJob(job, *hash, o, seconds);
        if (const int signal = notedSignal(); signal != 0) {
            err << "batch: interrupted by " << signalName(signal) << " in job " << job.id << " after " << done
                << " of " << mine.size() << " jobs; --resume finishes the rest\n";
            return kExitError;
        }
        if (problem.empty()) {
            ++done;
            if (!o.quiet) err << progress << ": done in " << fmt(seconds) << " s\n";
        } else {
            ++failed;
            failedHere[mine[k]] = true;
            err << progress << ": failed: " << problem << "\n";
        }
    }
    out << "batch: shard " << shardName << ": " << done << " done, " << skipped << " skipped (done before), "
        << failed << " failed\n";
    return failed == 0 ? kExitOk : kExitError;
}

// This binary's absolute path, for the scripts the nodes run.
std::string thisBinary() {
    std::error_code ec;
    const fs::path self = fs::read_symlink("/proc/self/exe", ec);
    return ec ? std::string("frugal") : self.string();
}

// The job id sbatch --parsable printed: its last line, up to a ';' (a cluster's name after it).
Result<std::string> jobIdOf(const std::string& printed) {
    std::string last;
    std::istringstream in(printed);
    for (std::string line; std::getline(in, line);)
        if (!line.empty()) last = line;
    last = last.substr(0, last.find(';'));
    if (last.empty() || last.find_first_not_of("0123456789") != std::string::npos)
        return Error{"sbatch printed no job id: " + oneLine(printed, 200), ErrorKind::BadInput};
    return last;
}

int submitSlurm(const RunOptions& o, std::ostream& out, std::ostream& err) {
    Result<Checked> checked = check(o.manifest);  // OUT is written only once the dry run is ruled out
    if (!checked) return fail(err, checked.error());
    const Manifest* manifest = &checked->manifest;
    const std::vector<double>* costs = &checked->costs;
    Result<std::vector<std::string>> extra = splitWords(o.sbatchArgs);
    if (!extra) return fail(err, Error{"--sbatch-args: " + extra.error().message, ErrorKind::BadInput});
    const std::string dir = fs::absolute(o.out).lexically_normal().string();
    if (dir.find_first_of(" \t\n%") != std::string::npos)
        return fail(err, Error{"--out " + o.out + ": the Slurm scripts' #SBATCH --output takes no space or '%' in a path",
                               ErrorKind::BadInput, false});
    const SlurmScripts scripts =
        slurmScripts(thisBinary(), fs::absolute(o.manifest).lexically_normal().string(), dir, o.slurm);
    const std::string shardsPath = dir + "/slurm/shards.sh", mergePath = dir + "/slurm/merge.sh";
    std::vector<std::string> arrayCommand{"sbatch", "--parsable"};
    arrayCommand.insert(arrayCommand.end(), extra->begin(), extra->end());
    std::vector<std::string> mergeCommand = arrayCommand;
    arrayCommand.push_back(shardsPath);
    if (o.dryRun) {
        out << "# " << shardsPath << "\n" << scripts.shards << "# " << mergePath << "\n" << scripts.merge
            << "# submitted with:\n";
        for (const std::string& w : arrayCommand) out << (&w == &arrayCommand.front() ? "" : " ") << shellWord(w);
        out << "\n";
        for (const std::string& w : mergeCommand) out << shellWord(w) << " ";
        out << "--dependency=afterany:<the array's job id> " << shellWord(mergePath) << "\n";
        return kExitOk;
    }
    std::error_code ec;
    fs::create_directories(dir + "/slurm", ec);
    if (ec) return fail(err, Error{dir + "/slurm: cannot make the folder (" + ec.message() + ")", ErrorKind::Io});
    FileSet files;
    files.add(shardsPath, scripts.shards);
    files.add(mergePath, scripts.merge);
    files.add(dir + "/" + kJobList, jobListJson(*manifest, *costs));
    if (Result<bool> written = files.commit(); !written) return fail(err, written.error());
    if (Result<Plan> plan = writePlan(*manifest, *costs, dir, o.slurm); !plan) return fail(err, plan.error());
    Result<std::string> array = runProgram(arrayCommand);
    if (!array) return fail(err, array.error());
    Result<std::string> arrayId = jobIdOf(*array);
    if (!arrayId) return fail(err, arrayId.error());
    mergeCommand.push_back("--dependency=afterany:" + *arrayId);
    mergeCommand.push_back(mergePath);
    Result<std::string> merge = runProgram(mergeCommand);
    if (!merge) return fail(err, Error{"the array is job " + *arrayId + "; the merge job: " + merge.error().message, merge.error().kind});
    Result<std::string> mergeId = jobIdOf(*merge);
    if (!mergeId) return fail(err, mergeId.error());
    const Json jobs = {{"array", *arrayId}, {"merge", *mergeId}, {"shards", o.slurm}};
    if (Result<bool> w = writeFile(dir + "/slurm/jobs.json", jobs.dump(2) + "\n"); !w)
        return fail(err, w.error());
    out << "submitted: job array " << *arrayId << " (" << o.slurm << " shards of " << manifest->jobs.size()
        << " jobs), then merge job " << *mergeId << "; 'frugal batch status " << o.out << "' follows them\n";
    return kExitOk;
}

// The job list an output folder holds.
Result<Json> jobList(const std::string& dir) {
    const std::optional<std::string> text = readFile((fs::path(dir) / kJobList).string());
    if (!text) return Error{dir + ": no " + kJobList + " (not the output folder of a batch)", ErrorKind::BadInput};
    Json doc = Json::parse(*text, nullptr, false);
    if (!doc.is_object() || !doc.contains("jobs") || !doc["jobs"].is_array())
        return Error{dir + "/" + kJobList + ": not a batch's job list", ErrorKind::BadInput};
    return doc;
}

int runStatus(const std::string& dir, std::ostream& out, std::ostream& err) {
    Result<Json> list = jobList(dir);
    if (!list) return fail(err, list.error());
    int done = 0, running = 0, stale = 0, left = 0;
    double doneSeconds = 0, doneCost = 0, leftCost = 0;
    std::vector<std::string> failures;
    for (const Json& job : (*list)["jobs"]) {
        const fs::path jobDir = fs::path(dir) / job.value("id", "");
        const double cost = job.value("cost", 0.0);
        if (const std::optional<DoneRecord> record = doneRecord(jobDir)) {
            ++done;
            doneSeconds += record->seconds;
            doneCost += cost;
            continue;
        }
        leftCost += cost;
        if (const std::optional<std::string> text = readFile((jobDir / kFailed).string())) {
            const Json failed = Json::parse(*text, nullptr, false);
            failures.push_back(job.value("id", "") + ": " +
                               (failed.is_object() ? failed.value("error", std::string("?")) : std::string("?")));
        } else if (const std::optional<std::string> runningText = readFile((jobDir / kRunning).string())) {
            // A record whose process is gone (killed outright) on this host: the job will not finish.
            const Json r = Json::parse(*runningText, nullptr, false);
            const bool gone = r.is_object() && r.value("host", "") == hostName() && r.contains("pid") &&
                              r["pid"].is_number_integer() && kill(pid_t(r["pid"].get<long>()), 0) != 0 &&
                              errno == ESRCH;
            ++(gone ? stale : running);
        } else {
            ++left;
        }
    }
    out << "jobs: " << (*list)["jobs"].size() << ", done " << done << ", running " << running << ", failed "
        << failures.size() << ", not started " << left << "\n";
    if (stale > 0)
        out << "stopped: " << stale << " (their process on this host is gone, killed before they finished: "
            << "--resume runs them)\n";
    if (done > 0 && leftCost > 0 && doneCost > 0)
        out << "time left: about " << fmt(doneSeconds / doneCost * leftCost)
            << " s of work (the finished jobs' seconds per unit of estimated cost, over the rest)\n";
    for (const std::string& f : failures) out << "failed " << f << "\n";
    return kExitOk;
}

int runMerge(const std::string& dir, std::ostream& out, std::ostream& err) {
    Result<Json> list = jobList(dir);
    if (!list) return fail(err, list.error());
    Json jobs = Json::array();
    std::string times = "id,command,seconds\n";
    // The jobs' CSV tables joined by file name, each row led by its job's id: merged-<name>.csv.
    std::map<std::string, std::string> tables;
    for (const Json& entry : (*list)["jobs"]) {
        const std::string id = entry.value("id", "");
        const fs::path jobDir = fs::path(dir) / id;
        const std::optional<DoneRecord> record = doneRecord(jobDir);
        if (!record)
            return fail(err, Error{dir + ": job " + id + " is not done (run its shard again, with --resume)",
                                   ErrorKind::BadInput});
        // Its files, by name; a render's images and settings (deterministic) with their hash, the
        // rest (reports, whose figures are timed and whose picks follow the timings) without.
        const bool render = entry.value("command", "") == "render";
        std::vector<std::string> names;
        for (const fs::directory_entry& f : fs::directory_iterator(jobDir)) {
            const std::string name = f.path().filename().string();
            if (name != kDone && name != kRunning && name != kFailed && f.is_regular_file()) names.push_back(name);
        }
        std::sort(names.begin(), names.end());
        Json files = Json::array();
        for (const std::string& name : names) {
            Json file = {{"name", name}};
            if (render && (hasExtension(name, ".png") || hasExtension(name, ".pfm") || name == "settings.json")) {
                const std::optional<std::string> bytes = readFile((jobDir / name).string());
                if (!bytes) return fail(err, Error{(jobDir / name).string() + ": cannot read the file", ErrorKind::Io});
                file["fnv1a"] = fnv1a(bytes->data(), bytes->size());
            } else if (hasExtension(name, ".csv")) {
                const std::optional<std::string> csv = readFile((jobDir / name).string());
                if (!csv) return fail(err, Error{(jobDir / name).string() + ": cannot read the file", ErrorKind::Io});
                std::istringstream lines(*csv);
                std::string header;
                std::getline(lines, header);
                std::string& table = tables[name];
                if (table.empty()) table = "job," + header + "\n";
                else if (table.compare(0, table.find('\n'), "job," + header) != 0)
                    return fail(err, Error{(jobDir / name).string() + ": its header differs from the other jobs' " + name,
                                           ErrorKind::BadInput});
                for (std::string row; std::getline(lines, row);)
                    if (!row.empty()) table += id + "," + row + "\n";
            }
            files.push_back(file);
        }
        jobs.push_back({{"id", id}, {"command", entry.value("command", "")}, {"inputs", record->inputs},
                        {"version", record->version}, {"files", files}});
        times += id + "," + entry.value("command", "") + "," + fmt(record->seconds) + "\n";
    }
    FileSet files;
    files.add(dir + "/merged.json", Json{{"frugal_batch", 1}, {"jobs", jobs}}.dump(2) + "\n");
    files.add(dir + "/times.csv", times);
    std::string joined;
    for (const auto& [name, table] : tables) {
        files.add(dir + "/merged-" + name, table);
        joined += ", merged-" + name;
    }
    if (Result<bool> written = files.commit(); !written) return fail(err, written.error());
    out << "merged " << jobs.size() << " jobs into " << dir << "/merged.json" << joined << " and times.csv\n";
    return kExitOk;
}

}  // namespace

int runBatch(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    if (!args.empty() && (args[0] == "status" || args[0] == "merge")) {
        if (args.size() != 2 || args[1].rfind("-", 0) == 0)
            return usageError(err, "batch " + args[0] + ": expected one output folder (frugal batch " + args[0] +
                                       " DIR)");
        return args[0] == "status" ? runStatus(args[1], out, err) : runMerge(args[1], out, err);
    }
    RunOptions o;
    std::string shard;  // empty: not given, every job
    CommandLine command{"batch", batchHelp(), nullptr};
    command.flags = {{"batch", {
        flag::text("--shard", "I/N", "run shard I of N (0 <= I < N; default 0/1: every job); array/N: I from "
                   "SLURM_ARRAY_TASK_ID (a Slurm job array) or JOB_COMPLETION_INDEX (a Kubernetes Indexed Job)",
                   shard, "a shard"),
        flag::text("--out", "DIR", "the output folder: DIR/<id>/ for each job (default batch-out)", o.out),
        flag::on("--resume", "skip the jobs whose done.json matches their inputs (the others run again)", o.resume),
        flag::on("-q, --quiet", "no progress lines", o.quiet),
        flag::whole("--plan", "N", "write OUT/plan.json, the split into N shards that every shard then follows, "
                    "from costs corrected by the jobs OUT holds done (--slurm writes one itself)", o.plan, 1, 100000),
    }}, {"Slurm", {
        flag::whole("--slurm", "N", "submit the batch as a Slurm job array of N shards and a merge job after it",
                    o.slurm, 1, 100000),
        flag::text("--sbatch-args", "\"...\"", "options for both sbatch calls (--partition=..., --time=..., "
                   "--mem=...), split at spaces, '...' and \"...\" quoting", o.sbatchArgs, "options"),
        flag::on("--dry-run", "with --slurm: print the scripts and the sbatch commands; write and submit nothing",
                 o.dryRun),
    }}};
    command.positional = [&o](const std::string& arg, ArgCursor& cursor) {
        if (!o.manifest.empty()) return cursor.fail("unexpected argument '" + arg + "' (one MANIFEST only)");
        o.manifest = arg;
    };
    command.finish = [&](ArgCursor& cursor) {
        const bool shardGiven = !shard.empty();
        const bool fromArray = shard.rfind("array/", 0) == 0;
        Result<Shard> s = parseShard(fromArray ? "0/" + shard.substr(6) : shardGiven ? shard : "0/1");
        if (o.manifest.empty()) cursor.fail("batch: no manifest (frugal batch MANIFEST.json; 'frugal help batch')");
        else if (!s) cursor.fail(s.error().message);
        else if (o.slurm > 0 && shardGiven) cursor.fail("--slurm: each array task picks its shard; give no --shard");
        else if (o.plan > 0 && (shardGiven || o.slurm > 0)) cursor.fail("--plan: it runs nothing; give no --shard or --slurm");
        else if (o.dryRun && o.slurm == 0) cursor.fail("--dry-run: only with --slurm N");
        else if (!o.sbatchArgs.empty() && o.slurm == 0) cursor.fail("--sbatch-args: only with --slurm N");
        else if (!fromArray) o.shard = *s;
        else if (Result<int> index = arrayTaskIndex(s->count); !index) cursor.fail(index.error().message);
        else o.shard = Shard{*index, s->count};
    };
    if (std::optional<int> status = parseCommandLine(command, args, out, err)) return *status;
    return o.slurm > 0 ? submitSlurm(o, out, err) : o.plan > 0 ? planBatch(o, out, err) : runBatch(o, out, err);
}

}  // namespace frugal
