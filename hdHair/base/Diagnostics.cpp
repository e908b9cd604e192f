#include "hdHair/base/Diagnostics.h"

#include "hdHair/base/PrintableText.h"

namespace hdhair {

void Diagnostics::warn(std::string where, std::string message) {
    Diagnostic diagnostic{printableText(where), printableText(message)};
    std::lock_guard<std::mutex> lock(mutex_);
    if (listener_) listener_(diagnostic);
    warnings_.push_back(std::move(diagnostic));
}

std::vector<Diagnostic> Diagnostics::warnings() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return warnings_;
}

size_t Diagnostics::warningCount() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return warnings_.size();
}

void Diagnostics::setListener(Listener listener) {
    std::lock_guard<std::mutex> lock(mutex_);
    listener_ = std::move(listener);
}

}  // namespace hdhair
