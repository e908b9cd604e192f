#include "hdHair/image/DisplayTransform.h"

#include <cmath>
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>

#include <OpenColorIO/OpenColorIO.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

namespace OCIO = OCIO_NAMESPACE;

namespace hdhair {

namespace fs = std::filesystem;

struct DisplayTransform::Ocio {
    OCIO::ConstProcessorRcPtr processor;
    OCIO::ConstCPUProcessorRcPtr cpu;
};

namespace {

// The sRGB encoding (IEC 61966-2-1): linear segment below 0.0031308.
float srgbEncode(float linear) {
    return linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
}

std::string joined(const std::vector<std::string>& names) {
    std::string text;
    for (const std::string& name : names) text += (text.empty() ? "" : ", ") + name;
    return text;
}

std::vector<std::string> displaysOf(const OCIO::ConstConfigRcPtr& config) {
    std::vector<std::string> names;
    for (int i = 0; i < config->getNumDisplays(); ++i) names.emplace_back(config->getDisplay(i));
    return names;
}

std::vector<std::string> viewsOf(const OCIO::ConstConfigRcPtr& config, const std::string& display) {
    std::vector<std::string> names;
    for (int i = 0; i < config->getNumViews(display.c_str()); ++i) names.emplace_back(config->getView(display.c_str(), i));
    return names;
}

std::vector<std::string> looksOf(const OCIO::ConstConfigRcPtr& config) {
    std::vector<std::string> names;
    for (int i = 0; i < config->getNumLooks(); ++i) names.emplace_back(config->getLookNameByIndex(i));
    return names;
}

std::vector<std::string> colorSpacesOf(const OCIO::ConstConfigRcPtr& config) {
    std::vector<std::string> names;
    for (int i = 0; i < config->getNumColorSpaces(); ++i) names.emplace_back(config->getColorSpaceNameByIndex(i));
    return names;
}

bool contains(const std::vector<std::string>& names, const std::string& name) {
    return std::find(names.begin(), names.end(), name) != names.end();
}

}  // namespace

std::string DisplayTransform::shippedConfigPath() {
    std::error_code error;
    fs::path executable = fs::read_symlink("/proc/self/exe", error);
    if (error) return std::string();
    return (executable.parent_path().parent_path() / "share" / "hdhair" / "ocio" / "config.ocio").string();
}

DisplayTransform DisplayTransform::create(const DisplayTransformOptions& options) {
    DisplayTransform transform;
    transform.mode_ = options.mode;
    transform.colorSpace_ = options.colorSpace.empty() ? options.renderingSpace : options.colorSpace;
    if (options.mode == ColorCorrectionMode::Disabled) return transform;
    if (options.mode == ColorCorrectionMode::SRGB) {
        if (transform.colorSpace_ != kLinearRec709 && transform.colorSpace_ != kAcesCg)
            throw std::invalid_argument(fmt::format("--colorCorrectionMode sRGB takes {} or {} images, not '{}'; use "
                                                    "openColorIO for other colour spaces",
                                                    kLinearRec709, kAcesCg, transform.colorSpace_));
        transform.fromAcesCg_ = transform.colorSpace_ == kAcesCg;
        return transform;
    }

    // openColorIO: --ocioConfig, else $OCIO, else the shipped config.
    std::string path = options.config;
    const char* environment = std::getenv("OCIO");
    if (path.empty() && environment && *environment) path = environment;
    if (path.empty()) path = shippedConfigPath();
    OCIO::ConstConfigRcPtr config;
    try {
        config = OCIO::Config::CreateFromFile(path.c_str());
    } catch (const OCIO::Exception& error) {
        throw std::invalid_argument(fmt::format("cannot read the OCIO config '{}': {}", path, error.what()));
    }
    transform.configPath_ = path;

    const std::vector<std::string> displays = displaysOf(config);
    transform.display_ = options.display.empty() ? config->getDefaultDisplay() : options.display;
    if (!contains(displays, transform.display_))
        throw std::invalid_argument(fmt::format("the OCIO config '{}' has no display '{}' (displays: {})", path,
                                                transform.display_, joined(displays)));
    const std::vector<std::string> views = viewsOf(config, transform.display_);
    transform.view_ = options.view.empty() ? config->getDefaultView(transform.display_.c_str()) : options.view;
    if (!contains(views, transform.view_))
        throw std::invalid_argument(fmt::format("display '{}' of the OCIO config '{}' has no view '{}' (views: {})",
                                                transform.display_, path, transform.view_, joined(views)));
    const std::vector<std::string> spaces = colorSpacesOf(config);
    if (!contains(spaces, transform.colorSpace_))
        throw std::invalid_argument(fmt::format("the OCIO config '{}' has no colour space '{}' (colour spaces: {})",
                                                path, transform.colorSpace_, joined(spaces)));
    transform.look_ = options.look;
    if (!transform.look_.empty()) {
        const std::vector<std::string> looks = looksOf(config);
        if (!contains(looks, transform.look_))
            throw std::invalid_argument(fmt::format("the OCIO config '{}' has no look '{}' (looks: {})", path,
                                                    transform.look_,
                                                    looks.empty() ? std::string("none") : joined(looks)));
    }

    auto ocio = std::make_shared<Ocio>();
    try {
        OCIO::DisplayViewTransformRcPtr displayView = OCIO::DisplayViewTransform::Create();
        displayView->setSrc(transform.colorSpace_.c_str());
        displayView->setDisplay(transform.display_.c_str());
        displayView->setView(transform.view_.c_str());
        OCIO::LegacyViewingPipelineRcPtr pipeline = OCIO::LegacyViewingPipeline::Create();
        pipeline->setDisplayViewTransform(displayView);
        if (!transform.look_.empty()) {
            pipeline->setLooksOverrideEnabled(true);
            pipeline->setLooksOverride(transform.look_.c_str());
        }
        ocio->processor = pipeline->getProcessor(config, config->getCurrentContext());
        ocio->cpu = ocio->processor->getDefaultCPUProcessor();
    } catch (const OCIO::Exception& error) {
        throw std::invalid_argument(fmt::format("OCIO cannot show '{}' on display '{}', view '{}': {}",
                                                transform.colorSpace_, transform.display_, transform.view_,
                                                error.what()));
    }
    transform.ocio_ = ocio;
    return transform;
}

void DisplayTransform::apply(float* rgba, size_t pixels) const {
    switch (mode_) {
    case ColorCorrectionMode::Disabled: return;
    case ColorCorrectionMode::SRGB:
        for (size_t p = 0; p < pixels; ++p) {
            float* c = rgba + 4 * p;
            if (fromAcesCg_) {
                const float r = c[0], g = c[1], b = c[2];
                for (size_t row = 0; row < 3; ++row)
                    c[row] = float(kAp1ToRec709[row][0] * r + kAp1ToRec709[row][1] * g + kAp1ToRec709[row][2] * b);
            }
            for (int channel = 0; channel < 3; ++channel) c[channel] = srgbEncode(c[channel]);
        }
        return;
    case ColorCorrectionMode::OpenColorIO: {
        // OCIO's image descriptions index with long: chunks of rows keep
        // every size in range whatever the image.
        constexpr size_t kChunk = 1 << 20;
        for (size_t first = 0; first < pixels; first += kChunk) {
            const size_t count = std::min(kChunk, pixels - first);
            OCIO::PackedImageDesc image(rgba + 4 * first, long(count), 1, 4);
            ocio_->cpu->apply(image);
        }
        return;
    }
    }
}

namespace {

// The sRGB mode's shader: the sRGB encoding, after AP1 primaries are taken
// to Rec.709 when the colour space is ACEScg.
std::string srgbDisplaySource(bool fromAcesCg) {
    std::string source = "vec3 hdhairSrgbEncode(vec3 c) {\n"
                         "    return mix(12.92 * c, 1.055 * pow(max(c, vec3(0.0)), vec3(1.0 / 2.4)) - 0.055,\n"
                         "               greaterThan(c, vec3(0.0031308)));\n"
                         "}\n"
                         "vec4 hdhairDisplay(vec4 color) {\n";
    if (fromAcesCg) {
        // GLSL matrices are column-major: column j is kAp1ToRec709[.][j].
        source += fmt::format(
            "    color.rgb = mat3({:.8f}, {:.8f}, {:.8f}, {:.8f}, {:.8f}, {:.8f}, {:.8f}, {:.8f}, {:.8f}) * "
            "color.rgb;\n",
            kAp1ToRec709[0][0], kAp1ToRec709[1][0], kAp1ToRec709[2][0], kAp1ToRec709[0][1], kAp1ToRec709[1][1],
            kAp1ToRec709[2][1], kAp1ToRec709[0][2], kAp1ToRec709[1][2], kAp1ToRec709[2][2]);
    }
    source += "    return vec4(hdhairSrgbEncode(color.rgb), color.a);\n}\n";
    return source;
}

// The shader's 3D LUTs, RGB.
void add3dTextures(const OCIO::GpuShaderDescRcPtr& description, DisplayShader& shader) {
    for (unsigned i = 0; i < description->getNum3DTextures(); ++i) {
        const char *textureName = nullptr, *samplerName = nullptr;
        unsigned edge = 0;
        OCIO::Interpolation interpolation = OCIO::INTERP_LINEAR;
        description->get3DTexture(i, textureName, samplerName, edge, interpolation);
        const float* values = nullptr;
        description->get3DTextureValues(i, values);
        DisplayShader::Texture texture;
        texture.samplerName = samplerName;
        texture.width = texture.height = texture.depth = edge;
        texture.linear = interpolation != OCIO::INTERP_NEAREST;
        texture.values.assign(values, values + size_t(3) * edge * edge * edge);
        shader.textures.push_back(std::move(texture));
    }
}

// The shader's 1D LUTs, as textures of one or more rows, red or RGB.
void add2dTextures(const OCIO::GpuShaderDescRcPtr& description, DisplayShader& shader) {
    for (unsigned i = 0; i < description->getNumTextures(); ++i) {
        const char *textureName = nullptr, *samplerName = nullptr;
        unsigned width = 0, height = 0;
        OCIO::GpuShaderDesc::TextureType channel = OCIO::GpuShaderDesc::TEXTURE_RGB_CHANNEL;
        OCIO::Interpolation interpolation = OCIO::INTERP_LINEAR;
        description->getTexture(i, textureName, samplerName, width, height, channel, interpolation);
        const float* values = nullptr;
        description->getTextureValues(i, values);
        DisplayShader::Texture texture;
        texture.samplerName = samplerName;
        texture.width = width;
        texture.height = std::max(height, 1u);
        texture.channels = channel == OCIO::GpuShaderDesc::TEXTURE_RED_CHANNEL ? 1 : 3;
        texture.linear = interpolation != OCIO::INTERP_NEAREST;
        texture.values.assign(values, values + size_t(texture.channels) * texture.width * texture.height);
        shader.textures.push_back(std::move(texture));
    }
}

// The shader's uniforms, their values as OCIO has them now; those of an
// unknown type are left out.
void addUniforms(const OCIO::GpuShaderDescRcPtr& description, DisplayShader& shader) {
    for (unsigned i = 0; i < description->getNumUniforms(); ++i) {
        OCIO::GpuShaderDesc::UniformData data;
        DisplayShader::Uniform uniform;
        uniform.name = description->getUniform(i, data);
        using Kind = DisplayShader::Uniform::Kind;
        switch (data.m_type) {
        case OCIO::UNIFORM_DOUBLE: uniform.values = {data.m_getDouble()}; break;
        case OCIO::UNIFORM_BOOL:
            uniform.kind = Kind::Bool;
            uniform.values = {data.m_getBool() ? 1.0 : 0.0};
            break;
        case OCIO::UNIFORM_FLOAT3: {
            uniform.kind = Kind::Float3;
            const OCIO::Float3& value = data.m_getFloat3();
            uniform.values = {value[0], value[1], value[2]};
            break;
        }
        case OCIO::UNIFORM_VECTOR_FLOAT: {
            uniform.kind = Kind::FloatArray;
            const float* values = data.m_vectorFloat.m_getVector();
            uniform.values.assign(values, values + data.m_vectorFloat.m_getSize());
            break;
        }
        case OCIO::UNIFORM_VECTOR_INT: {
            uniform.kind = Kind::IntPairArray;
            const int* values = data.m_vectorInt.m_getVector();
            uniform.values.assign(values, values + 2 * data.m_vectorInt.m_getSize());
            break;
        }
        case OCIO::UNIFORM_UNKNOWN: continue;
        }
        shader.uniforms.push_back(std::move(uniform));
    }
}

}  // namespace

DisplayShader DisplayTransform::shader() const {
    DisplayShader shader;
    if (mode_ == ColorCorrectionMode::Disabled) {
        shader.source = "vec4 hdhairDisplay(vec4 color) { return color; }\n";
        return shader;
    }
    if (mode_ == ColorCorrectionMode::SRGB) {
        shader.source = srgbDisplaySource(fromAcesCg_);
        return shader;
    }
    OCIO::GpuShaderDescRcPtr description = OCIO::GpuShaderDesc::CreateShaderDesc();
    description->setLanguage(OCIO::GPU_LANGUAGE_GLSL_4_0);
    description->setFunctionName("hdhairDisplay");
    description->setResourcePrefix("hdhairOcio");
    ocio_->processor->getDefaultGPUProcessor()->extractGpuShaderInfo(description);
    shader.source = description->getShaderText();
    add3dTextures(description, shader);
    add2dTextures(description, shader);
    addUniforms(description, shader);
    return shader;
}

nlohmann::json DisplayTransform::describe() const {
    nlohmann::json json = {{"mode", toString(mode_)}, {"colorSpace", colorSpace_}};
    if (mode_ == ColorCorrectionMode::OpenColorIO) {
        json["config"] = configPath_;
        json["display"] = display_;
        json["view"] = view_;
        json["look"] = look_;
    }
    return json;
}

std::string DisplayTransform::summary() const {
    if (mode_ == ColorCorrectionMode::OpenColorIO)
        return fmt::format("OCIO {} / {}{} from {} ({})", display_, view_, look_.empty() ? "" : " + look " + look_,
                           colorSpace_, configPath_);
    return fmt::format("{} from {}", toString(mode_), colorSpace_);
}

}  // namespace hdhair
