// SPDX-License-Identifier: MIT
// `sabo sweep SWEEP.toml`: a grid of cases, one `sabo run` process per case, resumable (a case whose
// summary.json says "completed" is skipped, one with a checkpoint goes on from it), then
// python/sweep_report.py for the table and the design charts (docs/sweeps.md).
#include "app/sweep.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <spawn.h>
#include <spdlog/spdlog.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <toml++/toml.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/json_writer.h"
#include "io/report_script.h"
#include "sim/run_control.h"

namespace sabo::app {

namespace {

volatile std::sig_atomic_t g_sweep_signal = 0;
extern "C" void on_sweep_signal(int sig) {
    g_sweep_signal = sig;
}

[[noreturn]] void fail(const std::filesystem::path& file, std::string_view key, std::string_view msg) {
    throw InputError(fmt::format("{}: {}: {}", file.string(), key, msg));
}

// A TOML value as it would be written after --set key= (empty for tables and arrays: refused)
std::string value_text(const toml::node& n) {
    if (const auto* s = n.as_string()) return std::string(s->get());
    if (const auto* v = n.as_floating_point()) return fmt::format("{}", v->get());
    if (const auto* i = n.as_integer()) return fmt::format("{}", i->get());
    if (const auto* b = n.as_boolean()) return b->get() ? "true" : "false";
    return {};
}

std::vector<std::string> string_list(const toml::table& t, std::string_view key,
                                     const std::filesystem::path& file) {
    std::vector<std::string> out;
    const auto* node = t.get(key);
    if (node == nullptr) return out;
    const auto* arr = node->as_array();
    if (arr == nullptr) fail(file, key, "must be an array of \"key.path=value\" strings");
    for (const auto& e : *arr) {
        const auto* s = e.as_string();
        if (s == nullptr || s->get().find('=') == std::string::npos)
            fail(file, key, "must be an array of \"key.path=value\" strings");
        out.emplace_back(s->get());
    }
    return out;
}

std::string grid_case_id(const std::vector<std::pair<std::string, std::string>>& values) {
    std::string id;
    for (const auto& [key, value] : values) {
        const auto dot = key.rfind('.');
        std::string part = (dot == std::string::npos ? key : key.substr(dot + 1)) + "=" + value;
        for (char& c : part) {
            if (!std::isalnum(static_cast<unsigned char>(c)) && c != '=' && c != '.' && c != '-') c = '_';
        }
        id += (id.empty() ? "" : "__") + part;
    }
    return id.empty() ? "base" : id;
}

// Cartesian product of the chosen grid keys, with `fixed` overrides and the common ones in front.
void add_product(SweepPlan& plan, const std::vector<std::pair<std::string, std::vector<std::string>>>& axes,
                 const std::vector<std::string>& common, const std::vector<std::string>& fixed) {
    std::vector<std::size_t> index(axes.size(), 0);
    while (true) {
        SweepCase c;
        c.overrides = common;
        c.overrides.insert(c.overrides.end(), fixed.begin(), fixed.end());
        for (const auto& f : fixed)
            c.values.emplace_back(f.substr(0, f.find('=')), f.substr(f.find('=') + 1));
        for (std::size_t a = 0; a < axes.size(); ++a) {
            c.values.emplace_back(axes[a].first, axes[a].second[index[a]]);
            c.overrides.push_back(axes[a].first + "=" + axes[a].second[index[a]]);
        }
        c.id = grid_case_id(c.values);
        plan.cases.push_back(std::move(c));
        std::size_t a = axes.size();
        while (a > 0 && ++index[a - 1] == axes[a - 1].second.size()) index[--a] = 0;
        if (a == 0) break;
    }
}

SweepPlan read_plan(const SweepRequest& req) {
    const auto& file = req.sweep_file;
    toml::table root;
    try {
        root = toml::parse_file(file.string());
    } catch (const toml::parse_error& e) {
        throw InputError(fmt::format("{}: TOML error: {}", file.string(), e.description()));
    }
    for (const auto& [k, v] : root) {
        if (k != "sweep" && k != "grid" && k != "also")
            fail(file, k.str(), "unknown table (allowed: [sweep], [grid], [[also]])");
    }
    const auto* sweep = root["sweep"].as_table();
    if (sweep == nullptr) fail(file, "sweep", "missing table [sweep]");
    for (const auto& [k, v] : *sweep) {
        const std::string key(k.str());
        if (key != "case" && key != "name" && key != "threads" && key != "jobs" && key != "set")
            fail(file, "sweep." + key, "unknown key (allowed: case, name, threads, jobs, set)");
    }
    SweepPlan plan;
    const auto case_rel = (*sweep)["case"].value<std::string>();
    if (!case_rel)
        fail(file, "sweep.case", "missing: the case file the grid varies (path relative to the sweep file)");
    plan.case_file = file.parent_path() / *case_rel;
    if (!std::filesystem::exists(plan.case_file)) {
        // a relative path is read from the sweep file's folder (the sweep runs from any working directory)
        const std::string from_here =
            std::filesystem::path(*case_rel).is_relative() && std::filesystem::exists(*case_rel)
                ? fmt::format(
                      " ({} exists from the working directory: write the path "
                      "from the sweep file's folder, or an absolute one)",
                      *case_rel)
                : "";
        fail(file, "sweep.case",
             fmt::format("'{}': {} does not exist (a relative path is read from the sweep file's folder){}",
                         *case_rel, plan.case_file.string(), from_here));
    }
    const std::string name = (*sweep)["name"].value_or<std::string>(file.stem().string());
    plan.name = name;
    plan.out_dir = req.out_dir ? *req.out_dir : std::filesystem::path("out/sweeps") / name;
    plan.threads = static_cast<int>((*sweep)["threads"].value_or<std::int64_t>(1));
    plan.jobs = static_cast<int>((*sweep)["jobs"].value_or<std::int64_t>(1));
    if (req.jobs > 0) plan.jobs = req.jobs;
    if (plan.threads < 1 || plan.threads > 1024) fail(file, "sweep.threads", "allowed range [1, 1024]");
    if (plan.jobs < 1 || plan.jobs > 256) fail(file, "sweep.jobs", "allowed range [1, 256]");
    if (!req.shard.empty()) {
        int i = -1, n = 0;
        char rest = 0;
        if (std::sscanf(req.shard.c_str(), "%d/%d%c", &i, &n, &rest) != 2 || n < 1 || n > 100000 || i < 0 ||
            i >= n)
            throw InputError(fmt::format(
                "--shard {}: expected i/N with N in [1, 100000] and i in [0, N-1] (the shard's index, "
                "counted from 0, and the number of shards)",
                req.shard));
        plan.shard = i;
        plan.shards = n;
    }
    const auto common = string_list(*sweep, "set", file);

    std::vector<std::pair<std::string, std::vector<std::string>>> axes;
    if (const auto* grid = root["grid"].as_table()) {
        for (const auto& [k, v] : *grid) {
            const auto* arr = v.as_array();
            if (arr == nullptr || arr->empty())
                fail(file, fmt::format("grid.\"{}\"", k.str()), "must be a non-empty array of values");
            std::vector<std::string> values;
            for (const auto& e : *arr) {
                values.push_back(value_text(e));
                if (values.back().empty())
                    fail(file, fmt::format("grid.\"{}\"", k.str()),
                         "values must be numbers, strings or booleans");
            }
            axes.emplace_back(std::string(k.str()), values);
            plan.grid_keys.emplace_back(k.str());
        }
    }
    add_product(plan, axes, common, {});
    if (const auto* also = root["also"].as_array()) {
        for (std::size_t a = 0; a < also->size(); ++a) {
            const auto* t = (*also)[a].as_table();
            const std::string where = fmt::format("also[{}]", a);
            if (t == nullptr) fail(file, where, "must be a table with set = [...] and vary = [grid keys]");
            const auto fixed = string_list(*t, "set", file);
            std::vector<std::pair<std::string, std::vector<std::string>>> sub;
            if (const auto* vary = t->get_as<toml::array>("vary")) {
                for (const auto& e : *vary) {
                    const auto* s = e.as_string();
                    auto it = std::find_if(axes.begin(), axes.end(),
                                           [&](const auto& ax) { return s && ax.first == s->get(); });
                    if (it == axes.end()) fail(file, where + ".vary", "must list keys of [grid]");
                    sub.push_back(*it);
                }
            }
            for (const auto& f : fixed) {
                const std::string key = f.substr(0, f.find('='));
                if (std::find(plan.grid_keys.begin(), plan.grid_keys.end(), key) == plan.grid_keys.end())
                    plan.grid_keys.push_back(key);
            }
            add_product(plan, sub, common, fixed);
        }
    }
    std::map<std::string, int> seen;
    for (const auto& c : plan.cases) {
        if (++seen[c.id] > 1) fail(file, "grid", fmt::format("case '{}' appears twice", c.id));
    }
    return plan;
}

bool completed(const std::filesystem::path& dir) {
    std::ifstream in(dir / "summary.json");
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str().find("\"status\": \"completed\"") != std::string::npos;
}

// A case's state as the last process to touch it recorded it (sweep_status.txt: running, completed,
// failed (exit N), interrupted), or, for a folder without one, completed or pending.
std::string recorded_status(const std::filesystem::path& dir) {
    std::ifstream in(dir / "sweep_status.txt");
    std::string line;
    if (std::getline(in, line) && !line.empty()) return line;
    return completed(dir) ? "completed" : "pending";
}

void record_status(const std::filesystem::path& dir, const std::string& status) {
    io::write_text_atomically(dir / "sweep_status.txt", status + "\n");
}

bool ended(const std::string& status) {
    return status == "completed" || status.starts_with("failed");
}

// An exclusive lock on the sweep folder (flock on sweep.lock) while a process writes the index or the
// report: shards on several machines sharing the folder take turns.
class FolderLock {
  public:
    explicit FolderLock(const std::filesystem::path& dir)
        : fd_(::open((dir / "sweep.lock").c_str(), O_CREAT | O_RDWR | O_CLOEXEC, 0644)) {
        if (fd_ < 0 || ::flock(fd_, LOCK_EX) != 0)
            throw RunError(
                fmt::format("cannot lock {}: {}", (dir / "sweep.lock").string(), std::strerror(errno)));
    }
    ~FolderLock() { ::close(fd_); }
    FolderLock(const FolderLock&) = delete;
    FolderLock& operator=(const FolderLock&) = delete;

  private:
    int fd_;
};

pid_t launch(const SweepPlan& plan, const SweepCase& c, const std::filesystem::path& dir) {
    std::filesystem::create_directories(dir);
    std::vector<std::string> args{"sabo",       "run",       plan.case_file.string(),     "--out",
                                  dir.string(), "--threads", std::to_string(plan.threads)};
    for (const auto& o : c.overrides) args.insert(args.end(), {"--set", o});
    args.insert(args.end(), {"--set", "output.report=false"});  // one report for the sweep
    // a case the sweep's last attempt interrupted goes on from its checkpoint; any other case's folder is
    // the sweep's own (a failed attempt's outputs are replaced)
    args.emplace_back(std::filesystem::exists(dir / "checkpoint.bin") ? "--resume" : "--overwrite");
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    // a case is one process of its own, not a rank of the sweep's MPI job
    std::vector<std::string> env = MpiWorld::environment_for_children();
    std::vector<char*> envp;
    for (auto& e : env) envp.push_back(e.data());
    envp.push_back(nullptr);
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    const std::string console = (dir / "console.log").string();
    posix_spawn_file_actions_addopen(&fa, 1, console.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&fa, 1, 2);
    // Each case in a process group of its own: a stop signal reaches it once, through the sweep (a
    // terminal's Ctrl-C reaches only the sweep; mpirun and schedulers signal the ranks).
    posix_spawnattr_t attr;
    posix_spawnattr_init(&attr);
    posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETPGROUP);
    posix_spawnattr_setpgroup(&attr, 0);
    pid_t pid = 0;
    const int rc = posix_spawn(&pid, "/proc/self/exe", &fa, &attr, argv.data(), envp.data());
    posix_spawnattr_destroy(&attr);
    posix_spawn_file_actions_destroy(&fa);
    if (rc != 0) throw RunError(fmt::format("cannot start a case process: {}", std::strerror(rc)));
    return pid;
}

// The index of every case of the plan: this process's own from `status`, the others' from their folders.
// The caller holds the folder's lock.
void write_index_locked(const SweepPlan& plan, const std::map<std::string, std::string>& status) {
    std::string csv = "case,dir,status";
    for (const auto& k : plan.grid_keys) csv += "," + k;
    csv += "\n";
    for (const auto& c : plan.cases) {
        const auto own = status.find(c.id);
        csv += c.id + "," + c.id + "," +
               (own != status.end() ? own->second : recorded_status(plan.out_dir / c.id));
        for (const auto& k : plan.grid_keys) {
            std::string v;
            for (const auto& [key, value] : c.values) {
                if (key == k) v = value;
            }
            csv += "," + v;
        }
        csv += "\n";
    }
    io::write_text_atomically(plan.out_dir / "sweep_cases.csv", csv);
}

void write_index(const SweepPlan& plan, const std::map<std::string, std::string>& status) {
    const FolderLock lock(plan.out_dir);
    write_index_locked(plan, status);
}

}  // namespace

int run_sweep(const SweepRequest& req, const MpiWorld& world) {
    SweepPlan plan = read_plan(req);
    if (world.size() > 1 && plan.shards > 1)
        throw InputError(
            fmt::format("--shard {}: under mpirun the {} ranks share the cases already; use one or the other",
                        req.shard, world.size()));
    return execute_sweep(plan, "sweep_report.py", &world);
}

void add_grid(SweepPlan& plan, const std::vector<std::pair<std::string, std::vector<std::string>>>& axes,
              const std::vector<std::string>& common) {
    for (const auto& ax : axes) plan.grid_keys.push_back(ax.first);
    add_product(plan, axes, common, {});
}

int execute_sweep(const SweepPlan& plan, const std::string& report_script, const MpiWorld* world) {
    // MPI ranks take the cases as they free up (the folder's lock hands each pending case to one rank);
    // shards, which may run at different times, take theirs by index: k mod N = i.
    const bool ranks = world != nullptr && world->size() > 1;
    std::vector<const SweepCase*> mine;
    for (std::size_t k = 0; k < plan.cases.size(); ++k)
        if (ranks || static_cast<int>(k % plan.shards) == plan.shard) mine.push_back(&plan.cases[k]);
    std::filesystem::create_directories(plan.out_dir);
    if (!ranks || world->rank() == 0) {  // what the report names the sweep by
        io::JsonObject about;
        about.text("name", plan.name)
            .text("case_file", std::filesystem::absolute(plan.case_file).lexically_normal().string());
        io::write_text_atomically(plan.out_dir / "sweep.json", about.dump() + "\n");
    }
    // (a rank's messages carry its number already: init_logging)
    const std::string who = plan.shards > 1 ? fmt::format("shard {}/{}: ", plan.shard, plan.shards) : "";
    if (ranks) {
        spdlog::info(
            "sweep: {} cases of {} shared by {} ranks as they free up ({} at a time, {} threads each) in {}",
            plan.cases.size(), plan.case_file.string(), world->size(), plan.jobs, plan.threads,
            plan.out_dir.string());
    } else {
        spdlog::info("{}sweep: {} of {} cases of {} ({} at a time, {} threads each) in {}", who, mine.size(),
                     plan.cases.size(), plan.case_file.string(), plan.jobs, plan.threads,
                     plan.out_dir.string());
    }
    // OpenMP threads spin at barriers: more threads than cores in total slows every case many times
    const auto cores = static_cast<int>(std::max(1L, sysconf(_SC_NPROCESSORS_ONLN)));
    const int on_this_machine = ranks ? world->local_size() : 1;
    if (plan.jobs * plan.threads * on_this_machine > cores) {
        spdlog::warn(
            "{}{} jobs x {} threads{} exceed the {} cores: cases get OMP_WAIT_POLICY=passive (still slower "
            "than jobs x threads <= cores)",
            who, plan.jobs, plan.threads,
            on_this_machine > 1 ? fmt::format(" x {} ranks", on_this_machine) : "", cores);
        setenv("OMP_WAIT_POLICY", "passive", 1);
    }
    if (ranks) {
        // this invocation's work: every case not completed is pending (failed, interrupted or left
        // "running" by a sweep that was killed), before any rank takes one
        if (world->rank() == 0) {
            const FolderLock lock(plan.out_dir);
            for (const auto& c : plan.cases) {
                const auto dir = plan.out_dir / c.id;
                std::filesystem::create_directories(dir);
                const bool finished = completed(dir);
                record_status(dir, finished ? "completed" : "pending");
                if (finished) spdlog::info("{}: already completed, skipped", c.id);
            }
        }
        world->barrier();
    }
    std::map<std::string, std::string> status;  // this process's cases
    std::map<pid_t, const SweepCase*> running;
    g_sweep_signal = 0;
    struct sigaction on_stop {};
    on_stop.sa_handler = on_sweep_signal;  // no SA_RESTART: a signal ends the wait for the cases
    sigemptyset(&on_stop.sa_mask);
    sigaction(SIGINT, &on_stop, nullptr);
    sigaction(SIGTERM, &on_stop, nullptr);
    bool passed_on = false;
    std::size_t next = 0, done = 0;
    std::int64_t failed = 0;
    // The next case this process runs (nullptr: none left for it).
    auto claim = [&]() -> const SweepCase* {
        if (ranks) {
            const FolderLock lock(plan.out_dir);
            for (const auto& c : plan.cases) {
                if (recorded_status(plan.out_dir / c.id) != "pending") continue;
                record_status(plan.out_dir / c.id, "running");
                return &c;
            }
            return nullptr;
        }
        while (next < mine.size()) {
            const SweepCase& c = *mine[next++];
            if (!completed(plan.out_dir / c.id)) return &c;
            status[c.id] = "completed";
            record_status(plan.out_dir / c.id, status[c.id]);
            ++done;
            spdlog::info("{}[{}/{}] {}: already completed, skipped", who, done, mine.size(), c.id);
        }
        return nullptr;
    };
    // "[done/of mine]"; a rank knows only its own count
    auto progress = [&] {
        return ranks ? fmt::format("[{} here]", done) : fmt::format("[{}/{}]", done, mine.size());
    };
    // the whole sweep's progress: the cases this invocation ran so far set the rate of the rest
    const auto started = std::chrono::steady_clock::now();
    std::size_t ran_here = 0;
    auto whole_sweep_eta = [&]() -> std::string {
        if (ranks || ran_here == 0 || done >= mine.size()) return "";
        const double elapsed =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
        const double left = static_cast<double>(mine.size() - done) * elapsed / static_cast<double>(ran_here);
        return fmt::format(" — sweep {:.0f} % after {}, about {} left",
                           100.0 * static_cast<double>(done) / static_cast<double>(mine.size()),
                           sim::format_duration(elapsed), sim::format_duration(left));
    };
    auto reap = [&](bool block) {
        int st = 0;
        const pid_t pid = waitpid(-1, &st, block ? 0 : WNOHANG);
        if (pid <= 0) return false;
        const SweepCase* c = running.at(pid);
        running.erase(pid);
        const int code = WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
        status[c->id] =
            code == 0 ? "completed" : (code == 130 ? "interrupted" : fmt::format("failed (exit {})", code));
        record_status(plan.out_dir / c->id, status[c->id]);
        ++done;
        ++ran_here;
        if (code != 0) ++failed;
        spdlog::info("{}{} {}: {}{}", who, progress(), c->id, status[c->id], whole_sweep_eta());
        write_index(plan, status);
        return true;
    };
    if (!ranks)
        for (const SweepCase* c : mine) status[c->id] = "pending";
    bool exhausted = false;
    while (true) {
        while (!exhausted && static_cast<int>(running.size()) < plan.jobs && g_sweep_signal == 0) {
            const SweepCase* c = claim();
            if (c == nullptr) {
                exhausted = true;
                break;
            }
            const auto dir = plan.out_dir / c->id;
            status[c->id] = "running";
            running[launch(plan, *c, dir)] = c;
            record_status(dir, status[c->id]);
        }
        write_index(plan, status);
        if (running.empty()) break;
        do {
            if (g_sweep_signal != 0 && !passed_on) {  // the running cases checkpoint and stop
                for (const auto& [pid, c] : running) ::kill(pid, g_sweep_signal);
                passed_on = true;
            }
        } while (!reap(true));
        if (g_sweep_signal != 0 && running.empty()) break;
    }
    // Every rank gets here, interrupted or not: the ranks wait for each other, then rank 0 reports.
    const bool interrupted = ranks ? world->max(g_sweep_signal != 0 ? 1 : 0) != 0 : g_sweep_signal != 0;
    if (ranks) failed = world->sum(failed);
    if (interrupted) {
        spdlog::warn("{}sweep interrupted: {} case(s) done{}; run the same command again to resume", who,
                     done, ranks ? " here" : fmt::format(" of {}", mine.size()));
        return 130;
    }
    if (ranks && world->rank() != 0) return failed > 0 ? 3 : 0;
    const FolderLock lock(plan.out_dir);
    std::size_t open = 0;
    for (const auto& c : plan.cases)
        if (!ended(recorded_status(plan.out_dir / c.id))) ++open;
    write_index_locked(plan, {});
    if (open > 0) {
        spdlog::info(
            "{}done; {} case(s) of other shards not ended yet: the shard that ends last writes the report",
            who, open);
        return failed > 0 ? 3 : 0;
    }
    const int rc = io::run_python(report_script, {plan.out_dir.string()});
    if (rc == 0) {
        spdlog::info("sweep report written in {}", plan.out_dir.string());
    } else {
        spdlog::warn("python/{} failed (exit {}): no sweep table/charts (needs python3-matplotlib)",
                     report_script, rc);
    }
    return failed > 0 ? 3 : 0;
}

}  // namespace sabo::app
