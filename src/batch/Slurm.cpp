#include "batch/Slurm.h"

#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>

namespace frugal::batch {

namespace {

// A whole number in `text` (all of it), or -1.
long long wholeNumber(const char* text) {
    if (text == nullptr || *text == '\0') return -1;
    char* end = nullptr;
    errno = 0;
    const long long value = std::strtoll(text, &end, 10);
    return (errno != 0 || *end != '\0' || value < 0) ? -1 : value;
}

// Single-quoted for a shell: nothing is special inside but the quote itself.
std::string shellQuoted(const std::string& text) {
    std::string out = "'";
    for (const char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

}  // namespace

std::string shellWord(const std::string& word) {
    const bool plain = !word.empty() && word.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                                               "0123456789-_=.,:/@%+") == std::string::npos;
    return plain ? word : shellQuoted(word);
}

Result<int> arrayTaskIndex(int count) {
    const char* slurm = std::getenv("SLURM_ARRAY_TASK_ID");
    const char* kubernetes = std::getenv("JOB_COMPLETION_INDEX");
    const char* source = slurm != nullptr ? "SLURM_ARRAY_TASK_ID" : "JOB_COMPLETION_INDEX";
    const char* text = slurm != nullptr ? slurm : kubernetes;
    if (text == nullptr)
        return Error{"--shard array/" + std::to_string(count) +
                         ": neither SLURM_ARRAY_TASK_ID (a Slurm job array) nor JOB_COMPLETION_INDEX (a Kubernetes "
                         "Indexed Job) is set",
                     ErrorKind::BadInput};
    long long index = wholeNumber(text);
    if (index >= 0 && slurm != nullptr) {
        const long long first = wholeNumber(std::getenv("SLURM_ARRAY_TASK_MIN"));
        if (first > 0) index -= first;  // an array numbered from 1 (--array=1-N)
    }
    if (index < 0 || index >= count)
        return Error{"--shard array/" + std::to_string(count) + ": " + source + "=" + text +
                         " is not a shard index (0 to " + std::to_string(count - 1) + ")",
                     ErrorKind::BadInput};
    return int(index);
}

SlurmScripts slurmScripts(const std::string& frugal, const std::string& manifest, const std::string& out, int count) {
    const std::string n = std::to_string(count), logs = out + "/slurm";
    SlurmScripts s;
    s.shards = "#!/bin/sh\n"
               "# frugal batch: shard $SLURM_ARRAY_TASK_ID of " + n + ", written by 'frugal batch --slurm'.\n"
               "#SBATCH --job-name=frugal-batch\n"
               "#SBATCH --array=0-" + std::to_string(count - 1) + "\n"
               "#SBATCH --output=" + logs + "/shard-%a.log\n"
               "#SBATCH --open-mode=append\n"
               "# --resume: a task that is requeued or submitted again finishes only what is missing.\n"
               "exec " + shellQuoted(frugal) + " batch " + shellQuoted(manifest) + " --shard array/" + n +
               " --out " + shellQuoted(out) + " --resume\n";
    s.merge = "#!/bin/sh\n"
              "# frugal batch: joins the shards' outputs once the array has ended.\n"
              "#SBATCH --job-name=frugal-merge\n"
              "#SBATCH --output=" + logs + "/merge.log\n"
              "exec " + shellQuoted(frugal) + " batch merge " + shellQuoted(out) + "\n";
    return s;
}

Result<std::vector<std::string>> splitWords(const std::string& text) {
    std::vector<std::string> words;
    std::string word;
    bool inWord = false;
    char quote = 0;
    for (const char c : text) {
        if (quote != 0) {
            if (c == quote) quote = 0;
            else word += c;
        } else if (c == '\'' || c == '"') {
            quote = c;
            inWord = true;
        } else if (c == ' ' || c == '\t' || c == '\n') {
            if (inWord) words.push_back(word);
            word.clear();
            inWord = false;
        } else {
            word += c;
            inWord = true;
        }
    }
    if (quote != 0) return Error{"an unclosed " + std::string(1, quote) + " quote in '" + text + "'", ErrorKind::BadInput};
    if (inWord) words.push_back(word);
    return words;
}

Result<std::string> runProgram(const std::vector<std::string>& argv) {
    int pipeFds[2];
    if (pipe(pipeFds) != 0) return Error{argv[0] + ": cannot make a pipe (" + std::strerror(errno) + ")", ErrorKind::Io};
    std::vector<char*> pointers;
    std::vector<std::string> copy = argv;
    for (std::string& a : copy) pointers.push_back(a.data());
    pointers.push_back(nullptr);
    const pid_t pid = fork();
    if (pid < 0) return Error{argv[0] + ": cannot start it (" + std::strerror(errno) + ")", ErrorKind::Io};
    if (pid == 0) {
        dup2(pipeFds[1], 1);
        dup2(pipeFds[1], 2);
        close(pipeFds[0]);
        close(pipeFds[1]);
        execvp(pointers[0], pointers.data());
        _exit(errno == ENOENT ? 127 : 126);
    }
    close(pipeFds[1]);
    std::string output;
    char buffer[4096];
    for (ssize_t got; (got = read(pipeFds[0], buffer, sizeof buffer)) != 0;) {
        if (got < 0 && errno == EINTR) continue;
        if (got < 0) break;
        output.append(buffer, std::size_t(got));
    }
    close(pipeFds[0]);
    int raw = 0;
    while (waitpid(pid, &raw, 0) < 0 && errno == EINTR) {}
    const int status = WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + WTERMSIG(raw);
    if (status == 127) return Error{argv[0] + ": not found (is it on PATH?)", ErrorKind::BadInput};
    if (status != 0) {
        std::string first = output.substr(0, output.find('\n'));
        return Error{argv[0] + " exited " + std::to_string(status) + (first.empty() ? "" : ": " + first),
                     ErrorKind::BadInput};
    }
    return output;
}

}  // namespace frugal::batch
