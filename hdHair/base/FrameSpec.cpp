#include "hdHair/base/FrameSpec.h"

#include <charconv>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include <fmt/format.h>

namespace hdhair {
namespace {

double parseNumber(const std::string& text, const std::string& spec) {
    double value = 0.0;
    const char* begin = text.data();
    const char* end = begin + text.size();
    auto [next, error] = std::from_chars(begin, end, value);
    if (text.empty() || error != std::errc() || next != end || !std::isfinite(value))
        throw std::invalid_argument(fmt::format("bad frame spec '{}': '{}' is not a number", spec, text));
    return value;
}

}  // namespace

std::vector<double> parseFrameSpec(const std::string& spec) {
    std::vector<double> frames;
    std::stringstream items(spec);
    std::string item;
    while (std::getline(items, item, ',')) {
        std::string::size_type colon = item.find(':');
        if (colon == std::string::npos) {
            frames.push_back(parseNumber(item, spec));
            continue;
        }
        std::string rest = item.substr(colon + 1);
        std::string::size_type x = rest.find('x');
        double start = parseNumber(item.substr(0, colon), spec);
        double end = parseNumber(rest.substr(0, x), spec);
        double stride = x == std::string::npos ? 1.0 : parseNumber(rest.substr(x + 1), spec);
        if (stride <= 0.0)
            throw std::invalid_argument(fmt::format("bad frame spec '{}': the stride must be positive", spec));
        if (end < start)
            throw std::invalid_argument(fmt::format("bad frame spec '{}': range {} ends before it starts", spec, item));
        if ((end - start) / stride > 1e6)
            throw std::invalid_argument(fmt::format("bad frame spec '{}': more than a million frames", spec));
        // Count steps rather than accumulate, so strides like 0.1 do not drift.
        auto steps = static_cast<long>(std::floor((end - start) / stride + 1e-9));
        for (long i = 0; i <= steps; ++i) frames.push_back(start + double(i) * stride);
    }
    if (frames.empty()) throw std::invalid_argument(fmt::format("bad frame spec '{}': no frames", spec));
    return frames;
}

std::string formatFrameSpec(const std::vector<double>& frames) {
    std::string spec;
    for (size_t i = 0; i < frames.size();) {
        size_t end = i;
        if (frames[i] == std::floor(frames[i]))
            while (end + 1 < frames.size() && frames[end + 1] == frames[end] + 1.0) ++end;
        // "{}" is the shortest text that reads back as the same double;
        // "{:g}" would round to six digits (123456.5 -> 123456, 1e6 -> 1e+06).
        spec += (spec.empty() ? "" : ",") + (end > i ? fmt::format("{}:{}", frames[i], frames[end])
                                                     : fmt::format("{}", frames[i]));
        i = end + 1;
    }
    return spec;
}

bool hasFramePlaceholder(const std::string& pattern) { return pattern.find('#') != std::string::npos; }

std::string expandFramePlaceholder(const std::string& pattern, double frame) {
    std::string::size_type begin = pattern.find('#');
    if (begin == std::string::npos) return pattern;
    std::string::size_type end = begin;
    while (end < pattern.size() && pattern[end] == '#') ++end;
    int integerDigits = int(end - begin), decimals = 0;
    if (end + 1 < pattern.size() && pattern[end] == '.' && pattern[end + 1] == '#') {
        std::string::size_type decimalEnd = end + 1;
        while (decimalEnd < pattern.size() && pattern[decimalEnd] == '#') ++decimalEnd;
        decimals = int(decimalEnd - end - 1);
        end = decimalEnd;
    }
    double scale = std::pow(10.0, decimals);
    if (std::abs(frame * scale - std::round(frame * scale)) > 1e-6)
        throw std::invalid_argument(fmt::format(
            "frame {} has more decimals than the output name '{}' can show (use e.g. ####.## in it)", frame, pattern));
    int width = integerDigits + (decimals > 0 ? decimals + 1 : 0) + (frame < 0 ? 1 : 0);
    std::string number = fmt::format("{:0{}.{}f}", frame, width, decimals);
    return pattern.substr(0, begin) + number + pattern.substr(end);
}

}  // namespace hdhair
