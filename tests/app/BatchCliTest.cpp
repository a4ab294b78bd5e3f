// `frugal batch`: a manifest's jobs split into shards that together run each job once and merge to
// what one process gives; --resume redoes only what is missing or changed; a failed job is recorded
// and the others run; an interrupted shard leaves whole files and no done record for the job it
// cut; a bad manifest is one line, before any work.
#include <gtest/gtest.h>

#include <algorithm>
#include <csignal>
#include <filesystem>
#include <optional>
#include <random>
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

// Seven jobs of every command on built-in scenes, small; the camera path beside the manifest.
void writeManifest(const fs::path& dir) {
    test::writeFile(dir / "path.json", R"([{"eye":[0,0.5,3],"target":[0,0,0]},{"eye":[2,0.5,2],"target":[0,0,0]}])");
    test::writeFile(dir / "m.json", R"({
  "frugal_batch": 1,
  "defaults": {"size": "64x48"},
  "jobs": [
    {"id": "cubes", "scene": "builtin:cubes", "frames": "0:3", "outputs": ["color", "depth", "ids", "json"]},
    {"id": "culled", "scene": "builtin:cubes?count=6", "settings": {"cull": "conservative", "order": "key"}},
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

TEST(BatchCliTest, ShardsRunEachJobOnceAndMergeToWhatOneProcessGives) {
    const fs::path dir = test::freshDir("BatchShards");
    writeManifest(dir);
    CliRun one = runFrugal(dir, {"batch", "m.json", "--out", "one", "-q"});
    ASSERT_EQ(one.status, 0) << one.err;
    EXPECT_EQ(one.out, "batch: shard 0/1: 7 done, 0 skipped (done before), 0 failed\n");
    for (int i = 0; i < 4; ++i) {
        const CliRun shard = runFrugal(dir, {"batch", "m.json", "--shard", std::to_string(i) + "/4", "--out", "four", "-q"});
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
    ASSERT_EQ(runFrugal(dir, {"batch", "merge", "one"}).status, 0);
    ASSERT_EQ(runFrugal(dir, {"batch", "merge", "four"}).status, 0);
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
                             "dominoes/color_0005.png", "job-6/color.png"})
        EXPECT_EQ(readAll(dir / "one" / file), readAll(dir / "four" / file)) << file;
    const nlohmann::json merged = test::readJson(dir / "one" / "merged.json");
    ASSERT_EQ(merged["jobs"].size(), 7u);
    EXPECT_EQ(merged["jobs"][3]["id"], "cull") << "manifest order";

    // Each shard's share of the jobs: every job once, whatever N.
    Result<batch::Manifest> manifest = batch::readManifest((dir / "m.json").string());
    ASSERT_TRUE(manifest) << manifest.error();
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
        ASSERT_EQ(m.error().rfind("manifest " + path, 0), 0u) << m.error();
        ASSERT_EQ(m.error().find('\n'), std::string::npos) << m.error();
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
    ASSERT_EQ(runFrugal(dir, {"batch", "m.json", "--out", "one", "-q"}).status, 0);
    // Kubernetes' index for shards 0 and 1, Slurm's (an array numbered from 1) for 2 and 3.
    for (const std::string env : {"JOB_COMPLETION_INDEX=0", "JOB_COMPLETION_INDEX=1",
                                  "SLURM_ARRAY_TASK_ID=3 SLURM_ARRAY_TASK_MIN=1", "SLURM_ARRAY_TASK_ID=4 SLURM_ARRAY_TASK_MIN=1"}) {
        const CliRun task = runFrugal(dir, {"batch", "m.json", "--shard", "array/4", "--out", "array", "-q"}, env);
        ASSERT_EQ(task.status, 0) << env << ": " << task.err;
    }
    ASSERT_EQ(runFrugal(dir, {"batch", "merge", "one"}).status, 0);
    ASSERT_EQ(runFrugal(dir, {"batch", "merge", "array"}).status, 0);
    EXPECT_EQ(readAll(dir / "one" / "merged.json"), readAll(dir / "array" / "merged.json"));

    CliRun bad = runFrugal(dir, {"batch", "m.json", "--shard", "array/4"}, "JOB_COMPLETION_INDEX=4");
    EXPECT_EQ(bad.status, 2);
    EXPECT_EQ(bad.err, "error: --shard array/4: JOB_COMPLETION_INDEX=4 is not a shard index (0 to 3)\n");
    bad = runFrugal(dir, {"batch", "m.json", "--shard", "array/4"}, "env -u SLURM_ARRAY_TASK_ID -u JOB_COMPLETION_INDEX");
    EXPECT_EQ(bad.status, 2);
    EXPECT_EQ(bad.err.rfind("error: --shard array/4: neither SLURM_ARRAY_TASK_ID", 0), 0u) << bad.err;

    // --slurm --dry-run: the two scripts and the sbatch lines, nothing written.
    const CliRun dry = runFrugal(dir, {"batch", "m.json", "--slurm", "3", "--dry-run", "--out", "slurm-out",
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
    bad = runFrugal(dir, {"batch", "m.json", "--slurm", "2", "--shard", "0/2"});
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
    ASSERT_EQ(runFrugal(dir, {"batch", "m.json", "--out", "out", "-q"}).status, 0);
    fs::remove(dir / "out" / "cubes" / "done.json");
    fs::remove(dir / "out" / "report" / "done.json");
    const CliRun plan = runFrugal(dir, {"batch", "m.json", "--plan", "2", "--out", "out"});
    ASSERT_EQ(plan.status, 0) << plan.err;
    EXPECT_EQ(plan.out.rfind("plan: out/plan.json, 2 shards of 7 jobs\n", 0), 0u) << plan.out;
    const nlohmann::json written = test::readJson(dir / "out" / "plan.json");
    ASSERT_EQ(written["costs"].size(), 7u);
    for (std::size_t i = 0; i < 7; ++i)
        EXPECT_EQ(written["costs"][i].get<double>() > 0, kIds[i] == "cubes" || kIds[i] == "report") << kIds[i];
    EXPECT_NE(written["shard_of"][0], written["shard_of"][5]) << "the two jobs left, one a shard";
    int ran = 0;
    for (int i = 0; i < 2; ++i) {
        const CliRun shard = runFrugal(dir, {"batch", "m.json", "--shard", std::to_string(i) + "/2", "--out", "out",
                                             "--resume"});
        ASSERT_EQ(shard.status, 0) << shard.err;
        EXPECT_NE(shard.err.find("jobs (split by out/plan.json)"), std::string::npos) << shard.err;
        ran += shard.out.find(": 1 done,") != std::string::npos;
    }
    EXPECT_EQ(ran, 2);
    // Another N, or another manifest: the plan is not theirs, and each shard splits by itself.
    const CliRun three = runFrugal(dir, {"batch", "m.json", "--shard", "0/3", "--out", "out", "--resume"});
    EXPECT_EQ(three.err.find("split by"), std::string::npos) << three.err;
}

TEST(BatchCliTest, ResumeRedoesOnlyWhatIsMissingOrChanged) {
    const fs::path dir = test::freshDir("BatchResume");
    writeManifest(dir);
    ASSERT_EQ(runFrugal(dir, {"batch", "m.json", "--out", "out", "-q"}).status, 0);
    CliRun again = runFrugal(dir, {"batch", "m.json", "--out", "out", "--resume", "-q"});
    ASSERT_EQ(again.status, 0) << again.err;
    EXPECT_EQ(again.out, "batch: shard 0/1: 0 done, 7 skipped (done before), 0 failed\n");

    // A job whose record is gone (killed before it finished), and one whose input file changed.
    fs::remove(dir / "out" / "cubes" / "done.json");
    test::writeFile(dir / "path.json", R"([{"eye":[0,0.6,3],"target":[0,0,0]}])");
    again = runFrugal(dir, {"batch", "m.json", "--out", "out", "--resume"});
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

}  // namespace
}  // namespace frugal
