// hdhair-compare: how far images are from a reference, in the measure the
// dome and Cycles comparisons use (relativeColorError, ImageComparison.h):
// over the pixels either image covers, the RMS of the colour difference over
// the RMS of the reference, the largest difference over the reference's
// largest value, and the ratio of their sums.
//
//   hdhair-compare reference.exr image.exr [image.exr ...]
//
// Prints one JSON object a line per image. Exit status 0, or 1 with one line
// "hdhair-compare: error: ..." (unreadable file, sizes that differ).

#include <cstdio>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "hdHair/image/ImageComparison.h"
#include "hdHair/image/ImageWriter.h"

int main(int argc, char** argv) {
    CLI::App app{"Compares images with a reference over the pixels they cover.", "hdhair-compare"};
    std::string referencePath;
    std::vector<std::string> imagePaths;
    app.add_option("reference", referencePath, "The reference image (scene-linear, pre-multiplied RGBA)")->required();
    app.add_option("images", imagePaths, "Images of the same size to compare with it")->required();
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& help) {
        return app.exit(help);
    } catch (const CLI::ParseError& error) {
        std::fprintf(stderr, "hdhair-compare: error: %s (see --help)\n", error.what());
        return 2;
    }
    try {
        const hdhair::Image reference = hdhair::readImage(referencePath);
        for (const std::string& path : imagePaths) {
            const hdhair::RelativeColorError error = hdhair::relativeColorError(hdhair::readImage(path), reference);
            const nlohmann::json line = {{"image", path},
                                         {"reference", referencePath},
                                         {"coveredPixels", error.coveredPixels},
                                         {"relativeRmse", error.rootMeanSquare},
                                         {"largest", error.largest},
                                         {"sumRatio", error.sumRatio}};
            std::printf("%s\n", line.dump().c_str());
        }
    } catch (const std::exception& error) {
        std::fprintf(stderr, "hdhair-compare: error: %s\n", error.what());
        return 1;
    }
    return 0;
}
