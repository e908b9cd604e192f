#pragma once
// Warnings raised while reading and preparing a scene. Bad input that can be
// repaired (a primvar of the wrong size, a NaN point) is repaired by a
// documented rule and reported here, naming the file or prim and attribute;
// input that cannot be repaired throws hdhair::InputError instead.

#include <functional>
#include <mutex>
#include <string>
#include <vector>

namespace hdhair {

struct Diagnostic {
    std::string where;    // "file.usda:12:5" or "/World/hair.widths"
    std::string message;  // what is wrong and what was done about it
};

// Thread-safe: curve preparation runs in parallel and reports here.
class Diagnostics {
public:
    using Listener = std::function<void(const Diagnostic&)>;

    void warn(std::string where, std::string message);
    std::vector<Diagnostic> warnings() const;
    size_t warningCount() const;
    // Called for each new warning (the CLI prints them as they come).
    void setListener(Listener listener);

private:
    mutable std::mutex mutex_;
    std::vector<Diagnostic> warnings_;
    Listener listener_;
};

}  // namespace hdhair
