// SPDX-License-Identifier: MIT
#include "io/checkpoint.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <csignal>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <stdexcept>

#include "core/error.h"

namespace sabo::io {

CheckpointOut::CheckpointOut(std::filesystem::path path) : path_(std::move(path)) {
    tmp_ = path_;
    tmp_ += ".tmp";
    file_ = std::fopen(tmp_.c_str(), "wb");
    if (file_ == nullptr) throw std::runtime_error(fmt::format("cannot write checkpoint {}", tmp_.string()));
    bytes(checkpoint_magic, sizeof checkpoint_magic);
}

CheckpointOut::~CheckpointOut() {
    if (file_ != nullptr) {  // not committed: leave the previous checkpoint as it was
        std::fclose(file_);
        std::error_code ignored;
        std::filesystem::remove(tmp_, ignored);
    }
}

void CheckpointOut::bytes(const void* data, std::size_t size) {
    if (size > 0 && std::fwrite(data, 1, size, file_) != size)
        throw std::runtime_error(fmt::format("writing checkpoint {} failed (disk full?)", tmp_.string()));
}

void CheckpointOut::put(const std::string& s) {
    put(static_cast<std::uint64_t>(s.size()));
    bytes(s.data(), s.size());
}

namespace {

// Fault injection for the kill tests (tests/scripts/check_resume.py): with SABO_TEST_KILL_AT_CHECKPOINT=N
// the process kills itself (SIGKILL, as a machine stop would) in the N-th checkpoint written, after its
// bytes and before the rename.
void kill_if_asked() {
    static int written = 0;
    static const char* at = std::getenv("SABO_TEST_KILL_AT_CHECKPOINT");
    if (at != nullptr && ++written == std::atoi(at)) std::raise(SIGKILL);
}

}  // namespace

void CheckpointOut::commit() {
    // on the disk before it replaces the previous one: a power cut after the rename finds it whole
    bool ok = std::fflush(file_) == 0 && ::fsync(::fileno(file_)) == 0;
    kill_if_asked();
    ok = std::fclose(file_) == 0 && ok;
    file_ = nullptr;
    if (!ok) throw std::runtime_error(fmt::format("writing checkpoint {} failed", tmp_.string()));
    std::filesystem::rename(tmp_, path_);
    const std::filesystem::path dir = path_.has_parent_path() ? path_.parent_path() : ".";
    if (const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY); fd >= 0) {  // the rename itself
        ::fsync(fd);
        ::close(fd);
    }
}

CheckpointIn::CheckpointIn(std::filesystem::path path) : path_(std::move(path)) {
    std::error_code ec;
    const auto size = std::filesystem::file_size(path_, ec);
    file_ = ec ? nullptr : std::fopen(path_.c_str(), "rb");
    if (file_ == nullptr) throw InputError(fmt::format("cannot read checkpoint {}", path_.string()));
    left_ = size;
    char magic[sizeof checkpoint_magic];
    if (left_ < sizeof magic) throw InputError(fmt::format("{}: not a sabo checkpoint", path_.string()));
    bytes(magic, sizeof magic);
    if (std::memcmp(magic, checkpoint_magic, sizeof magic) != 0)
        throw InputError(
            fmt::format("{}: not a sabo checkpoint of this version (written by another kind or version of "
                        "sabo?)",
                        path_.string()));
}

CheckpointIn::~CheckpointIn() {
    if (file_ != nullptr) std::fclose(file_);
}

void CheckpointIn::bytes(void* data, std::size_t size) {
    if (size > left_ || (size > 0 && std::fread(data, 1, size, file_) != size))
        throw InputError(fmt::format("{}: truncated checkpoint", path_.string()));
    left_ -= size;
}

std::uint64_t CheckpointIn::count() {
    std::uint64_t n = 0;
    get(n);
    if (n > left_)
        throw InputError(fmt::format("{}: corrupt checkpoint (a list longer than the file)", path_.string()));
    return n;
}

void CheckpointIn::get(std::string& s) {
    s.resize(count());
    bytes(s.data(), s.size());
}

void CheckpointIn::expect_end() {
    if (left_ != 0)
        throw InputError(
            fmt::format("{}: {} bytes more than this build's checkpoint holds (another version?)",
                        path_.string(), left_));
}

std::string case_identity(const Config& cfg) {
    std::istringstream in(cfg.resolved_toml());
    std::string line, identity;
    while (std::getline(in, line))
        if (!line.starts_with("end_time_s") && !line.starts_with("checkpoint_interval") &&
            !line.starts_with("progress_interval") && !line.starts_with("#"))
            identity += line + '\n';
    return identity;
}

void check_same_case(const std::filesystem::path& checkpoint, const std::string& stored,
                     const std::string& current) {
    if (stored == current) return;
    std::istringstream a(stored), b(current);
    std::string la, lb, table, found_a, found_b, found_table;
    while (std::getline(a, la) && std::getline(b, lb)) {
        if (la.starts_with("[")) table = la;
        if (la == lb || (!found_a.empty() && table == "[derived]")) continue;
        if (found_a.empty() || found_table == "[derived]") {
            found_a = la;
            found_b = lb;
            found_table = table;
            if (table != "[derived]") break;
        }
    }
    throw InputError(
        fmt::format("{} was written for another case: in {} it has '{}', this case '{}' (a resumed "
                    "run may change case.end_time_s and the checkpoint and progress intervals only)",
                    checkpoint.string(), found_table.empty() ? "the case" : found_table, found_a, found_b));
}

}  // namespace sabo::io
