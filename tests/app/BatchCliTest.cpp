// `frugal batch`: a manifest's jobs split into shards that together run each job once and merge to
// what one process gives; --resume redoes only what is missing or changed; a failed job is recorded
// and the others run; an interrupted shard leaves whole files and no done record for the job it
// cut; a bad manifest is one line, before any work. A job that reads a file an earlier job writes:
// checked before any work, run in the writer's shard after it, redone when that file changed; and
// docs/batch.md's example, which does so, run as written.
#include <gtest/gtest.h>

#include <algorithm>
#include <csignal>
#include <filesystem>
#include <optional>
#include <random>
#include <regex>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "BackgroundSupport.h"
#include "CliSupport.h"
#include "JsonSupport.h"
#include "TestSupport.h"
#include "batch/Manifest.h"
#include "batch/Shards.h"

namespace frugal {
namespace {

namespace fs = std::filesystem;

using test::CliRun;
using test::readAll;
using test::runFrugal;
using test::runLab;  // writeManifest's jobs include reuse-bench, a research command: frugal-lab runs them

// Seven jobs of every command on built-in scenes, small; the camera path beside the manifest.
void writeManifest(const fs::path& dir) {
    test::writeFile(dir / "path.json", R"([{"eye":[0,0.5,3],"target":[0,0,0]},{"eye":[2,0.5,2],"target":[0,0,0]}])");
    test::writeFile(dir / "m.json", R"({
  "frugal_batch": 1,
  "defaults": {"size": "64x48"},
  "jobs": [
    {"id": "cubes", "scene": "builtin:cubes", "frames": "0:3", "outputs": ["color", "depth", "ids", "json"]},
    {"id": "culled", "scene": "builtin:cubes?count=6", "settings": {"cull": "conservative", "order": "key"},
     "outputs": ["color", "linear"]},
    {"id": "dominoes", "scene": "builtin:dominoes", "frames": "0:5", "camera_path": "path.json",
     "settings": {"reuse": true}},
    {"id": "cull", "command": "cull-report", "scene": "builtin:cubes", "views": 3, "repeat": 1},
    {"id": "reuse", "command": "reuse-bench", "scene": "builtin:dominoes", "frames": "0:3"},
    {"id": "report", "command": "report", "scene": "builtin:cubes?count=4", "views": 2, "repeat": 1},
    {"scene": "builtin:default", "camera": {"eye": [0, 1, 4], "target": [0, 0, 0], "fov": 35}}
  ]
})");
}

const std::vector<std::string> kIds = {"cubes", "culled", "dominoes", "cull", "reuse", "report", "job-6"};

// A reuse-bench job is a research command's: frugal refuses the manifest before any job runs, and
// frugal-lab (which has frugal's commands besides its own) runs it.
TEST(BatchCliTest, AResearchJobNeedsFrugalLab) {
    const fs::path dir = test::freshDir("BatchLab");
    writeManifest(dir);
    const CliRun refused = runFrugal(dir, {"batch", "m.json", "--out", "out", "-q"});
    EXPECT_EQ(refused.status, 1);
    EXPECT_EQ(refused.err,
              "error: manifest m.json line 11: job 4 'reuse': command: 'reuse-bench' is not a command of "
              "frugal (a research command: run this manifest with frugal-lab batch)\n");
    EXPECT_FALSE(fs::exists(dir / "out"));
}

TEST(BatchCliTest, ShardsRunEachJobOnceAndMergeToWhatOneProcessGives) {
    const fs::path dir = test::freshDir("BatchShards");
    writeManifest(dir);
    CliRun one = runLab(dir, {"batch", "m.json", "--out", "one", "-q"});
    ASSERT_EQ(one.status, 0) << one.err;
    EXPECT_EQ(one.out, "batch: shard 0/1: 7 done, 0 skipped (done before), 0 failed\n");
    for (int i = 0; i < 4; ++i) {
        const CliRun shard = runLab(dir, {"batch", "m.json", "--shard", std::to_string(i) + "/4", "--out", "four", "-q"});
        ASSERT_EQ(shard.status, 0) << shard.err;
    }
    int ran = 0;
    for (const std::string& id : kIds) {
        SCOPED_TRACE(id);
        EXPECT_TRUE(fs::exists(dir / "four" / id / "done.json"));
        const nlohmann::json done = test::readJson(dir / "four" / id / "done.json");
        EXPECT_EQ(done["id"], id);
        ++ran;
    }
    EXPECT_EQ(ran, 7);
    ASSERT_EQ(runLab(dir, {"batch", "merge", "one"}).status, 0);
    ASSERT_EQ(runLab(dir, {"batch", "merge", "four"}).status, 0);
    EXPECT_EQ(readAll(dir / "one" / "merged.json"), readAll(dir / "four" / "merged.json"));
    EXPECT_EQ(test::lines(readAll(dir / "four" / "times.csv")).size(), 8u);
    // The reports' tables joined, a row each led by the job: cull-report's 3 views x 9 methods.
    const std::vector<std::string> cull = test::lines(readAll(dir / "four" / "merged-cull-report.csv"));
    ASSERT_EQ(cull.size(), 1u + 3 * 9);
    EXPECT_EQ(cull[0], "job," + test::lines(readAll(dir / "four" / "cull" / "cull-report.csv"))[0]);
    EXPECT_EQ(cull[1].rfind("cull,", 0), 0u) << cull[1];
    EXPECT_TRUE(fs::exists(dir / "four" / "merged-report.csv"));
    EXPECT_TRUE(fs::exists(dir / "four" / "merged-reuse-bench.csv"));
    // The images themselves, byte for byte.
    for (const char* file : {"cubes/color_0003.png", "cubes/depth_0000.png", "cubes/ids_0002.png", "culled/color.png",
                             "culled/linear.pfm", "dominoes/color_0005.png", "job-6/color.png"})
        EXPECT_EQ(readAll(dir / "one" / file), readAll(dir / "four" / file)) << file;
    EXPECT_GT(fs::file_size(dir / "four" / "culled" / "linear.pfm"), 64u * 48u * 12u) << "a PFM of the linear colour";
    const nlohmann::json merged = test::readJson(dir / "one" / "merged.json");
    ASSERT_EQ(merged["jobs"].size(), 7u);
    EXPECT_EQ(merged["jobs"][3]["id"], "cull") << "manifest order";

    // Each shard's share of the jobs: every job once, whatever N.
    Result<batch::Manifest> manifest = batch::readManifest((dir / "m.json").string());
    ASSERT_TRUE(manifest) << manifest.error().message;
    const std::vector<int> shards = batch::assignShards(std::vector<double>(7, 1.0), 4);
    EXPECT_EQ(shards, (std::vector<int>{0, 1, 2, 3, 0, 1, 2})) << "equal costs: round robin in manifest order";
}

// The manifest parser on damaged text: bytes flipped, cut, doubled, deleted, and on noise. Each parse
// ends with a manifest or one error line naming the manifest; never a crash (ASan and UBSan check
// the scan of lines and nesting in the sanitizer build).
TEST(BatchManifestTest, DamagedTextGivesAManifestOrOneErrorLine) {
    const fs::path dir = test::freshDir("BatchDamaged");
    writeManifest(dir);
    const std::string good = readAll(dir / "m.json");
    const std::string path = (dir / "m.json").string();
    ASSERT_TRUE(batch::parseManifest(good, path));
    std::mt19937 random(20261203);
    const std::string alphabet = "{}[]\":,\\ \n\t0123456789.-+eE/abcdefghijklmnopqrstuvwxyz_ \x01\xff\xc3";
    int parsed = 0, refused = 0;
    for (int i = 0; i < 10000; ++i) {
        std::string text = good;
        const int edits = 1 + int(random() % 4);
        for (int e = 0; e < edits && !text.empty(); ++e) {
            const std::size_t at = random() % text.size();
            switch (random() % 5) {
            case 0: text[at] = alphabet[random() % alphabet.size()]; break;
            case 1: text.erase(at, 1 + random() % 8); break;
            case 2: text.insert(at, 1, alphabet[random() % alphabet.size()]); break;
            case 3: text.resize(at); break;
            default: text.insert(at, text.substr(at, 1 + random() % 40)); break;
            }
        }
        if (i % 10 == 0) {  // noise, and deep nesting
            text.assign(std::size_t(random() % 200), ' ');
            for (char& c : text) c = alphabet[random() % alphabet.size()];
            if (i % 100 == 0) text = std::string(5000, '[') + std::string(5000, ']');
        }
        Result<batch::Manifest> m = batch::parseManifest(text, path);
        if (m) {
            ++parsed;
            continue;
        }
        ++refused;
        ASSERT_EQ(m.error().message.rfind("manifest " + path, 0), 0u) << m.error().message;
        ASSERT_EQ(m.error().message.find('\n'), std::string::npos) << m.error().message;
    }
    EXPECT_GT(refused, 1000);
    EXPECT_GT(parsed, 10) << "some edits leave a valid manifest (in a string, in whitespace)";
}

TEST(BatchShardsTest, TheCostliestJobsGoFirstToTheLeastLoadedShard) {
    EXPECT_EQ(batch::assignShards({5, 4, 3, 3, 2, 1}, 2), (std::vector<int>{0, 1, 1, 0, 1, 0}))
        << "5 | 4 | 4+3 | 5+3 | 7+2 | 8+1: loads 9 and 9";
    EXPECT_EQ(batch::assignShards({1, 2, 3}, 5), (std::vector<int>{2, 1, 0})) << "more shards than jobs: some idle";
    // Any costs: the shards' loads differ by at most the largest job.
    std::vector<double> costs;
    for (int i = 0; i < 200; ++i) costs.push_back(double((i * 7919) % 101 + 1));
    for (const int n : {1, 3, 8, 64}) {
        const std::vector<int> shard = batch::assignShards(costs, n);
        std::vector<double> load(std::size_t(n), 0.0);
        for (std::size_t j = 0; j < costs.size(); ++j) load[std::size_t(shard[j])] += costs[j];
        const auto [least, most] = std::minmax_element(load.begin(), load.end());
        EXPECT_LE(*most - *least, 101.0) << n << " shards";
    }
}

TEST(BatchCliTest, AnArrayTaskTakesItsShardFromSlurmOrKubernetes) {
    const fs::path dir = test::freshDir("BatchArray");
    writeManifest(dir);
    ASSERT_EQ(runLab(dir, {"batch", "m.json", "--out", "one", "-q"}).status, 0);
    // Kubernetes' index for shards 0 and 1, Slurm's (an array numbered from 1) for 2 and 3.
    for (const std::string env : {"JOB_COMPLETION_INDEX=0", "JOB_COMPLETION_INDEX=1",
                                  "SLURM_ARRAY_TASK_ID=3 SLURM_ARRAY_TASK_MIN=1", "SLURM_ARRAY_TASK_ID=4 SLURM_ARRAY_TASK_MIN=1"}) {
        const CliRun task = runLab(dir, {"batch", "m.json", "--shard", "array/4", "--out", "array", "-q"}, env);
        ASSERT_EQ(task.status, 0) << env << ": " << task.err;
    }
    ASSERT_EQ(runLab(dir, {"batch", "merge", "one"}).status, 0);
    ASSERT_EQ(runLab(dir, {"batch", "merge", "array"}).status, 0);
    EXPECT_EQ(readAll(dir / "one" / "merged.json"), readAll(dir / "array" / "merged.json"));

    CliRun bad = runLab(dir, {"batch", "m.json", "--shard", "array/4"}, "JOB_COMPLETION_INDEX=4");
    EXPECT_EQ(bad.status, 2);
    EXPECT_EQ(bad.err, "error: --shard array/4: JOB_COMPLETION_INDEX=4 is not a shard index (0 to 3)\n");
    bad = runLab(dir, {"batch", "m.json", "--shard", "array/4"}, "env -u SLURM_ARRAY_TASK_ID -u JOB_COMPLETION_INDEX");
    EXPECT_EQ(bad.status, 2);
    EXPECT_EQ(bad.err.rfind("error: --shard array/4: neither SLURM_ARRAY_TASK_ID", 0), 0u) << bad.err;

    // --slurm --dry-run: the two scripts and the sbatch lines, nothing written.
    const CliRun dry = runLab(dir, {"batch", "m.json", "--slurm", "3", "--dry-run", "--out", "slurm-out",
                                       "--sbatch-args", "--partition=cpu --comment='two words'"});
    ASSERT_EQ(dry.status, 0) << dry.err;
    const std::string out = fs::weakly_canonical(dir / "slurm-out").string();
    EXPECT_NE(dry.out.find("#SBATCH --array=0-2\n"), std::string::npos) << dry.out;
    EXPECT_NE(dry.out.find("#SBATCH --output=" + out + "/slurm/shard-%a.log\n"), std::string::npos) << dry.out;
    EXPECT_NE(dry.out.find(" batch '" + fs::weakly_canonical(dir / "m.json").string() + "' --shard array/3 --out '" +
                           out + "' --resume\n"),
              std::string::npos)
        << dry.out;
    EXPECT_NE(dry.out.find("sbatch --parsable --partition=cpu '--comment=two words' " + out + "/slurm/shards.sh\n"),
              std::string::npos)
        << dry.out;
    EXPECT_NE(dry.out.find("--dependency=afterany:<the array's job id> " + out + "/slurm/merge.sh"), std::string::npos);
    EXPECT_FALSE(fs::exists(dir / "slurm-out"));
    bad = runLab(dir, {"batch", "m.json", "--slurm", "2", "--shard", "0/2"});
    EXPECT_EQ(bad.err, "error: --slurm: each array task picks its shard; give no --shard\n");
}

TEST(BatchShardsTest, FinishedJobsCorrectTheEstimatesOfTheirCommand) {
    batch::Manifest m;
    for (const batch::Command c : {batch::Command::Render, batch::Command::Render, batch::Command::Report,
                                   batch::Command::Report, batch::Command::CullReport}) {
        batch::Job job;
        job.command = c;
        m.jobs.push_back(job);
    }
    const std::vector<double> estimates{100, 200, 100, 300, 50};
    EXPECT_EQ(batch::correctedCosts(m, estimates, std::vector<std::optional<double>>(5)), estimates) << "none done";
    // A render done in 1 s (0.01 s a unit), a report in 5 s (0.05 s a unit): the rest in seconds.
    const std::vector<double> costs = batch::correctedCosts(m, estimates, {1.0, std::nullopt, 5.0, std::nullopt, std::nullopt});
    ASSERT_EQ(costs.size(), 5u);
    EXPECT_EQ(costs[0], 0.0) << "done: skipped";
    EXPECT_DOUBLE_EQ(costs[1], 2.0);
    EXPECT_EQ(costs[2], 0.0);
    EXPECT_DOUBLE_EQ(costs[3], 15.0) << "its command's rate";
    EXPECT_DOUBLE_EQ(costs[4], 50 * 0.03) << "no cull-report done: the median of all (0.01, 0.05)";
}

TEST(BatchCliTest, APlanCorrectedByWhatIsDoneIsTheSplitEveryShardFollows) {
    const fs::path dir = test::freshDir("BatchPlan");
    writeManifest(dir);
    ASSERT_EQ(runLab(dir, {"batch", "m.json", "--out", "out", "-q"}).status, 0);
    fs::remove(dir / "out" / "cubes" / "done.json");
    fs::remove(dir / "out" / "report" / "done.json");
    const CliRun plan = runLab(dir, {"batch", "m.json", "--plan", "2", "--out", "out"});
    ASSERT_EQ(plan.status, 0) << plan.err;
    EXPECT_EQ(plan.out.rfind("plan: out/plan.json, 2 shards of 7 jobs\n", 0), 0u) << plan.out;
    const nlohmann::json written = test::readJson(dir / "out" / "plan.json");
    ASSERT_EQ(written["costs"].size(), 7u);
    for (std::size_t i = 0; i < 7; ++i)
        EXPECT_EQ(written["costs"][i].get<double>() > 0, kIds[i] == "cubes" || kIds[i] == "report") << kIds[i];
    EXPECT_NE(written["shard_of"][0], written["shard_of"][5]) << "the two jobs left, one a shard";
    int ran = 0;
    for (int i = 0; i < 2; ++i) {
        const CliRun shard = runLab(dir, {"batch", "m.json", "--shard", std::to_string(i) + "/2", "--out", "out",
                                             "--resume"});
        ASSERT_EQ(shard.status, 0) << shard.err;
        EXPECT_NE(shard.err.find("jobs (split by out/plan.json)"), std::string::npos) << shard.err;
        ran += shard.out.find(": 1 done,") != std::string::npos;
    }
    EXPECT_EQ(ran, 2);
    // Another N, or another manifest: the plan is not theirs, and each shard splits by itself.
    const CliRun three = runLab(dir, {"batch", "m.json", "--shard", "0/3", "--out", "out", "--resume"});
    EXPECT_EQ(three.err.find("split by"), std::string::npos) << three.err;
}

TEST(BatchCliTest, ResumeRedoesOnlyWhatIsMissingOrChanged) {
    const fs::path dir = test::freshDir("BatchResume");
    writeManifest(dir);
    ASSERT_EQ(runLab(dir, {"batch", "m.json", "--out", "out", "-q"}).status, 0);
    CliRun again = runLab(dir, {"batch", "m.json", "--out", "out", "--resume", "-q"});
    ASSERT_EQ(again.status, 0) << again.err;
    EXPECT_EQ(again.out, "batch: shard 0/1: 0 done, 7 skipped (done before), 0 failed\n");

    // A job whose record is gone (killed before it finished), and one whose input file changed.
    fs::remove(dir / "out" / "cubes" / "done.json");
    test::writeFile(dir / "path.json", R"([{"eye":[0,0.6,3],"target":[0,0,0]}])");
    again = runLab(dir, {"batch", "m.json", "--out", "out", "--resume"});
    ASSERT_EQ(again.status, 0) << again.err;
    EXPECT_EQ(again.out, "batch: shard 0/1: 2 done, 5 skipped (done before), 0 failed\n");
    EXPECT_NE(again.err.find("] cubes: done in"), std::string::npos) << again.err;
    EXPECT_NE(again.err.find("] dominoes: done in"), std::string::npos) << again.err;
    EXPECT_NE(again.err.find("] report: done before, skipped"), std::string::npos) << again.err;
}

TEST(BatchCliTest, AFailedJobIsRecordedAndTheOthersRun) {
    const fs::path dir = test::freshDir("BatchFailed");
    test::writeFile(dir / "m.json", R"({"frugal_batch": 1, "jobs": [
      {"id": "fine", "scene": "builtin:cubes", "size": [32, 24]},
      {"id": "bad", "scene": "builtin:cubes", "size": [32, 24], "settings": {"reuse": true, "cull": "oracle"}},
      {"id": "also-fine", "scene": "builtin:default", "size": [32, 24]}]})");
    const CliRun run = runFrugal(dir, {"batch", "m.json", "--out", "out", "-q"});
    EXPECT_EQ(run.status, 1);
    EXPECT_EQ(run.out, "batch: shard 0/1: 2 done, 0 skipped (done before), 1 failed\n");
    const nlohmann::json failed = test::readJson(dir / "out" / "bad" / "failed.json");
    EXPECT_EQ(failed["error"].get<std::string>().rfind("error: ", 0), 0u) << failed;
    EXPECT_NE(failed["error"].get<std::string>().find("--reuse with --cull oracle"), std::string::npos) << failed;
    EXPECT_FALSE(fs::exists(dir / "out" / "bad" / "done.json"));
    EXPECT_TRUE(fs::exists(dir / "out" / "also-fine" / "done.json"));

    const CliRun status = runFrugal(dir, {"batch", "status", "out"});
    ASSERT_EQ(status.status, 0) << status.err;
    EXPECT_EQ(status.out.rfind("jobs: 3, done 2, running 0, failed 1, not started 0\n", 0), 0u) << status.out;
    EXPECT_NE(status.out.find("failed bad: error: "), std::string::npos) << status.out;
    const CliRun merge = runFrugal(dir, {"batch", "merge", "out"});
    EXPECT_EQ(merge.status, 1);
    EXPECT_EQ(merge.err, "error: out: job bad is not done (run its shard again, with --resume)\n");
}

TEST(BatchCliTest, AnInterruptedShardLeavesNoRecordForTheJobItCut) {
    const fs::path dir = test::freshDir("BatchInterrupted");
    test::writeFile(dir / "work" / "m.json", R"({"frugal_batch": 1, "jobs": [
      {"id": "short", "scene": "builtin:cubes", "size": [32, 24]},
      {"id": "long", "scene": "builtin:cubes", "size": [64, 48], "frames": "0:99999"}]})");
    test::Background run(dir, {"batch", "m.json", "--out", "out"});
    ASSERT_TRUE(run.waitUntil([&] { return fs::exists(run.work() / "out" / "long" / "color_0002.png"); })) << run.err();
    run.send(SIGTERM);
    EXPECT_EQ(run.wait(), 128 + SIGTERM);
    EXPECT_NE(run.err().find("batch: interrupted by SIGTERM in job long after 1 of 2 jobs"), std::string::npos)
        << run.err();
    EXPECT_TRUE(fs::exists(run.work() / "out" / "short" / "done.json"));
    EXPECT_FALSE(fs::exists(run.work() / "out" / "long" / "done.json"));
    EXPECT_FALSE(fs::exists(run.work() / "out" / "long" / "running.json"));
    for (const fs::directory_entry& f : fs::recursive_directory_iterator(run.work()))
        EXPECT_EQ(f.path().filename().string().find(".tmp-"), std::string::npos) << f.path();

    // Killed outright, the shard cannot say so: status finds its process gone.
    test::Background killed(dir / "killed", {"batch", (run.work() / "m.json").string(), "--out", "out", "--resume"});
    ASSERT_TRUE(killed.waitUntil([&] { return fs::exists(killed.work() / "out" / "long" / "color_0002.png"); }))
        << killed.err();
    killed.send(SIGKILL);
    EXPECT_EQ(killed.wait(), 128 + SIGKILL);
    const CliRun status = runFrugal(killed.work(), {"batch", "status", "out"});
    EXPECT_EQ(status.out.rfind("jobs: 2, done 1, running 0, failed 0, not started 0\nstopped: 1 (their process on "
                               "this host is gone, killed before they finished: --resume runs them)\ntime left: about ",
                               0),
              0u)
        << status.out;
}

TEST(BatchCliTest, ABadManifestIsOneLineBeforeAnyWork) {
    const fs::path dir = test::freshDir("BatchBad");
    const fs::path m = dir / "manifests";
    const fs::path run = dir / "run";
    fs::create_directories(run);
    const auto manifest = [&m](const std::string& name, const std::string& text) {
        test::writeFile(m / name, text);
        return (m / name).string();
    };
    const std::string head = "{\"frugal_batch\": 1,\n \"jobs\": [\n";
    const std::string unknown = manifest("unknown.json", head + "  {\"scene\": \"builtin:cubes\",\n   \"frame\": \"0:3\"}]}");
    const std::string missing = manifest("missing.json", head + "  {\"scene\": \"nowhere.obj\"}]}");
    const std::string twice = manifest("twice.json", head + "  {\"id\": \"a\", \"scene\": \"builtin:cubes\"},\n"
                                                            "  {\"id\": \"a\", \"scene\": \"builtin:default\"}]}");
    const std::string views = manifest("views.json", head + "  {\"scene\": \"builtin:cubes\", \"views\": 3}]}");
    const std::string setting = manifest("setting.json", head + "  {\"scene\": \"builtin:cubes\",\n"
                                                                "   \"settings\": {\"cull\": \"fast\"}}]}");
    const std::string broken = manifest("broken.json", "{\"frugal_batch\": 1, \"jobs\": [");
    const std::string version = manifest("version.json", "{\"frugal_batch\": 2, \"jobs\": []}");
    test::writeFile(m / "broken.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n");
    const std::string badScene = manifest("scene.json", head + "  {\"scene\": \"broken.obj\"}]}");
    test::expectOneErrorLine(run, {
        {{"batch", unknown}, "error: manifest " + unknown + " line 4: job 0: frame: not a key of a job (backend, "
                                                             "camera, camera_path, command, fps, frames, id, outputs, repeat, "
                                                             "scene, settings, size, time, views)", 1},
        {{"batch", missing}, "error: manifest " + missing + " line 3: job 0: scene: 'nowhere.obj': no such file (" +
                                 (m / "nowhere.obj").string() + ")", 1},
        {{"batch", twice}, "error: manifest " + twice + " line 4: job 1: id 'a' is also the id of the job at line 3 "
                                                        "(each job writes into a folder of its id)", 1},
        {{"batch", views}, "error: manifest " + views + " line 3: job 0 'job-0': views: render renders a camera or a "
                                                        "camera path, not views", 1},
        {{"batch", setting}, "", 1},
        {{"batch", broken}, "error: manifest " + broken + ": not JSON", 1},
        {{"batch", version}, "error: manifest " + version + " line 1: frugal_batch: expected 1 (the version of this "
                                                            "format)", 1},
        {{"batch", badScene}, "", 1},
        {{"batch", unknown, "--shard", "2/2"}, "error: --shard 2/2: I must be below N (0 to 1)", 2},
    });
    const CliRun bad = runFrugal(run, {"batch", setting});
    EXPECT_NE(bad.err.find("line 4: job 0: settings: key 'cull': "), std::string::npos) << bad.err;
    const CliRun scene = runFrugal(run, {"batch", badScene});
    EXPECT_NE(scene.err.find("line 3: scene: "), std::string::npos) << scene.err;
}

// Where each of `ids` is in a shard's progress lines ("[2/3] w: done in ..."), or npos.
std::vector<std::size_t> progressAt(const std::string& err, const std::vector<std::string>& ids) {
    std::vector<std::size_t> at;
    for (const std::string& id : ids) {
        const std::size_t line = err.find("] " + id + ": ");
        at.push_back(line);
    }
    return at;
}

// docs/batch.md's ```json blocks, in order.
std::vector<std::string> jsonBlocksOfBatchDoc() {
    const std::string page = readAll(fs::path(FRUGAL_TEST_DATA_DIR) / ".." / ".." / "docs" / "batch.md");
    static const std::regex block("```json\n([^`]*)```");
    std::vector<std::string> blocks;
    for (auto m = std::sregex_iterator(page.begin(), page.end(), block); m != std::sregex_iterator(); ++m)
        blocks.push_back((*m)[1].str());
    return blocks;
}

TEST(BatchCliTest, TheDocumentedExampleRunsAsWritten) {
    if (!fs::exists(FRUGAL_BUNNY_OBJ)) FRUGAL_SKIP_IF_MISSING(FRUGAL_BUNNY_OBJ << " (glmark2-data)");
    const fs::path dir = test::freshDir("BatchDocExample");
    // The page's manifest, and after it orbit.json, the camera path it names; the bunny as the page says.
    const std::vector<std::string> blocks = jsonBlocksOfBatchDoc();
    ASSERT_GE(blocks.size(), 2u) << "docs/batch.md: the manifest and orbit.json";
    test::writeFile(dir / "manifest.json", blocks[0]);
    test::writeFile(dir / "orbit.json", blocks[1]);
    fs::create_directories(dir / "models");
    fs::copy_file(FRUGAL_BUNNY_OBJ, dir / "models" / "bunny.obj");
    const nlohmann::json manifest = nlohmann::json::parse(blocks[0]);
    ASSERT_EQ(manifest["jobs"][0]["command"], "report");
    ASSERT_EQ(manifest["jobs"][1]["settings"], manifest["jobs"][0]["id"].get<std::string>() + "/settings.json")
        << "the example's point: a render with the settings the report before it writes";
    const std::string report = manifest["jobs"][0]["id"], orbit = manifest["jobs"][1]["id"];

    const CliRun run = runFrugal(dir, {"batch", "manifest.json", "--out", "out"});
    ASSERT_EQ(run.status, 0) << run.err;
    EXPECT_EQ(run.out, "batch: shard 0/1: " + std::to_string(manifest["jobs"].size()) +
                           " done, 0 skipped (done before), 0 failed\n");
    // The orbit read the settings where the report wrote them, and its record has their digest.
    const std::string settings = readAll(dir / "out" / report / "settings.json");
    ASSERT_FALSE(settings.empty());
    const nlohmann::json done = test::readJson(dir / "out" / orbit / "done.json");
    EXPECT_EQ(done["reads"], nlohmann::json({{report + "/settings.json", batch::fnv1a(settings.data(), settings.size())}}));
    EXPECT_NE(readAll(dir / "out" / orbit / "log.txt").find(" --settings out/" + report + "/settings.json "),
              std::string::npos)
        << readAll(dir / "out" / orbit / "log.txt");

    // In two shards: the report and the orbit in one, the report first; every job once.
    int ran = 0;
    for (const std::string shard : {"0/2", "1/2"}) {
        const CliRun part = runFrugal(dir, {"batch", "manifest.json", "--shard", shard, "--out", "two"});
        ASSERT_EQ(part.status, 0) << shard << ": " << part.err;
        const std::vector<std::size_t> at = progressAt(part.err, {report, orbit});
        EXPECT_EQ(at[0] == std::string::npos, at[1] == std::string::npos) << shard << ": " << part.err;
        if (at[0] != std::string::npos) {
            EXPECT_LT(at[0], at[1]) << part.err;
        }
        ran += int(test::lines(part.err).size()) - 1;
    }
    EXPECT_EQ(ran, int(manifest["jobs"].size()));
}

TEST(BatchCliTest, AJobReadsOnlyWhatAnEarlierJobWrites) {
    const fs::path dir = test::freshDir("BatchReadsBad");
    const fs::path m = dir / "manifests";
    const fs::path run = dir / "run";
    fs::create_directories(run);
    const auto manifest = [&m](const std::string& name, const std::string& jobs) {
        test::writeFile(m / name, "{\"frugal_batch\": 1,\n \"jobs\": [\n" + jobs + "]}");
        return (m / name).string();
    };
    const std::string self = manifest("self.json", "  {\"id\": \"a\", \"scene\": \"builtin:cubes\",\n"
                                                   "   \"settings\": \"a/settings.json\"}");
    const std::string later = manifest("later.json", "  {\"scene\": \"builtin:cubes\",\n"
                                                     "   \"settings\": \"r/settings.json\"},\n"
                                                     "  {\"id\": \"r\", \"command\": \"report\", \"scene\": \"builtin:cubes\"}");
    const std::string none = manifest("none.json", "  {\"id\": \"plain\", \"scene\": \"builtin:cubes\"},\n"
                                                   "  {\"scene\": \"builtin:cubes\", \"settings\": \"plain/settings.json\"}");
    const std::string images = manifest("images.json", "  {\"id\": \"plain\", \"scene\": \"builtin:cubes\", \"outputs\": [\"color\"]},\n"
                                                       "  {\"scene\": \"builtin:cubes\", \"settings\": \"plain/color.png\"}");
    const std::string kind = manifest("kind.json", "  {\"id\": \"r\", \"command\": \"report\", \"scene\": \"builtin:cubes\"},\n"
                                                   "  {\"scene\": \"builtin:cubes\", \"settings\": \"r/report.json\"}");
    test::expectOneErrorLine(run, {
        {{"batch", self}, "error: manifest " + self + " line 4: job 0: settings: 'a/settings.json': this job's own "
                                                      "output (a job reads what an earlier job writes)", 1},
        {{"batch", later}, "error: manifest " + later + " line 4: job 0: settings: 'r/settings.json': job 1 'r' at "
                                                        "line 5 comes after this one (a job reads what an earlier job "
                                                        "writes: put it first)", 1},
        {{"batch", none}, "error: manifest " + none + " line 4: job 1: settings: 'plain/settings.json': job 0 'plain' "
                                                      "writes no settings.json a job may read (it writes render.json; "
                                                      "a render writes settings.json when its settings are an object)", 1},
        {{"batch", images}, "error: manifest " + images + " line 4: job 1: settings: 'plain/color.png': job 0 "
                                                          "'plain' writes no color.png a job may read (it writes only images)", 1},
        {{"batch", kind}, "error: manifest " + kind + " line 4: job 1: settings: 'r/report.json': not a settings "
                                                      "file (settings reads a settings.json an earlier job writes: a "
                                                      "report's, or a render's whose settings are an object)", 1},
    });

    // A path that starts with "./" is a file beside the manifest, though its first part is a job's id.
    test::writeFile(m / "a" / "settings.json", R"({"cull": "sphere"})");
    const std::string own = manifest("own.json", "  {\"id\": \"a\", \"scene\": \"builtin:cubes\",\n"
                                                 "   \"settings\": \"./a/settings.json\"}");
    Result<batch::Manifest> parsed = batch::readManifest(own);
    ASSERT_TRUE(parsed) << parsed.error().message;
    EXPECT_TRUE(parsed->jobs[0].reads.empty());
    EXPECT_EQ(parsed->jobs[0].inputFiles, std::vector<std::string>{(m / "a" / "settings.json").string()});
}

// Six renders of equal cost: w writes settings.json (its settings are an object), r1 and r2 read it.
void writeLinkedManifest(const fs::path& dir, const std::string& wSettings = R"({"cull": "conservative"})") {
    test::writeFile(dir / "m.json", R"({"frugal_batch": 1, "defaults": {"size": [32, 24]}, "jobs": [
      {"id": "w", "scene": "builtin:cubes", "settings": )" + wSettings + R"(},
      {"id": "x", "scene": "builtin:cubes"},
      {"id": "r1", "scene": "builtin:cubes", "settings": "w/settings.json"},
      {"id": "y", "scene": "builtin:cubes"},
      {"id": "r2", "scene": "builtin:cubes", "settings": "w/settings.json", "outputs": ["color"]},
      {"id": "z", "scene": "builtin:cubes"}]})");
}

TEST(BatchShardsTest, AGroupGoesWholeToOneShardAtItsSummedCost) {
    batch::Manifest m;
    m.jobs.resize(6);
    m.jobs[5].reads.push_back({"--settings", 1, "job-1/settings.json"});
    m.jobs[4].reads.push_back({"--settings", 2, "job-2/settings.json"});
    EXPECT_EQ(batch::groupsOf(m), (std::vector<std::size_t>{0, 1, 2, 3, 2, 1}));
    // Groups {0} 5, {1, 5} 4+1, {2, 4} 3+2, {3} 3: 5 | 5 | 5+5 (fewer jobs) | 5+3.
    EXPECT_EQ(batch::assignShards({5, 4, 3, 3, 2, 1}, batch::groupsOf(m), 2), (std::vector<int>{0, 1, 0, 1, 0, 1}));
    EXPECT_EQ(batch::assignShards({5, 4, 3, 3, 2, 1}, 2), (std::vector<int>{0, 1, 1, 0, 1, 0})) << "alone, as before";
    // A chain through a middle job: one group.
    m.jobs[3].reads.push_back({"--settings", 0, "job-0/settings.json"});
    m.jobs[4].reads.push_back({"--settings", 3, "job-3/settings.json"});
    EXPECT_EQ(batch::groupsOf(m), (std::vector<std::size_t>{0, 1, 0, 0, 0, 1}));
}

TEST(BatchCliTest, JobsLinkedByAFileRunInOneShardWriterFirst) {
    const fs::path dir = test::freshDir("BatchLinkedShards");
    writeLinkedManifest(dir);
    CliRun one = runFrugal(dir, {"batch", "m.json", "--out", "one", "-q"});
    ASSERT_EQ(one.status, 0) << one.err;
    const nlohmann::json reader = test::readJson(dir / "one" / "r1" / "done.json");
    const std::string settings = readAll(dir / "one" / "w" / "settings.json");
    EXPECT_EQ(reader["reads"]["w/settings.json"], batch::fnv1a(settings.data(), settings.size()));
    EXPECT_FALSE(test::readJson(dir / "one" / "x" / "done.json").contains("reads"));

    // Equal costs alone would go round robin, w, r1 and r2 to three shards; linked, they go to one.
    // The shards run one after another, readers' first: a reader apart from its writer would fail.
    int ran = 0;
    for (const std::string shard : {"2/3", "1/3", "0/3"}) {
        const CliRun part = runFrugal(dir, {"batch", "m.json", "--shard", shard, "--out", "three"});
        ASSERT_EQ(part.status, 0) << shard << ": " << part.err;
        const std::vector<std::size_t> at = progressAt(part.err, {"w", "r1", "r2"});
        if (at[0] == std::string::npos) {
            EXPECT_EQ(at[1], std::string::npos) << part.err;
            EXPECT_EQ(at[2], std::string::npos) << part.err;
        } else {
            EXPECT_LT(at[0], at[1]) << part.err;
            EXPECT_LT(at[1], at[2]) << part.err;
        }
        ran += int(test::lines(part.err).size()) - 1;
    }
    EXPECT_EQ(ran, 6);
    ASSERT_EQ(runFrugal(dir, {"batch", "merge", "one"}).status, 0);
    ASSERT_EQ(runFrugal(dir, {"batch", "merge", "three"}).status, 0);
    EXPECT_EQ(readAll(dir / "one" / "merged.json"), readAll(dir / "three" / "merged.json"));

    // A plan keeps the group whole too, at its jobs' summed cost.
    fs::remove(dir / "three" / "w" / "done.json");
    const CliRun plan = runFrugal(dir, {"batch", "m.json", "--plan", "3", "--out", "three"});
    ASSERT_EQ(plan.status, 0) << plan.err;
    const nlohmann::json written = test::readJson(dir / "three" / "plan.json");
    EXPECT_EQ(written["shard_of"][0], written["shard_of"][2]) << written;
    EXPECT_EQ(written["shard_of"][0], written["shard_of"][4]) << written;
    EXPECT_GT(written["costs"][2].get<double>(), 0.0) << "its writer is not done: it may write another file";
    EXPECT_EQ(written["costs"][1].get<double>(), 0.0);
    EXPECT_NE(plan.out.find(": 3 jobs, 3 to run, cost "), std::string::npos) << plan.out;
    // A plan that parts a group (made by hand, or by a frugal before groups) is not followed.
    nlohmann::json parted = written;
    parted["shard_of"][2] = (written["shard_of"][0].get<int>() + 1) % 3;
    test::writeFile(dir / "three" / "plan.json", parted.dump());
    const CliRun unplanned = runFrugal(dir, {"batch", "m.json", "--shard", "0/3", "--out", "three", "--resume"});
    EXPECT_EQ(unplanned.status, 0) << unplanned.err;
    EXPECT_EQ(unplanned.err.find("split by"), std::string::npos) << unplanned.err;
}

TEST(BatchCliTest, ResumeRedoesAJobWhoseWritersFileChanged) {
    const fs::path dir = test::freshDir("BatchLinkedResume");
    writeLinkedManifest(dir);
    const auto resume = [&dir] { return runFrugal(dir, {"batch", "m.json", "--out", "out", "--resume"}); };
    ASSERT_EQ(runFrugal(dir, {"batch", "m.json", "--out", "out", "-q"}).status, 0);
    CliRun again = resume();
    EXPECT_EQ(again.out, "batch: shard 0/1: 0 done, 6 skipped (done before), 0 failed\n") << again.err;

    // The writer redone with another result: its readers are redone too, though their keys are the same.
    writeLinkedManifest(dir, R"({"cull": "sphere"})");
    again = resume();
    ASSERT_EQ(again.status, 0) << again.err;
    EXPECT_EQ(again.out, "batch: shard 0/1: 3 done, 3 skipped (done before), 0 failed\n") << again.err;
    for (const std::string id : {"w", "r1", "r2"}) EXPECT_NE(again.err.find("] " + id + ": done in"), std::string::npos) << again.err;
    const std::string settings = readAll(dir / "out" / "w" / "settings.json");
    EXPECT_NE(settings.find("sphere"), std::string::npos);
    EXPECT_EQ(test::readJson(dir / "out" / "r2" / "done.json")["reads"]["w/settings.json"],
              batch::fnv1a(settings.data(), settings.size()));

    // The writer redone with the same result (its record gone): the readers are skipped.
    fs::remove(dir / "out" / "w" / "done.json");
    again = resume();
    EXPECT_EQ(again.out, "batch: shard 0/1: 1 done, 5 skipped (done before), 0 failed\n") << again.err;
    EXPECT_NE(again.err.find("] r1: done before, skipped"), std::string::npos) << again.err;

    // The file the readers read changed, the writer's record standing: the readers are redone.
    test::writeFile(dir / "out" / "w" / "settings.json", R"({"cull": "backface"})");
    again = resume();
    EXPECT_EQ(again.out, "batch: shard 0/1: 2 done, 4 skipped (done before), 0 failed\n") << again.err;
    EXPECT_NE(again.err.find("] w: done before, skipped"), std::string::npos) << again.err;
    EXPECT_NE(again.err.find("] r1: done in"), std::string::npos) << again.err;

    // The file gone: its writer is redone, as a later job reads it.
    fs::remove(dir / "out" / "w" / "settings.json");
    again = resume();
    EXPECT_EQ(again.status, 0) << again.err;
    EXPECT_NE(again.err.find("] w: done in"), std::string::npos) << again.err;
    EXPECT_TRUE(fs::exists(dir / "out" / "w" / "settings.json"));

    // The writer failing: its readers do not run, each a failed job with one line.
    writeLinkedManifest(dir, R"({"reuse": true, "cull": "oracle"})");
    again = resume();
    EXPECT_EQ(again.status, 1);
    EXPECT_EQ(again.out, "batch: shard 0/1: 0 done, 3 skipped (done before), 3 failed\n") << again.err;
    const nlohmann::json failed = test::readJson(dir / "out" / "r1" / "failed.json");
    EXPECT_EQ(failed["error"], "error: w/settings.json: job 'w' failed, so this job, which reads it, did not run");
    EXPECT_FALSE(fs::exists(dir / "out" / "r1" / "done.json"));
    EXPECT_FALSE(fs::exists(dir / "out" / "r2" / "done.json"));
    EXPECT_EQ(runFrugal(dir, {"batch", "merge", "out"}).err, "error: out: job w is not done (run its shard again, with --resume)\n");
}

}  // namespace
}  // namespace frugal
