#pragma once
// OpenUSD's diagnostics (TfDiagnosticMgr), taken while one of these lives
// instead of printed by Tf in its several-line form: hdhair-record words
// them as its own one-line warnings and errors, as the embedded reader's.
//
// Warnings go to the listener; until release() they are held, so that a
// stage refused for an error prints its one error line and nothing else.
// Errors (runtime and coding errors: OpenUSD posts some bad input it
// repairs and goes on with as coding errors) are kept for the caller to word,
// as the reason for a failure or as warnings.

#include <functional>
#include <mutex>
#include <string>
#include <vector>

#include "pxr/base/tf/diagnosticMgr.h"

namespace hdhair::hydra {

class TfDiagnosticCapture : public PXR_NS::TfDiagnosticMgr::Delegate {
public:
    using Listener = std::function<void(const std::string& warning)>;

    explicit TfDiagnosticCapture(Listener listener);
    ~TfDiagnosticCapture() override;
    TfDiagnosticCapture(const TfDiagnosticCapture&) = delete;
    TfDiagnosticCapture& operator=(const TfDiagnosticCapture&) = delete;

    // The errors posted since the last call, oldest first.
    std::vector<std::string> takeErrors();
    // Passes the warnings held so far to the listener, and every later one as it comes.
    void release();

    void IssueError(PXR_NS::TfError const& error) override;
    void IssueFatalError(PXR_NS::TfCallContext const& context, std::string const& message) override;
    void IssueStatus(PXR_NS::TfStatus const& status) override;
    void IssueWarning(PXR_NS::TfWarning const& warning) override;

private:
    void warn(std::string text);

    std::mutex mutex_;
    Listener listener_;
    bool released_ = false;
    std::vector<std::string> held_, errors_;
};

}  // namespace hdhair::hydra
