#pragma once
// Runs Blender headless on an exported scene (CyclesScene.h) and follows it:
//   blender -b --factory-startup --python-exit-code 2 -P renderCyclesScene.py -- scene.json out.exr
// Blender's output is read line by line: its "Sample i/N" and "Remaining"
// reports become progress callbacks, the script's own "hdhair-cycles:" lines
// its result or its error. A stop request (the caller's flag, set from a
// signal handler) ends Blender with SIGTERM and throws CyclesStopped, so a
// farm's kill leaves no half-written image and no orphaned renderer.
// Blender's TMPDIR is the scene's folder, so its own temporary files go
// with that folder too.

#include <atomic>
#include <functional>
#include <stdexcept>
#include <string>

namespace hdhair {

struct CyclesProgress {
    int sample = 0, samples = 0;
    double secondsLeft = -1.0;  // Cycles' estimate; < 0 before it has one
};

struct CyclesProcessRequest {
    std::string blender;  // the executable: a path, or a name looked up on PATH
    std::string script;   // renderCyclesScene.py
    std::string sceneJson;
    std::string outputExr;
    std::function<void(const CyclesProgress&)> progress;
    const std::atomic<bool>* stop = nullptr;
};

struct CyclesProcessResult {
    std::string blenderVersion;  // "Blender 3.4.1"
    int samplesDone = 0;         // fewer than asked when the time limit ended it
    double renderSeconds = 0.0;  // Cycles' own render time
};

class CyclesStopped : public std::runtime_error {
public:
    CyclesStopped() : std::runtime_error("stopped before Cycles finished; nothing written") {}
};

// Throws std::runtime_error with one line: Blender missing (naming the
// package), or Blender's or the script's error, and CyclesStopped.
CyclesProcessResult runCyclesProcess(const CyclesProcessRequest& request);

// The script beside an installed or built hdhair-record
// (<prefix>/share/hdhair/cycles/renderCyclesScene.py), or
// $HDHAIR_CYCLES_SCRIPT when set.
std::string defaultCyclesScript();

}  // namespace hdhair
