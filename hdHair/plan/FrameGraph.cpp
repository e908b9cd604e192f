#include "hdHair/plan/FrameGraph.h"

#include <algorithm>
#include <set>
#include <stdexcept>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

namespace hdhair {

std::string FrameGraph::nameOf(const FrameResource& resource) const {
    if (!isPerLight(resource.kind)) return toString(resource.kind);
    return std::string(toString(resource.kind)) + " " +
           (resource.light < lightNames_.size() ? lightNames_[resource.light] : std::to_string(resource.light));
}

std::vector<std::string> FrameGraph::namesOf(const std::vector<FrameResource>& resources) const {
    std::vector<std::string> names;
    for (const FrameResource& resource : resources) names.push_back(nameOf(resource));
    return names;
}

std::string FrameGraph::joined(const std::vector<FrameResource>& resources) const {
    std::string text;
    for (const FrameResource& resource : resources) text += (text.empty() ? "" : ", ") + nameOf(resource);
    return text.empty() ? "-" : text;
}

void FrameGraph::input(const FrameResource& resource) { inputs_.push_back(resource); }

FramePass& FrameGraph::add(FramePass pass) {
    passes_.push_back(std::move(pass));
    return passes_.back();
}

void FrameGraph::output(const FrameResource& resource) { outputs_.push_back(resource); }

void FrameGraph::compile() {
    // Backwards from the outputs: what is still needed by something later.
    std::set<FrameResource> needed(outputs_.begin(), outputs_.end());
    for (auto pass = passes_.rbegin(); pass != passes_.rend(); ++pass) {
        pass->enabled = false;
        if (!pass->wanted) continue;
        bool read = std::any_of(pass->writes.begin(), pass->writes.end(),
                                [&](const FrameResource& resource) { return needed.count(resource) > 0; });
        if (!read) continue;
        pass->enabled = true;
        // A pass that only writes a resource provides it to those after it;
        // one that also reads it (updates in place) still needs it before.
        for (const FrameResource& resource : pass->writes)
            if (std::find(pass->reads.begin(), pass->reads.end(), resource) == pass->reads.end())
                needed.erase(resource);
        needed.insert(pass->reads.begin(), pass->reads.end());
    }
    // Forwards: every read of a running pass has a provider before it.
    std::set<FrameResource> available(inputs_.begin(), inputs_.end());
    for (const FramePass& pass : passes_) {
        if (!pass.enabled) continue;
        for (const FrameResource& resource : pass.reads)
            if (!available.count(resource))
                throw std::logic_error(fmt::format("frame graph: pass '{}' reads '{}', which no earlier pass writes",
                                                   pass.name, nameOf(resource)));
        available.insert(pass.writes.begin(), pass.writes.end());
    }
}

const FramePass* FrameGraph::find(const std::string& name) const {
    auto it = std::find_if(passes_.begin(), passes_.end(), [&](const FramePass& pass) { return pass.name == name; });
    return it == passes_.end() ? nullptr : &*it;
}

bool FrameGraph::isEnabled(const std::string& name) const {
    const FramePass* pass = find(name);
    return pass && pass->enabled;
}

const FramePass* FrameGraph::find(PassKind kind, size_t subject) const {
    auto it = std::find_if(passes_.begin(), passes_.end(),
                           [&](const FramePass& pass) { return pass.kind == kind && pass.subject == subject; });
    return it == passes_.end() ? nullptr : &*it;
}

bool FrameGraph::isEnabled(PassKind kind, size_t subject) const {
    const FramePass* pass = find(kind, subject);
    return pass && pass->enabled;
}

std::string FrameGraph::reasonFor(const FramePass& pass) const {
    if (pass.wanted && !pass.enabled)
        return pass.reason + fmt::format("; not built: nothing reads its output ({})", joined(pass.writes));
    return pass.reason;
}

std::string FrameGraph::describe() const {
    // Names line up in a column as wide as the longest ("shadowDepth /World/key").
    size_t width = 12;
    for (const FramePass& pass : passes_) width = std::max(width, pass.name.size());
    std::string text;
    for (const FramePass& pass : passes_) {
        text += fmt::format("  {:<{}} {:<4} {}\n", pass.name, width, pass.enabled ? "on" : "off", reasonFor(pass));
        if (pass.enabled)
            text += fmt::format("  {:<{}}      reads {}; writes {}\n", "", width, joined(pass.reads), joined(pass.writes));
    }
    text += fmt::format("  {:<{}}      the frame delivers {}\n", "", width, joined(outputs_));
    return text;
}

nlohmann::json FrameGraph::toJson(const std::vector<double>& milliseconds) const {
    nlohmann::json json = nlohmann::json::array();
    for (size_t i = 0; i < passes_.size(); ++i) {
        const FramePass& pass = passes_[i];
        nlohmann::json entry = {{"pass", pass.name},       {"enabled", pass.enabled}, {"reason", reasonFor(pass)},
                                {"reads", namesOf(pass.reads)}, {"writes", namesOf(pass.writes)}};
        if (pass.enabled) entry["milliseconds"] = milliseconds.size() == passes_.size() ? milliseconds[i] : 0.0;
        json.push_back(std::move(entry));
    }
    return json;
}

}  // namespace hdhair
