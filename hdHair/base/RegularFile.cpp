#include "hdHair/base/RegularFile.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <system_error>

namespace hdhair {

namespace fs = std::filesystem;

namespace {

const char* kindOf(fs::file_type type) {
    switch (type) {
    case fs::file_type::directory: return "a directory";
    case fs::file_type::character: return "a character device";
    case fs::file_type::block: return "a block device";
    case fs::file_type::fifo: return "a FIFO";
    case fs::file_type::socket: return "a socket";
    default: return "not a regular file";
    }
}

}  // namespace

std::string regularFileProblem(const std::string& path) {
    std::error_code error;
    const fs::file_status status = fs::status(path, error);  // follows symbolic links
    if (error) return error.message();
    if (status.type() != fs::file_type::regular) return std::string(kindOf(status.type())) + ", not a regular file";
    return std::string();
}

std::string readRegularFile(const std::string& path, std::string& contents) {
    if (std::string problem = regularFileProblem(path); !problem.empty()) return problem;
    std::FILE* file = std::fopen(path.c_str(), "rb");
    if (!file) return errno ? std::strerror(errno) : "cannot be opened";
    contents.clear();
    char buffer[1 << 16];
    size_t read = 0;
    errno = 0;
    while ((read = std::fread(buffer, 1, sizeof buffer, file)) > 0) contents.append(buffer, read);
    const bool failed = std::ferror(file) != 0;
    const int reason = errno;
    std::fclose(file);
    if (failed) return reason ? std::strerror(reason) : "a read error";
    return std::string();
}

}  // namespace hdhair
