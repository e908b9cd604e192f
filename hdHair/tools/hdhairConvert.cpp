// hdhair-convert: converts hair assets (AMD TressFX .tfx 3.0/4.0, Cem Yuksel
// .hair) into a BasisCurves .usda stage that hdhair-record and OpenUSD render
// as it is, with the head they were made on (.obj) as a Mesh beside them
// (see tools/README.md "Converting hair assets").
//
//   hdhair-convert [options] input.(tfx|hair|obj)... output.usda
//
// Several inputs merge into one stage, one BasisCurves (or Mesh) prim per
// input named after the file. Exit status: 0 on success; 1 with one line
// "hdhair-convert: error: ..." on any failure (bad arguments, unreadable or
// malformed input, unwritable output). Nothing is written on failure.

#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "hdHair/assets/ObjMeshReader.h"
#include "hdHair/assets/TressFxReader.h"
#include "hdHair/assets/UsdaCurvesWriter.h"
#include "hdHair/assets/YukselHairReader.h"

namespace {

using namespace hdhair::convert;
using Clock = std::chrono::steady_clock;

struct Options {
    std::vector<std::string> files;  // inputs..., output
    std::vector<std::string> meshes;  // --mesh
    std::optional<float> rootWidth, tipWidth, followRadius;
    std::string color, cameraFrom, upAxis = "Y";
    std::string meshScheme = "none", meshColor;
    size_t maxStrands = 0;
    int followStrands = 0;
    float followTipSeparation = 1.0f;
    double metersPerUnit = 0.01;
    bool noCamera = false, verbose = false;
};

double millisecondsSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

std::string lowerExtension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

// "r,g,b" -> three finite floats.
Float3 parseTriple(const std::string& text, const char* option) {
    std::vector<float> values;
    std::stringstream stream(text);
    std::string item;
    while (std::getline(stream, item, ',')) {
        try {
            size_t used = 0;
            const float v = std::stof(item, &used);
            if (used != item.size() || !std::isfinite(v)) throw std::invalid_argument(item);
            values.push_back(v);
        } catch (const std::exception&) {
            values.clear();
            break;
        }
    }
    if (values.size() != 3)
        throw std::invalid_argument(
            fmt::format("{} wants three comma-separated numbers (x,y,z), not '{}'", option, text));
    return {values[0], values[1], values[2]};
}

HairStrands readAsset(const std::string& path) {
    const std::string ext = lowerExtension(path);
    if (ext == ".tfx") return readTressFx(path);
    if (ext == ".hair") return readYukselHair(path);
    throw std::invalid_argument(fmt::format("{}: unknown input format '{}' (reads .tfx, .hair and .obj)", path, ext));
}

// How the stage is written, from the options; throws std::invalid_argument
// for a bad one.
UsdaWriteOptions writeOptions(const Options& options) {
    UsdaWriteOptions write;
    if (options.upAxis != "Y" && options.upAxis != "Z")
        throw std::invalid_argument(fmt::format("--upAxis must be Y or Z, not '{}'", options.upAxis));
    write.upAxis = options.upAxis[0];
    write.metersPerUnit = options.metersPerUnit;
    write.rootWidth = options.rootWidth;
    write.tipWidth = options.tipWidth;
    write.camera = !options.noCamera;
    if (!options.color.empty()) write.color = parseTriple(options.color, "--color");
    if (!options.cameraFrom.empty()) write.cameraFrom = parseTriple(options.cameraFrom, "--cameraFrom");
    if (options.followStrands < 0) throw std::invalid_argument("--followStrands must be >= 0");
    return write;
}

// Every .obj (--mesh, and those among the inputs) as a Mesh input; each
// one's source for the stage's doc.
std::vector<MeshInput> readMeshes(const Options& options, std::vector<std::string>& sources) {
    std::vector<MeshInput> meshes;
    std::vector<std::string> meshFiles = options.meshes;
    for (size_t i = 0; i + 1 < options.files.size(); ++i)
        if (lowerExtension(options.files[i]) == ".obj") meshFiles.push_back(options.files[i]);
    for (const std::string& path : meshFiles) {
        const Clock::time_point readStart = Clock::now();
        MeshInput mesh;
        mesh.mesh = readObjMesh(path);
        mesh.name = std::filesystem::path(path).stem().string();
        mesh.subdivisionScheme = options.meshScheme;
        if (!options.meshColor.empty()) mesh.color = parseTriple(options.meshColor, "--meshColor");
        for (const std::string& warning : mesh.mesh.warnings)
            std::fprintf(stderr, "hdhair-convert: warning: %s: %s\n", path.c_str(), warning.c_str());
        if (options.verbose)
            std::printf("hdhair-convert: read %s: %zu faces, %zu points in %.1f ms\n", path.c_str(),
                        mesh.mesh.faceVertexCounts.size(), mesh.mesh.points.size(), millisecondsSince(readStart));
        sources.push_back(fmt::format("{} (mesh, {} faces)", path, mesh.mesh.faceVertexCounts.size()));
        meshes.push_back(std::move(mesh));
    }
    return meshes;
}

// Every hair asset among the inputs, thinned to --maxStrands; each one's
// source for the stage's doc.
std::vector<CurvesInput> readHair(const Options& options, std::vector<std::string>& sources) {
    std::vector<CurvesInput> inputs;
    for (size_t i = 0; i + 1 < options.files.size(); ++i) {
        const std::string& path = options.files[i];
        if (lowerExtension(path) == ".obj") continue;
        const Clock::time_point readStart = Clock::now();
        CurvesInput input;
        input.strands = readAsset(path);
        input.name = std::filesystem::path(path).stem().string();
        for (const std::string& repair : input.strands.repairs)
            std::fprintf(stderr, "hdhair-convert: warning: %s: %s\n", path.c_str(), repair.c_str());
        if (options.verbose) {
            const HairStrands& s = input.strands;
            std::printf("hdhair-convert: read %s: %s, %zu strands, %zu points in %.1f ms\n", path.c_str(),
                        s.format.c_str(), s.strandCount(), s.pointCount(), millisecondsSince(readStart));
        }
        if (options.maxStrands > 0 && input.strands.strandCount() > options.maxStrands) {
            input.strands = subsampleStrands(input.strands, options.maxStrands);
            if (options.verbose)
                std::printf("hdhair-convert: %s: kept %zu strands (--maxStrands)\n", input.strands.source.c_str(),
                            input.strands.strandCount());
        }
        sources.push_back(fmt::format("{} ({}, {} strands)", input.strands.source, input.strands.format,
                                      input.strands.strandCount()));
        inputs.push_back(std::move(input));
    }
    return inputs;
}

// --followStrands: strands grown around every guide.
void addFollowers(const Options& options, std::vector<CurvesInput>& inputs) {
    Bounds guides;
    for (const CurvesInput& input : inputs)
        for (const Float3& p : input.strands.points) guides.add(p);
    FollowOptions follow;
    follow.perGuide = options.followStrands;
    follow.radius = options.followRadius.value_or(0.01f * guides.diagonal());
    follow.tipSeparation = options.followTipSeparation;
    for (CurvesInput& input : inputs) {
        input.strands = addFollowStrands(input.strands, follow);
        if (options.verbose)
            std::printf("hdhair-convert: %s: %zu strands with %d follow strands per guide (radius %s)\n",
                        input.strands.source.c_str(), input.strands.strandCount(), follow.perGuide,
                        formatNumber(follow.radius).c_str());
    }
}

// --verbose: what was written.
void reportWritten(const CurvesUsda& usda, const std::string& output, Clock::time_point start) {
    for (const WrittenCurves& curves : usda.curves)
        std::printf("hdhair-convert: %s: %zu strands, %zu points, widths %s\n", curves.path.c_str(), curves.strands,
                    curves.points, curves.widths.c_str());
    for (const WrittenMesh& mesh : usda.meshes)
        std::printf("hdhair-convert: %s: a mesh of %zu faces, %zu points\n", mesh.path.c_str(), mesh.faces,
                    mesh.points);
    std::printf("hdhair-convert: wrote %s (%.1f MB) in %.1f ms\n", output.c_str(),
                double(usda.text.size()) / (1024.0 * 1024.0), millisecondsSince(start));
}

int run(const Options& options) {
    const Clock::time_point start = Clock::now();
    if (options.files.size() < 2 && !(options.files.size() == 1 && !options.meshes.empty()))
        throw std::invalid_argument("give at least one input file and the output .usda (see --help)");
    const std::string output = options.files.back();
    if (lowerExtension(output) != ".usda")
        throw std::invalid_argument(fmt::format("the output '{}' must be a .usda file (the last argument)", output));
    UsdaWriteOptions write = writeOptions(options);
    std::vector<std::string> sources;
    std::vector<MeshInput> meshes = readMeshes(options, sources);
    std::vector<CurvesInput> inputs = readHair(options, sources);
    if (options.followStrands > 0) addFollowers(options, inputs);
    std::string doc = "Converted by hdhair-convert from ";
    for (size_t i = 0; i < sources.size(); ++i) doc += (i ? ", " : "") + sources[i];
    write.doc = doc;
    CurvesUsda usda = buildCurvesUsda(inputs, write, meshes);
    writeFileAtomically(output, usda.text);
    if (options.verbose) reportWritten(usda, output, start);
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    Options options;
    CLI::App app{"Converts hair assets (AMD TressFX .tfx 3.0/4.0, Cem Yuksel .hair) into a BasisCurves .usda "
                 "stage with a camera (/World/main_cam) and a key light; .obj inputs (the head) become Mesh prims "
                 "beside the hair.",
                 "hdhair-convert"};
    app.add_option("files", options.files, "input.(tfx|hair|obj)... output.usda")->required();
    app.add_option("--mesh", options.meshes,
                   "A Wavefront .obj mesh to write as a Mesh prim beside the hair, in the same units and space "
                   "(repeatable; an .obj among the inputs does the same)")
        ->allow_extra_args(false);
    app.add_option("--meshScheme", options.meshScheme,
                   "subdivisionScheme of the written meshes: none (drawn as their polygons), catmullClark, loop or "
                   "bilinear")
        ->capture_default_str();
    app.add_option("--meshColor", options.meshColor, "displayColor r,g,b of the written meshes (default 0.72,0.56,0.48)");
    app.add_option("--rootWidth", options.rootWidth,
                   "Curve width at the root, in scene units (default 0.0015 x the bounding box diagonal)");
    app.add_option("--tipWidth", options.tipWidth, "Curve width at the tip (default 0.2 x the root width)");
    app.add_option("--color", options.color, "displayColor r,g,b for every strand (default: the file's, else brown)");
    app.add_option("--maxStrands", options.maxStrands,
                   "Keep at most N strands per input, evenly spread (0: all), for quick tests");
    app.add_option("--followStrands", options.followStrands,
                   "Add N TressFX-style follow strands around each guide strand (deterministic)");
    app.add_option("--followRadius", options.followRadius,
                   "Largest root offset of a follow strand from its guide (default 0.01 x the bounding box "
                   "diagonal)");
    app.add_option("--followTipSeparation", options.followTipSeparation,
                   "Follow strand offsets grow to (1 + this) x their root offset at the tip")
        ->capture_default_str();
    app.add_option("--upAxis", options.upAxis, "The stage's up axis, Y or Z (metadata; points are not rotated)")
        ->capture_default_str();
    app.add_option("--cameraFrom", options.cameraFrom,
                   "Direction x,y,z from the asset's centre to the camera (default 0,0,1; 0,-1,0 with --upAxis Z)");
    app.add_flag("--noCamera", options.noCamera, "Write no camera and no light");
    app.add_option("--units", options.metersPerUnit, "The stage's metersPerUnit")->capture_default_str();
    app.add_flag("--verbose,-v", options.verbose, "Print the strands and points read and written");
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& help) {
        return app.exit(help);
    } catch (const CLI::ParseError& error) {
        std::fprintf(stderr, "hdhair-convert: error: %s (see --help)\n", error.what());
        return 1;
    }
    try {
        return run(options);
    } catch (const std::exception& error) {
        std::fprintf(stderr, "hdhair-convert: error: %s\n", error.what());
        return 1;
    }
}
