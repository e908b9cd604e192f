// Every shader in shaders/ is checked by glslangValidator (the Khronos
// reference front end) without any GL context, after the same #include
// expansion the engine applies before handing sources to the driver.

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "hdHair/gl/ShaderSources.h"

using namespace hdhair::gl;
namespace fs = std::filesystem;

namespace {

bool isStageFile(const std::string& name) {
    for (const char* extension : {".vert", ".tesc", ".tese", ".geom", ".frag", ".comp"})
        if (fs::path(name).extension() == extension) return true;
    return false;
}

// Runs glslangValidator on source saved as `fileName`; returns its exit status
// and fills `output` with what it printed.
int validate(const std::string& source, const std::string& fileName, std::string& output) {
    fs::path directory = fs::temp_directory_path() / ("hdhair-shaders-" + std::to_string(::getpid()));
    fs::create_directories(directory);
    fs::path file = directory / fs::path(fileName).filename();
    std::ofstream(file) << source;
    fs::path log = directory / "log.txt";
    std::string command = std::string(HDHAIR_GLSLANG_VALIDATOR) + " \"" + file.string() + "\" > \"" +
                          log.string() + "\" 2>&1";
    int status = std::system(command.c_str());
    std::ifstream in(log);
    output.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    fs::remove_all(directory);
    return status;
}

}  // namespace

TEST(Shaders, EveryStageFileCompilesWithGlslang) {
    int checked = 0;
    for (const auto& [name, source] : embeddedShaderSources()) {
        if (!isStageFile(name)) continue;
        std::string output;
        EXPECT_EQ(validate(expandedShaderSource(name), name, output), 0) << name << ":\n" << output;
        ++checked;
    }
    EXPECT_GE(checked, 4) << "the strand program has four stages";
}

TEST(Shaders, ValidatorRejectsABrokenShader) {
    // Guards the test above against a validator that accepts anything.
    std::string output;
    EXPECT_NE(validate("#version 450 core\nvoid main() { undefinedFunction(); }\n", "broken.frag", output), 0);
}

TEST(Shaders, IncludesAreExpandedOnce) {
    std::string source = expandedShaderSource("strand.frag");
    EXPECT_EQ(source.find("#include"), std::string::npos);
    EXPECT_EQ(source.find("GL_GOOGLE_include_directive"), std::string::npos);
    size_t first = source.find("uniform FrameUniforms");
    ASSERT_NE(first, std::string::npos);
    EXPECT_EQ(source.find("uniform FrameUniforms", first + 1), std::string::npos);
}

TEST(Shaders, UnknownShaderIsAnError) {
    EXPECT_THROW(expandedShaderSource("missing.frag"), std::runtime_error);
}
