#include "hdHair/usda/Stage.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iterator>

#include "hdHair/usda/StageComposer.h"

namespace hdhair::usda {

std::string SourceLocation::toString() const {
    return file + ":" + std::to_string(line) + ":" + std::to_string(column);
}

namespace {

void slerpQuaternions(const Value& a, const Value& b, double t, Value& out) {
    for (size_t base = 0; base + 4 <= a.numbers.size(); base += 4) {
        double qa[4], qb[4];
        double dot = 0.0;
        for (int i = 0; i < 4; ++i) {
            qa[i] = a.numbers[base + static_cast<size_t>(i)];
            qb[i] = b.numbers[base + static_cast<size_t>(i)];
            dot += qa[i] * qb[i];
        }
        if (dot < 0.0) {  // the shorter way round
            dot = -dot;
            for (double& q : qb) q = -q;
        }
        double wa = 1.0 - t, wb = t;
        if (dot < 0.9995) {
            double theta = std::acos(std::min(1.0, dot));
            double sinTheta = std::sin(theta);
            wa = std::sin((1.0 - t) * theta) / sinTheta;
            wb = std::sin(t * theta) / sinTheta;
        }
        for (int i = 0; i < 4; ++i) out.numbers[base + static_cast<size_t>(i)] = wa * qa[i] + wb * qb[i];
    }
}

}  // namespace

std::optional<Value> Attribute::valueAt(double time) const {
    // NaN stands for UsdTimeCode::Default(): only the default value counts,
    // whatever samples exist (an attribute with samples only has no value).
    if (!std::isnan(time) && !timeSamples.empty()) {
        auto upper = timeSamples.lower_bound(time);  // first sample at or after `time`
        if (upper == timeSamples.end()) upper = std::prev(upper);
        if (upper->first == time || upper == timeSamples.begin() || !(time < upper->first)) {
            if (upper->second.isBlocked) return std::nullopt;
            return upper->second;
        }
        auto lower = std::prev(upper);
        const Value& a = lower->second;
        const Value& b = upper->second;
        if (a.isBlocked) return std::nullopt;
        const std::string scalar = scalarTypeNameOf(a.typeName);
        const bool interpolate = !b.isBlocked && isFloatingPointType(scalar) && a.typeName == b.typeName &&
                                 a.numbers.size() == b.numbers.size() && !a.numbers.empty();
        if (!interpolate) return a;  // held
        const double t = (time - lower->first) / (upper->first - lower->first);
        Value out = a;
        if (isQuaternionType(scalar)) {
            slerpQuaternions(a, b, t, out);
        } else {
            for (size_t i = 0; i < out.numbers.size(); ++i) {
                out.numbers[i] = a.numbers[i] + (b.numbers[i] - a.numbers[i]) * t;
            }
        }
        return out;
    }
    if (!defaultValue || defaultValue->isBlocked) return std::nullopt;
    return defaultValue;
}

std::string resolveAssetPath(const std::string& assetPath, const std::string& directory) {
    const std::filesystem::path asset(assetPath);
    if (asset.is_absolute()) return asset.lexically_normal().string();
    return (std::filesystem::path(directory) / asset).lexically_normal().string();
}

const std::string& Attribute::valueDirectoryAt(double time) const {
    return !std::isnan(time) && !timeSamples.empty() ? timeSamplesDirectory : defaultValueDirectory;
}

const Attribute* Prim::attribute(const std::string& attributeName) const {
    auto it = attributes.find(attributeName);
    return it == attributes.end() ? nullptr : &it->second;
}

const Prim* Prim::child(const std::string& childName) const {
    for (const auto& c : children) {
        if (c->name == childName) return c.get();
    }
    return nullptr;
}

std::unique_ptr<Stage> Stage::open(const std::string& path) { return StageComposer::openFile(path); }

std::unique_ptr<Stage> Stage::openFromString(const std::string& text, const std::string& identifier,
                                             const std::string& baseDirectory) {
    return StageComposer::openText(text, identifier, baseDirectory);
}

const Prim* Stage::findPrim(const std::string& path) const {
    if (path.empty() || path[0] != '/') return nullptr;
    const Prim* prim = pseudoRoot_.get();
    size_t pos = 1;
    while (prim && pos < path.size()) {
        size_t end = path.find('/', pos);
        if (end == std::string::npos) end = path.size();
        if (end == pos) return nullptr;  // "//"
        prim = prim->child(path.substr(pos, end - pos));
        pos = end + 1;
    }
    return prim;
}

namespace {

void collect(const Prim& prim, std::vector<const Prim*>& out) {
    for (const auto& child : prim.children) {
        // UsdPrimDefaultPredicate: active, defined (def, not an over-only
        // prim) and not abstract (class); skipped prims prune their subtree.
        if (!child->active || child->specifier != Specifier::Def) continue;
        out.push_back(child.get());
        collect(*child, out);
    }
}

}  // namespace

std::vector<const Prim*> Stage::traverse() const {
    std::vector<const Prim*> out;
    if (pseudoRoot_) collect(*pseudoRoot_, out);
    return out;
}

}  // namespace hdhair::usda
