#include "hdHair/base/AtomicFile.h"

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <stdexcept>

namespace hdhair {

namespace fs = std::filesystem;

namespace {

std::string temporarySibling(const fs::path& target) {
    std::random_device device;
    std::uniform_int_distribution<unsigned> digits(0, 0xffffff);
    char suffix[16];
    std::snprintf(suffix, sizeof suffix, "%06x", digits(device));
    return (target.parent_path() / ("." + target.stem().string() + ".tmp-" + suffix + target.extension().string()))
        .string();
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

}  // namespace hdhair
