#pragma once
// Output files are written atomically: to a temporary sibling in the same
// folder, then renamed over the target, so a reader never sees a half
// written file, a failed write leaves any previous file in place, and no
// temporary file is left behind whatever fails, short of the process being
// killed (removeLeftoverTemporaries clears up after that).

#include <functional>
#include <string>

namespace hdhair {

// Calls `write` with the temporary path (a hidden sibling of `path` that keeps
// its extension, for writers that choose a format by it), then renames it
// over `path`. `write` throws, or returns a reason ("" for success). Throws
// std::runtime_error "cannot write 'path': reason" when anything fails,
// having removed the temporary file.
void writeFileAtomically(const std::string& path, const std::function<std::string(const std::string&)>& write);

// writeFileAtomically for text: `text` is the whole file.
void writeTextFileAtomically(const std::string& path, const std::string& text);

// Removes the temporary siblings a writer of `path` left when it was killed
// before it could remove them (SIGKILL, a node going down), and returns how
// many it removed. Only for when nothing else may be writing `path` now: a
// farm task about to render a frame it owns.
int removeLeftoverTemporaries(const std::string& path);

// Why `path` could not be written (its folder is missing, not a folder, or
// not writable), or "" when it can: checked before work whose result goes there.
std::string whyNotWritable(const std::string& path);

}  // namespace hdhair
