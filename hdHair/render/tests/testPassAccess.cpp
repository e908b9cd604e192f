// Each pass's code touches only the resources its FramePass declares: a
// declaration that drifts from the code would make the graph cull a pass
// something still needs, or run one nothing reads. The real passes are run
// here against plans whose declarations were cut, and must fail; every image
// test (testenv's StageRendering) runs with the same check on.

#include <algorithm>
#include <memory>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "SquareCamera.h"
#include "hdHair/base/Diagnostics.h"
#include "hdHair/gl/GlRenderThread.h"
#include "hdHair/render/FrameResources.h"
#include "hdHair/render/FrameScheduler.h"
#include "hdHair/plan/RenderPlan.h"
#include "hdHair/render/RenderResult.h"
#include "hdHair/plan/RenderSettings.h"
#include "hdHair/scene/Scene.h"

using namespace hdhair;
using hdhair::test::squareCamera;

namespace {

// `graph` again, with `kind`'s pass declaring `resource` no more.
FrameGraph withoutDeclaration(const FrameGraph& graph, PassKind kind, FrameResource resource) {
    FrameGraph cut;
    for (const FrameResource& input : graph.inputs()) cut.input(input);
    for (FramePass pass : graph.passes()) {
        if (pass.kind == kind) {
            pass.reads.erase(std::remove(pass.reads.begin(), pass.reads.end(), resource), pass.reads.end());
            pass.writes.erase(std::remove(pass.writes.begin(), pass.writes.end(), resource), pass.writes.end());
        }
        cut.add(pass);
    }
    for (const FrameResource& output : graph.outputs()) cut.output(output);
    cut.compile();
    return cut;
}

// Runs `plan`'s passes for an empty stage on the GL thread, checking each
// pass's access; the error, or "" when none.
std::string runChecked(gl::GlRenderThread& thread, FrameResources& resources, const RenderPlan& plan) {
    return thread.run([&]() -> std::string {
        const CameraView camera = squareCamera(16);
        FrameInputs inputs;
        inputs.camera = &camera;
        inputs.depthRequested = true;
        RenderResult result;
        Diagnostics diagnostics;
        FrameContext context{inputs, plan, resources, diagnostics, result, {}, nullptr, false, {}};
        context.checkAccess = true;
        try {
            runFrameGraph(context, gl::PassTiming::Off);
        } catch (const std::logic_error& error) {
            return error.what();
        }
        return "";
    });
}

}  // namespace

TEST(PassAccess, APassTouchingWhatItDoesNotDeclareFails) {
    gl::GlRenderThread thread(gl::defaultGlBackend());
    std::unique_ptr<FrameResources> resources = thread.run([] { return std::make_unique<FrameResources>(); });
    const RenderPlan plan = makeRenderPlan(Scene{}, RenderSettings{}, squareCamera(16), StrandSummary{});
    ASSERT_TRUE(plan.isEnabled("clear"));
    ASSERT_TRUE(plan.isEnabled("readback"));
    // As planned, every pass touches only what it declares.
    EXPECT_EQ(runChecked(thread, *resources, plan), "");

    // Mutation: the readback no longer declares that it reads the depth.
    const RenderPlan readsUndeclared(plan.recipe(),
                                     withoutDeclaration(plan.graph(), PassKind::Readback, ResourceKind::Depth));
    EXPECT_EQ(runChecked(thread, *resources, readsUndeclared),
              "frame graph: pass 'readback' reads 'depth', which it does not declare");

    // Mutation: the clear no longer declares that it writes the depth (nor
    // the readback that it reads it, which no pass would then provide).
    const RenderPlan writesUndeclared(
        plan.recipe(), withoutDeclaration(withoutDeclaration(plan.graph(), PassKind::Readback, ResourceKind::Depth),
                                          PassKind::Clear, ResourceKind::Depth));
    EXPECT_EQ(runChecked(thread, *resources, writesUndeclared),
              "frame graph: pass 'clear' writes 'depth', which it does not declare");

    thread.run([&] { resources.reset(); });
}
