#pragma once
// usdrecord's --frames syntax and its output-name placeholders.
//   FRAMESPEC: comma-separated frames and ranges: "12", "1:10", "1:10x2",
//              "1.5", "0:1x0.25". Ranges include their end when the stride
//              lands on it.
//   Output names: a run of '#' is replaced by the frame number, zero-padded
//   to the run's length; '#' characters after a '.' in the run give decimal
//   places ("####.##" -> "0001.50"). Several frames need a placeholder.

#include <string>
#include <vector>

namespace hdhair {

// Throws std::invalid_argument with a one-line reason.
std::vector<double> parseFrameSpec(const std::string& spec);

// The frames as a spec parseFrameSpec reads back: runs of whole frames one
// apart as "a:b", the rest listed ("1:6,9,12.5"). For a command to resubmit.
std::string formatFrameSpec(const std::vector<double>& frames);

bool hasFramePlaceholder(const std::string& pattern);

// Throws std::invalid_argument when the frame has a fraction the pattern
// cannot show (two frames would write the same file).
std::string expandFramePlaceholder(const std::string& pattern, double frame);

}  // namespace hdhair
