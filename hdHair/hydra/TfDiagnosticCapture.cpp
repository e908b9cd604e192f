#include "hdHair/hydra/TfDiagnosticCapture.h"

#include <cstdio>
#include <utility>

#include "pxr/base/tf/diagnostic.h"
#include "pxr/base/tf/error.h"
#include "pxr/base/tf/status.h"
#include "pxr/base/tf/warning.h"

PXR_NAMESPACE_USING_DIRECTIVE

namespace hdhair::hydra {
namespace {

// OpenUSD's own words for repairs that hdHair's stage checks state again
// naming the prim and attribute (UsdStageChecks.h): said once, the better way.
bool restatedByStageChecks(const std::string& text) {
    for (const char* start : {"Unknown curve basis", "Unknown curve type", "Unknown curve wrap",
                              "Unknown USD interpolation"})
        if (text.rfind(start, 0) == 0) return true;
    return false;
}

// The plugin's warnings come as "hdHair: <where>: <what>"; hdhair-record
// prints them after its own prefix.
std::string withoutPluginPrefix(std::string text) {
    const std::string prefix = "hdHair: ";
    return text.rfind(prefix, 0) == 0 ? text.substr(prefix.size()) : text;
}

}  // namespace

TfDiagnosticCapture::TfDiagnosticCapture(Listener listener) : listener_(std::move(listener)) {
    TfDiagnosticMgr::GetInstance().AddDelegate(this);
}

TfDiagnosticCapture::~TfDiagnosticCapture() { TfDiagnosticMgr::GetInstance().RemoveDelegate(this); }

std::vector<std::string> TfDiagnosticCapture::takeErrors() {
    std::lock_guard<std::mutex> lock(mutex_);
    return std::exchange(errors_, {});
}

void TfDiagnosticCapture::release() {
    std::vector<std::string> held;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        released_ = true;
        held.swap(held_);
    }
    for (const std::string& text : held) listener_(text);
}

void TfDiagnosticCapture::warn(std::string text) {
    if (restatedByStageChecks(text)) return;
    text = withoutPluginPrefix(std::move(text));
    {
        std::lock_guard<std::mutex> lock(mutex_);
        if (!released_) {
            held_.push_back(std::move(text));
            return;
        }
    }
    listener_(text);
}

void TfDiagnosticCapture::IssueError(TfError const& error) {
    // Runtime and coding errors alike: OpenUSD posts "Cannot determine file
    // format" as a coding error, and it is the reason a layer did not open.
    if (restatedByStageChecks(error.GetCommentary())) return;
    std::lock_guard<std::mutex> lock(mutex_);
    errors_.push_back(error.GetCommentary());
}

void TfDiagnosticCapture::IssueFatalError(TfCallContext const&, std::string const& message) {
    // Tf aborts after this; say why on the way out, in one line.
    std::fprintf(stderr, "hdhair-record: error: OpenUSD: %s\n", message.c_str());
}

void TfDiagnosticCapture::IssueStatus(TfStatus const&) {}

void TfDiagnosticCapture::IssueWarning(TfWarning const& warning) { warn(warning.GetCommentary()); }

}  // namespace hdhair::hydra
