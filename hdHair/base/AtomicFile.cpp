#include "hdHair/base/AtomicFile.h"

#include <unistd.h>

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <stdexcept>

namespace hdhair {

namespace fs = std::filesystem;

namespace {

constexpr size_t kSuffixDigits = 6;

// ".<stem>.tmp-" and the extension: what every temporary sibling of `target`
// starts and ends with, around kSuffixDigits hexadecimal digits.
std::string temporaryPrefix(const fs::path& target) { return "." + target.stem().string() + ".tmp-"; }

std::string temporarySibling(const fs::path& target) {
    std::random_device device;
    std::uniform_int_distribution<unsigned> digits(0, 0xffffff);
    char suffix[16];
    std::snprintf(suffix, sizeof suffix, "%0*x", static_cast<int>(kSuffixDigits), digits(device));
    return (target.parent_path() / (temporaryPrefix(target) + suffix + target.extension().string())).string();
}

bool isTemporarySiblingOf(const std::string& name, const fs::path& target) {
    const std::string prefix = temporaryPrefix(target), extension = target.extension().string();
    if (name.size() != prefix.size() + kSuffixDigits + extension.size() || name.rfind(prefix, 0) != 0 ||
        name.compare(name.size() - extension.size(), extension.size(), extension) != 0)
        return false;
    for (size_t i = prefix.size(); i < prefix.size() + kSuffixDigits; ++i)
        if (!std::isxdigit(static_cast<unsigned char>(name[i]))) return false;
    return true;
}

}  // namespace

void writeFileAtomically(const std::string& path, const std::function<std::string(const std::string&)>& write) {
    const fs::path target = fs::absolute(path);
    const std::string temporary = temporarySibling(target);
    std::string reason;
    try {
        reason = write(temporary);
    } catch (const std::exception& error) {
        reason = error.what();
    }
    std::error_code error;
    if (reason.empty()) {
        fs::rename(temporary, target, error);
        if (error) reason = error.message();
    }
    if (!reason.empty()) {
        fs::remove(temporary, error);
        throw std::runtime_error("cannot write '" + path + "': " + reason);
    }
}

std::string whyNotWritable(const std::string& path) {
    const fs::path folder = fs::absolute(path).parent_path();
    std::error_code error;
    const fs::file_status status = fs::status(folder, error);
    if (error || status.type() == fs::file_type::not_found) return "folder '" + folder.string() + "' does not exist";
    if (status.type() != fs::file_type::directory) return "'" + folder.string() + "' is not a folder";
    if (::access(folder.c_str(), W_OK) != 0) return "folder '" + folder.string() + "' is not writable";
    return std::string();
}

void writeTextFileAtomically(const std::string& path, const std::string& text) {
    writeFileAtomically(path, [&](const std::string& temporary) {
        std::ofstream out(temporary);
        out << text;
        out.close();
        return out.good() ? std::string() : std::string("the file system refused the bytes");
    });
}

int removeLeftoverTemporaries(const std::string& path) {
    const fs::path target = fs::absolute(path);
    std::error_code error;
    fs::directory_iterator entries(target.parent_path(), error);
    if (error) return 0;
    int removed = 0;
    for (const fs::directory_entry& entry : entries)
        if (isTemporarySiblingOf(entry.path().filename().string(), target) && fs::remove(entry.path(), error))
            ++removed;
    return removed;
}

}  // namespace hdhair
