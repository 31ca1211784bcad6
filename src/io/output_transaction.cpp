#include <scantling/core/error.hpp>
#include <scantling/io/atomic_file.hpp>
#include <scantling/io/file_path.hpp>
#include <scantling/io/output_transaction.hpp>

#include <filesystem>
#include <system_error>

namespace scantling::io {
namespace {

namespace fs = std::filesystem;

constexpr int kCreateAttempts = 16;  // names taken by leftovers of killed processes

bool exists_no_follow(const std::string& path) {
    std::error_code ec;
    return fs::exists(fs::symlink_status(path, ec));
}

void remove_quietly(const std::string& path) {
    std::error_code ignored;
    if (!path.empty()) fs::remove_all(path, ignored);
}

void check_folder_destination(const std::string& folder, const std::string& name,
                              const OutputTransaction::ReplaceCheck& replace_check) {
    std::error_code ec;
    const fs::file_status status = fs::symlink_status(folder, ec);
    if (!fs::exists(status)) return;
    if (!fs::is_directory(status)) throw FileError(name, "exists and is not a folder");
    if (fs::is_empty(folder, ec) && !ec) return;
    if (!replace_check) throw FileError(name, "the folder exists and is not empty");
    replace_check(folder);
}

std::string make_temporary_folder(const fs::path& folder, const std::string& name) {
    std::error_code ec;
    fs::create_directories(folder.parent_path(), ec);
    if (ec) throw FileError(name, "cannot create its parent folder: " + ec.message());
    for (int attempt = 0; attempt < kCreateAttempts; ++attempt) {
        const std::string temporary = temporary_sibling(folder.string(), "partial");
        if (fs::create_directory(temporary, ec)) return temporary;
        if (ec) {
            throw FileError(
                name, "cannot create the temporary folder " + temporary + ": " + ec.message());
        }
    }
    throw FileError(name, "cannot create a temporary folder beside it: every name is taken");
}

void rename_or_throw(const std::string& from, const std::string& to, const std::string& name) {
    std::error_code ec;
    fs::rename(from, to, ec);
    if (ec) throw FileError(name, "cannot rename " + from + " to " + to + ": " + ec.message());
}

/// A hard link keeps the old file in place until the rename replaces it atomically.
bool link_backup(const std::string& destination, const std::string& backup) {
    std::error_code ec;
    fs::create_hard_link(destination, backup, ec);
    return !ec;
}

}  // namespace

OutputTransaction::~OutputTransaction() {
    if (finished_) return;
    for (const Output& output : outputs_) remove_quietly(output.temporary);
    remove_created_folders();
}

void OutputTransaction::create_folder(const std::string& path) {
    std::vector<std::string> missing;
    std::error_code ec;
    for (fs::path p = resolved_path(path); !p.empty() && !fs::exists(p, ec); p = p.parent_path()) {
        missing.insert(missing.begin(), p.string());
        if (p == p.root_path()) break;
    }
    fs::create_directories(path, ec);
    if (ec) throw FileError(path, "cannot create the folder: " + ec.message());
    created_folders_.insert(created_folders_.end(), missing.begin(), missing.end());
}

void OutputTransaction::remove_created_folders() {
    for (auto it = created_folders_.rbegin(); it != created_folders_.rend(); ++it) {
        std::error_code ignored;
        fs::remove(*it, ignored);  // fails, as intended, on a folder that is not empty
    }
    created_folders_.clear();
}

void OutputTransaction::check_not_staged(const std::string& destination) const {
    const fs::path canonical = resolved_path(destination);
    for (const Output& output : outputs_) {
        if (resolved_path(output.destination) == canonical) {
            throw FileError(destination,
                            "is already an output of this command (" + output.destination + ")");
        }
    }
}

std::string OutputTransaction::stage_file(const std::string& path) {
    if (finished_) throw FileError(path, "staged after the outputs were committed");
    check_output_file(path);
    check_not_staged(path);
    outputs_.push_back({.destination = path,
                        .temporary = temporary_sibling(path, "partial", /*keep_extension=*/true),
                        .is_folder = false,
                        .replace_check = {},
                        .backup = {},
                        .placed = false});
    return outputs_.back().temporary;
}

void OutputTransaction::write(const std::string& path,
                              const std::function<void(const std::string&)>& write) {
    const std::string staged = stage_file(path);
    try {
        write(staged);
    } catch (const FileError& e) {
        const std::string what = e.what();
        if (e.path() != staged || what.rfind(staged + ": ", 0) != 0) throw;
        throw FileError(path, what.substr(staged.size() + 2));
    }
}

void OutputTransaction::write_stream(const std::string& path,
                                     const std::function<void(std::ostream&)>& write_bytes) {
    write(path, [&](const std::string& staged) { write_file_atomically(staged, write_bytes); });
}

std::string OutputTransaction::stage_folder(const std::string& path,
                                            const ReplaceCheck& replace_check) {
    if (finished_) throw FileError(path, "staged after the outputs were committed");
    const fs::path folder = resolved_path(path);  // follows a symlink to the folder it names
    check_folder_destination(folder.string(), path, replace_check);
    check_not_staged(path);
    std::string temporary = make_temporary_folder(folder, path);
    outputs_.push_back({.destination = folder.string(),
                        .temporary = std::move(temporary),
                        .is_folder = true,
                        .replace_check = replace_check,
                        .backup = {},
                        .placed = false});
    return outputs_.back().temporary;
}

void OutputTransaction::place(Output& output) {
    std::error_code ec;
    const bool written = output.is_folder ? fs::is_directory(output.temporary, ec)
                                          : fs::is_regular_file(output.temporary, ec);
    if (!written) throw FileError(output.destination, "was staged but never written");
    if (output.is_folder) {
        check_folder_destination(output.destination, output.destination, output.replace_check);
    } else {
        check_output_file(output.destination);
    }
    if (exists_no_follow(output.destination)) {
        const std::string backup = temporary_sibling(output.destination, "old");
        if (output.is_folder || !link_backup(output.destination, backup)) {
            rename_or_throw(output.destination, backup, output.destination);
        }
        output.backup = backup;
    }
    rename_or_throw(output.temporary, output.destination, output.destination);
    output.placed = true;
}

void OutputTransaction::roll_back() {
    for (auto it = outputs_.rbegin(); it != outputs_.rend(); ++it) {
        std::error_code ec;
        if (it->placed && (it->is_folder || it->backup.empty())) {
            fs::remove_all(it->destination, ec);
        }
        if (!it->backup.empty()) fs::rename(it->backup, it->destination, ec);
        it->placed = false;
        it->backup.clear();
    }
}

void OutputTransaction::commit() {
    if (finished_) throw Error("OutputTransaction::commit() called twice");
    finished_ = true;
    try {
        for (Output& output : outputs_) place(output);
    } catch (...) {
        roll_back();
        for (const Output& output : outputs_) remove_quietly(output.temporary);
        remove_created_folders();
        throw;
    }
    for (const Output& output : outputs_) remove_quietly(output.backup);
}

}  // namespace scantling::io
