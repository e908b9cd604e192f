#pragma once
// Reading a whole input file (a .usda layer, a hair asset). Only regular
// files are read: a stage or reference naming a device (/dev/zero), a FIFO
// or a directory is refused before a byte is read, so no input can make
// hdHair read without end.

#include <string>

namespace hdhair {

// Reads `path` into `contents`. Returns "" on success, else why not in a few
// words for a message ("No such file or directory", "a character device, not
// a regular file"); never the C library's "Success".
std::string readRegularFile(const std::string& path, std::string& contents);

// Why `path` cannot be read as a regular file, in the same words, or "" when
// it can (for readers that open the file themselves, such as OpenImageIO).
std::string regularFileProblem(const std::string& path);

}  // namespace hdhair
