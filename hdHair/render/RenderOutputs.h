#pragma once
// What a frame must produce besides colour and depth: the request's side of
// RenderResult (Renderer::render).

namespace hdhair {

struct DisplayShader;

// What a frame must produce besides colour and depth.
struct RenderOutputs {
    // primId, instanceId and elementId images (for Hydra's picking and
    // selection). Off by default: id attachments are made only when asked for.
    bool ids = false;
    // The display image made on the GPU through this transform
    // (RenderResult::display), un-premultiplied, or over black for formats
    // without alpha. nullptr: none (hdhair-record applies it on the CPU).
    const DisplayShader* gpuDisplay = nullptr;
    bool displayOverBlack = false;
    // The depth image read back to the CPU (RenderResult::depth). Hosts pick
    // and composite with it; a tool that writes colour only turns it off and
    // saves 4 bytes a pixel of readback.
    bool depth = true;
};

}  // namespace hdhair
