#include "batch/Manifest.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <sstream>

#include <nlohmann/json.hpp>

#include <frugal/Files.h>
#include <frugal/Settings.h>

#include "base/Format.h"

namespace frugal::batch {

namespace fs = std::filesystem;
using Json = nlohmann::json;

const char* toString(Command command) {
    constexpr const char* names[] = {"render", "cull-report", "reuse-bench", "report"};
    return names[std::size_t(command)];
}

namespace {

constexpr int kMaxDepth = 32;  // a manifest is a few levels deep; deeper is refused before parsing

// The line of every value of a JSON text by its path ("jobs/2/scene"). The text has been parsed
// already, so it is valid JSON: the scan only steps over it.
class Lines {
public:
    explicit Lines(std::string_view text) : t_(text) { value(""); }
    int of(const std::string& path) const {
        const auto found = lines_.find(path);
        return found == lines_.end() ? 0 : found->second;
    }

private:
    bool more() const { return pos_ < t_.size(); }
    void space() {
        while (more() && std::strchr(" \t\r\n", t_[pos_]) != nullptr) {
            if (t_[pos_] == '\n') ++line_;
            ++pos_;
        }
    }
    std::string text() {  // at the opening quote; escapes kept as written (keys are compared plainly)
        std::string s;
        for (++pos_; more() && t_[pos_] != '"'; ++pos_) {
            if (t_[pos_] == '\\' && pos_ + 1 < t_.size()) s += t_[pos_++];
            s += t_[pos_];
        }
        ++pos_;
        return s;
    }
    void value(const std::string& path) {
        space();
        lines_[path] = line_;
        if (!more()) return;
        const char c = t_[pos_];
        if (c == '{' || c == '[') {
            const char close = c == '{' ? '}' : ']';
            ++pos_;
            for (int i = 0;; ++i) {
                space();
                if (!more() || t_[pos_] == close) break;
                std::string key = std::to_string(i);
                if (c == '{') {
                    key = text();
                    space();
                    ++pos_;  // ':'
                }
                value(path.empty() ? key : path + "/" + key);
                space();
                if (more() && t_[pos_] == ',') ++pos_;
            }
            ++pos_;
        } else if (c == '"') {
            text();
        } else {
            while (more() && std::strchr(",}] \t\r\n", t_[pos_]) == nullptr) ++pos_;
        }
    }
    std::string_view t_;
    std::size_t pos_ = 0;
    int line_ = 1;
    std::map<std::string, int> lines_;
};

// Nesting depth, strings skipped: checked before the parser and the scan recurse.
int depthOf(std::string_view text) {
    int depth = 0, deepest = 0;
    bool inString = false;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (inString) {
            if (c == '\\') ++i;
            else if (c == '"') inString = false;
        } else if (c == '"') {
            inString = true;
        } else if (c == '{' || c == '[') {
            deepest = std::max(deepest, ++depth);
        } else if (c == '}' || c == ']') {
            --depth;
        }
    }
    return deepest;
}

std::string kindOf(const Json& v) {
    if (v.is_string()) return "a string";
    if (v.is_boolean()) return "a boolean";
    if (v.is_number()) return "a number";
    if (v.is_array()) return "an array";
    if (v.is_object()) return "an object";
    return "null";
}

std::string quoted(const Json& v) { return oneLine(v.is_string() ? "'" + v.get<std::string>() + "'" : v.dump(), 80); }

bool validId(const std::string& id) {
    if (id.empty() || id.size() > 100 || id[0] == '.') return false;
    return std::all_of(id.begin(), id.end(), [](char c) {
        return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' || c == '_' ||
               c == '-';
    });
}

bool wholeIn(const Json& v, long long lo, long long hi) {
    return v.is_number_integer() && v.get<long long>() >= lo && v.get<long long>() <= hi;
}

// The jobs a job's keys may name by id: every job's id with its index and line, from a scan before
// the checks (so that a job named before it is read is known as a later one), and the jobs read.
struct JobIds {
    struct Entry {
        std::size_t index = 0;
        int line = 0;
    };
    std::map<std::string, Entry> ids;  // the first job of each id (a second is refused when read)
    const std::vector<Job>* read = nullptr;
};

// Checks one job: its keys (after the defaults) into a Job. `fail` gets the key and why.
class JobReader {
public:
    JobReader(const fs::path& base, const JobIds& jobs, std::size_t index, Job& job)
        : base_(base), jobs_(jobs), index_(index), job_(job) {}

    // "" when fine, else why (the caller adds where).
    std::string read(const std::string& key, const Json& v) {
        const auto handler = handlers().find(key);
        if (handler == handlers().end()) return "not a key of a job (" + keyNames() + ")";
        return (this->*(handler->second))(v);
    }
    // What only the whole job can tell (a key that does not fit the command, a missing scene).
    std::string finish(const std::map<std::string, Json>& keys) {
        const auto has = [&keys](const char* k) { return keys.count(k) != 0; };
        const Command c = job_.command;
        if (!has("scene")) return "scene: missing (every job renders a scene)";
        if (has("settings") && c != Command::Render) return "settings: only render jobs take settings";
        if (has("outputs") && c != Command::Render) return "outputs: only render jobs choose their outputs";
        if (has("views") && (c == Command::Render || c == Command::ReuseBench))
            return std::string("views: ") + toString(c) + " renders a camera or a camera path, not views";
        if (has("frames") && c == Command::CullReport) return "frames: cull-report measures views at one time";
        if (has("repeat") && c == Command::Render) return "repeat: render renders each frame once";
        if (has("views") && (has("camera") || has("camera_path")))
            return "views: give views, a camera or a camera path";
        if (has("camera") && has("camera_path")) return "camera_path: give a camera or a camera path";
        if (c == Command::Render && job_.outputs.empty()) job_.outputs = {"color", "json"};
        if (c == Command::ReuseBench && !has("frames")) return "frames: reuse-bench measures a sequence (A:B)";
        return "";
    }

private:
    using Handler = std::string (JobReader::*)(const Json&);
    static const std::map<std::string, Handler>& handlers() {
        static const std::map<std::string, Handler> table{
            {"id", &JobReader::id},           {"command", &JobReader::command}, {"scene", &JobReader::scene},
            {"size", &JobReader::size},       {"backend", &JobReader::backend}, {"camera", &JobReader::camera},
            {"camera_path", &JobReader::cameraPath}, {"views", &JobReader::views}, {"frames", &JobReader::frames},
            {"time", &JobReader::time},       {"fps", &JobReader::fps},         {"settings", &JobReader::settings},
            {"outputs", &JobReader::outputs}, {"repeat", &JobReader::repeat}};
        return table;
    }
    static std::string keyNames() {
        std::string names;
        for (const auto& [k, h] : handlers()) names += (names.empty() ? "" : ", ") + k;
        return names;
    }

    // A path relative to the manifest's folder, which must name a regular file.
    std::string file(const Json& v, std::string& out) {
        if (!v.is_string() || v.get<std::string>().empty()) return "expected a file name, got " + kindOf(v);
        const fs::path p = base_ / v.get<std::string>();
        std::error_code ec;
        if (!fs::is_regular_file(p, ec))
            return quoted(v) + ": no such file (" + oneLine(p.lexically_normal().string()) + ")";
        out = p.lexically_normal().string();
        job_.inputFiles.push_back(out);
        return "";
    }
    void flag(const std::string& name, const std::string& value) {
        job_.args.push_back(name);
        job_.args.push_back(value);
    }

    std::string id(const Json& v) {
        if (!v.is_string() || !validId(v.get<std::string>()))
            return quoted(v) + " is not an id (1 to 100 of A-Z a-z 0-9 . _ -, not starting with '.')";
        job_.id = v.get<std::string>();
        return "";
    }
    std::string command(const Json& v) {
        for (const Command c : {Command::Render, Command::CullReport, Command::ReuseBench, Command::Report})
            if (v.is_string() && v.get<std::string>() == toString(c)) {
                job_.command = c;
                return "";
            }
        return quoted(v) + " is not a command (render, cull-report, reuse-bench, report)";
    }
    std::string scene(const Json& v) {
        if (v.is_string() && v.get<std::string>().rfind("builtin:", 0) == 0) {
            job_.scene = v.get<std::string>();
        } else if (std::string why = file(v, job_.scene); !why.empty()) {
            return why;
        }
        job_.args.insert(job_.args.begin(), job_.scene);
        return "";
    }
    // A key that is a renderer setting (size, backend): read as a settings file reads it (the
    // library's schema, frugal/Settings.h), given to the command as its flag.
    std::string setting(const char* name, const Json& v) {
        const SettingInfo& info = *findSetting(name);
        Settings s;
        if (std::string why = setSettingJson(s, info, v.dump()); !why.empty()) return why;
        flag("--" + info.name, settingText(info, info.get(s)));
        if (info.name == "size") job_.pixels = std::int64_t(s.width) * s.height;
        return "";
    }
    std::string size(const Json& v) { return setting("size", v); }
    std::string backend(const Json& v) { return setting("backend", v); }
    std::string camera(const Json& v) {
        if (wholeIn(v, 0, 1 << 30)) {
            flag("--camera", std::to_string(v.get<long long>()));
            return "";
        }
        if (!v.is_object()) return "expected a scene camera's index or {\"eye\", \"target\", \"up\", \"fov\"}";
        for (const auto& [k, value] : v.items()) {
            if (k == "fov") {
                if (!value.is_number() || !(value.get<double>() > 0 && value.get<double>() < 180))
                    return "fov: " + quoted(value) + " is not an angle between 0 and 180 degrees";
                flag("--fov", fmt(value.get<double>()));
                continue;
            }
            if (k != "eye" && k != "target" && k != "up")
                return oneLine(k, 80) + ": not a key of a camera (eye, target, up, fov)";
            if (!value.is_array() || value.size() != 3 ||
                !std::all_of(value.begin(), value.end(),
                             [](const Json& n) { return n.is_number() && std::isfinite(n.get<double>()); }))
                return k + ": " + quoted(value) + " is not three finite numbers";
            flag("--" + k, fmt(value[0].get<double>()) + "," + fmt(value[1].get<double>()) + "," +
                               fmt(value[2].get<double>()));
        }
        return "";
    }
    std::string cameraPath(const Json& v) {
        std::string path;
        if (std::string why = file(v, path); !why.empty()) return why;
        flag("--camera-path", path);
        return "";
    }
    std::string views(const Json& v) {
        if (!wholeIn(v, 1, 10000)) return quoted(v) + " is not a whole number from 1 to 10000";
        job_.frames = v.get<long long>();
        flag("--views", std::to_string(job_.frames));
        return "";
    }
    std::string frames(const Json& v) {
        long long a = -1, b = -1;
        char colon = 0, extra = 0;
        if (v.is_string()) {
            std::istringstream in(v.get<std::string>());
            if (!(in >> a >> colon >> b) || colon != ':' || (in >> extra)) a = -1;
        }
        if (a < 0 || b < a || b > 100000000) return quoted(v) + " is not A:B (frames, 0 <= A <= B)";
        job_.frames = b - a + 1;
        flag("--frames", std::to_string(a) + ":" + std::to_string(b));
        return "";
    }
    std::string time(const Json& v) {
        if (!v.is_number() || !std::isfinite(v.get<double>())) return quoted(v) + " is not a finite number of seconds";
        flag("--time", fmt(v.get<double>()));
        return "";
    }
    std::string fps(const Json& v) {
        if (!v.is_number() || !(v.get<double>() > 0 && v.get<double>() <= 10000))
            return quoted(v) + " is not a frame rate (above 0, at most 10000)";
        flag("--fps", fmt(v.get<double>()));
        return "";
    }
    // "<id>/<name>" when <id> is a job's: the file that job writes, read from OUT when this job runs;
    // "" when it is one this job may read, else why not. Nothing when <id> is no job's (a path of
    // the manifest's folder, as is "./<id>/<name>").
    std::optional<std::string> produced(const Json& v, const std::string& flag, FileKind kind) {
        if (!v.is_string()) return std::nullopt;
        const std::string text = v.get<std::string>();
        const std::size_t slash = text.find('/');
        const auto producer = slash == std::string::npos ? jobs_.ids.end() : jobs_.ids.find(text.substr(0, slash));
        if (producer == jobs_.ids.end()) return std::nullopt;
        const auto [index, line] = producer->second;
        const std::string name = text.substr(slash + 1);
        if (index == index_) return quoted(v) + ": this job's own output (a job reads what an earlier job writes)";
        const std::string which = "job " + std::to_string(index) + " '" + producer->first + "'";
        if (index > index_)
            return quoted(v) + ": " + which + " at line " + std::to_string(line) +
                   " comes after this one (a job reads what an earlier job writes: put it first)";
        const Job& from = (*jobs_.read)[index];
        const std::vector<ProducedFile> files = producedFiles(from);
        const auto file =
            std::find_if(files.begin(), files.end(), [&name](const ProducedFile& f) { return f.name == name; });
        if (file == files.end()) {
            std::string names;
            for (const ProducedFile& f : files) names += (names.empty() ? "" : ", ") + f.name;
            return quoted(v) + ": " + which + " writes no " + oneLine(name, 80) + " a job may read (it writes " +
                   (names.empty() ? "only images" : names) +
                   (from.command == Command::Render && name == "settings.json"
                        ? "; a render writes settings.json when its settings are an object)"
                        : ")");
        }
        if (file->kind != kind)
            return quoted(v) + ": not a settings file (settings reads a settings.json an earlier job writes: a "
                               "report's, or a render's whose settings are an object)";
        job_.reads.push_back({flag, index, text});
        return "";
    }

    std::string settings(const Json& v) {
        if (v.is_object()) {
            Result<SettingsFile> parsed = parseSettingsJson(v.dump(), "settings");
            if (!parsed) return parsed.error().message.substr(parsed.error().message.find(": ") + 2);
            job_.settingsText = v.dump(2) + "\n";
            return "";
        }
        if (std::optional<std::string> why = produced(v, "--settings", FileKind::Settings)) return *why;
        std::string path;
        if (std::string why = file(v, path); !why.empty()) return why;
        if (Result<SettingsFile> parsed = readSettingsFile(path); !parsed) return parsed.error().message;
        flag("--settings", path);
        return "";
    }
    std::string outputs(const Json& v) {
        static const std::vector<std::string> kinds{"color", "depth", "ids", "linear", "json"};
        if (!v.is_array() || v.empty()) return "expected a list of color, depth, ids, linear, json";
        for (const Json& o : v) {
            if (!o.is_string() || std::find(kinds.begin(), kinds.end(), o.get<std::string>()) == kinds.end())
                return quoted(o) + " is not an output (color, depth, ids, linear, json)";
            if (std::find(job_.outputs.begin(), job_.outputs.end(), o.get<std::string>()) != job_.outputs.end())
                return quoted(o) + " is listed twice";
            job_.outputs.push_back(o.get<std::string>());
        }
        if (std::find(job_.outputs.begin(), job_.outputs.end(), "color") == job_.outputs.end())
            return "color: every render writes its colour image";
        return "";
    }
    std::string repeat(const Json& v) {
        if (!wholeIn(v, 1, 1000)) return quoted(v) + " is not a whole number from 1 to 1000";
        flag("--repeat", std::to_string(v.get<long long>()));
        return "";
    }

    fs::path base_;
    const JobIds& jobs_;
    std::size_t index_;
    Job& job_;
};

// The document's own keys: an object of frugal_batch (1), jobs (a list of one job or more) and
// optionally defaults (job keys, without an id) and a comment.
std::optional<Error> checkDocument(const Json& doc, const Lines& lines,
                                   const std::function<Error(int, const std::string&)>& problem) {
    if (!doc.is_object()) return problem(1, "expected an object with \"frugal_batch\": 1 and \"jobs\"");
    for (const auto& [key, value] : doc.items())
        if (key != "frugal_batch" && key != "defaults" && key != "jobs" && key != "comment")
            return problem(lines.of(key),
                           oneLine(key, 80) + ": not a key of a manifest (frugal_batch, defaults, jobs, comment)");
    if (!doc.contains("frugal_batch") || doc["frugal_batch"] != 1)
        return problem(lines.of("frugal_batch"), "frugal_batch: expected 1 (the version of this format)");
    const Json defaults = doc.value("defaults", Json::object());
    if (!defaults.is_object()) return problem(lines.of("defaults"), "defaults: expected an object of job keys");
    if (defaults.contains("id")) return problem(lines.of("defaults/id"), "defaults: id: every job has its own");
    if (!doc.contains("jobs") || !doc["jobs"].is_array() || doc["jobs"].empty())
        return problem(lines.of("jobs"), "jobs: expected a list of one job or more");
    return std::nullopt;
}

}  // namespace

Result<Manifest> parseManifest(std::string_view text, const std::string& path) {
    const auto problem = [&path](int line, const std::string& what) {
        return Error{"manifest " + path + (line > 0 ? " line " + std::to_string(line) : "") + ": " + what,
                     ErrorKind::BadInput};
    };
    if (depthOf(text) > kMaxDepth) return problem(0, "nested deeper than " + std::to_string(kMaxDepth) + " levels");
    Json doc = Json::parse(text, nullptr, false);
    if (doc.is_discarded()) return problem(0, "not JSON");
    const Lines lines(text);
    if (std::optional<Error> wrong = checkDocument(doc, lines, problem)) return *wrong;
    const Json defaults = doc.value("defaults", Json::object());

    const fs::path base = fs::path(path).parent_path();
    Manifest manifest;
    manifest.path = path;
    std::map<std::string, int> idLines;
    const std::size_t width = std::to_string(doc["jobs"].size() - 1).size();
    const auto defaultId = [width](std::size_t i) {
        const std::string number = std::to_string(i);
        return "job-" + std::string(width - number.size(), '0') + number;
    };
    JobIds ids;
    ids.read = &manifest.jobs;
    for (std::size_t i = 0; i < doc["jobs"].size(); ++i) {
        const Json& entry = doc["jobs"][i];
        if (!entry.is_object()) continue;
        const std::string id = !entry.contains("id") ? defaultId(i)
                               : entry["id"].is_string() ? entry["id"].get<std::string>()
                                                         : std::string();
        if (validId(id)) ids.ids.emplace(id, JobIds::Entry{i, lines.of("jobs/" + std::to_string(i))});
    }
    for (std::size_t i = 0; i < doc["jobs"].size(); ++i) {
        const Json& entry = doc["jobs"][i];
        const std::string at = "jobs/" + std::to_string(i);
        if (!entry.is_object()) return problem(lines.of(at), "job " + std::to_string(i) + ": expected an object");
        // Its keys over the defaults', each with the line it came from.
        std::map<std::string, Json> keys;
        std::map<std::string, int> keyLines;
        for (const auto& [k, v] : defaults.items()) {
            keys[k] = v;
            keyLines[k] = lines.of("defaults/" + k);
        }
        for (const auto& [k, v] : entry.items()) {
            keys[k] = v;
            keyLines[k] = lines.of(at + "/" + k);
        }
        Job job;
        job.line = lines.of(at);
        job.id = defaultId(i);
        JobReader reader(base, ids, i, job);
        // The command first: what a key means can depend on it.
        std::vector<std::string> order{"command", "scene"};
        for (const auto& [k, v] : keys)
            if (k != "command" && k != "scene") order.push_back(k);
        for (const std::string& k : order) {
            if (!keys.count(k)) continue;
            if (std::string why = reader.read(k, keys[k]); !why.empty())
                return problem(keyLines[k], "job " + std::to_string(i) + ": " + oneLine(k, 80) + ": " + why);
        }
        if (std::string why = reader.finish(keys); !why.empty())
            return problem(job.line, "job " + std::to_string(i) + " '" + job.id + "': " + why);
        if (const auto seen = idLines.find(job.id); seen != idLines.end())
            return problem(keyLines.count("id") ? keyLines["id"] : job.line,
                           "job " + std::to_string(i) + ": id '" + job.id + "' is also the id of the job at line " +
                               std::to_string(seen->second) + " (each job writes into a folder of its id)");
        idLines[job.id] = job.line;
        Json canonical(keys);
        canonical["id"] = job.id;
        job.canonical = canonical.dump();
        manifest.jobs.push_back(std::move(job));
    }
    return manifest;
}

Result<Manifest> readManifest(const std::string& path) {
    std::error_code ec;
    const std::optional<std::string> text = fs::is_directory(path, ec) ? std::nullopt : readFile(path);
    if (!text) return Error{"manifest " + path + ": cannot read the file", ErrorKind::Io};
    return parseManifest(*text, path);
}

std::vector<ProducedFile> producedFiles(const Job& job) {
    switch (job.command) {
    case Command::Render: {
        std::vector<ProducedFile> files;
        if (std::find(job.outputs.begin(), job.outputs.end(), "json") != job.outputs.end())
            files.push_back({"render.json", FileKind::Record});
        if (!job.settingsText.empty()) files.push_back({"settings.json", FileKind::Settings});
        return files;
    }
    case Command::CullReport: return {{"cull-report.json", FileKind::Record}, {"cull-report.csv", FileKind::Record}};
    case Command::ReuseBench: return {{"reuse-bench.json", FileKind::Record}, {"reuse-bench.csv", FileKind::Record}};
    case Command::Report:
        return {{"settings.json", FileKind::Settings}, {"report.json", FileKind::Record},
                {"report.csv", FileKind::Record},      {"papers.csv", FileKind::Record},
                {"index.html", FileKind::Record},      {"pareto.gp", FileKind::Record}};
    }
    return {};
}

std::vector<std::string> commandLine(const Job& job, const std::string& out) {
    std::vector<std::string> line{toString(job.command)};
    line.insert(line.end(), job.args.begin(), job.args.end());
    for (const ProducedInput& input : job.reads)
        line.insert(line.end(), {input.flag, (fs::path(out) / input.path).string()});
    const std::string jobDir = (fs::path(out) / job.id).string();
    const std::string dir = jobDir + "/";
    switch (job.command) {
    case Command::Render:
        if (!job.settingsText.empty()) line.insert(line.end(), {"--settings", dir + "settings.json"});
        for (const std::string& o : job.outputs) {
            if (o == "color") line.insert(line.end(), {"-o", dir + "color.png"});
            if (o == "depth") line.insert(line.end(), {"--depth", dir + "depth.png"});
            if (o == "ids") line.insert(line.end(), {"--ids", dir + "ids.png"});
            if (o == "linear") line.insert(line.end(), {"--linear", dir + "linear.pfm"});
            if (o == "json") line.insert(line.end(), {"--json", dir + "render.json"});
        }
        break;
    case Command::CullReport:
        line.insert(line.end(), {"--json", dir + "cull-report.json", "--csv", dir + "cull-report.csv"});
        break;
    case Command::ReuseBench:
        line.insert(line.end(), {"--json", dir + "reuse-bench.json", "--csv", dir + "reuse-bench.csv"});
        break;
    case Command::Report: line.insert(line.end(), {"-o", jobDir}); break;
    }
    line.push_back("-q");
    return line;
}

}  // namespace frugal::batch
