#!/usr/bin/python3
"""How long an interactive host waits for hdHair: time to the first image and
to the converged (full) frame, through the HdHair Hydra plugin, driven as
usdview drives it (UsdImagingGL, one Render every 5 ms until IsConverged).

For each stage, through its /World/main_cam (or the first camera) at
--imageWidth pixels:
  open   the first view: the plugin creates its GL context and compiles its
         shaders, and has no frame time yet, so no preview;
  move   the camera orbits the stage by --orbit degrees once: a preview (when
         the full frame is over interactiveBudgetMs), then the full frame;
  stop   the camera moves again half-way through a full frame (half of the
         time from the move's first image to its convergence): how soon the
         new view's first image comes (the full frame in flight is stopped at
         its next pass or piece of 2,048 segments), and converged;
  drag   the camera swings 10 degrees either side of the move, a step every
         --dragStepMs for --dragSeconds:
         how many images were shown while it moved, the longest wait between
         them, and the time from the last move to the converged frame.
Prints a Markdown table and the machine's state (cores, load, GL renderer).

Run with OpenUSD's Python modules and the plugin on the paths, e.g.
  PYTHONPATH=/opt/usd-24.08/lib/python \\
  PXR_PLUGINPATH_NAME=$PWD/build/plugin/usd/hdHair/resources \\
  /usr/bin/python3 scripts/interactive-timings.py examples/*.usda
"""

import argparse
import json
import math
import os
import time

from pxr import CameraUtil, Gf, Usd, UsdGeom, UsdImagingGL

PAUSE_SECONDS = 0.005  # usdview's re-render interval while not converged


def stage_camera(stage):
    prim = stage.GetPrimAtPath("/World/main_cam")
    if not prim or not prim.IsA(UsdGeom.Camera):
        prim = next((p for p in stage.Traverse() if p.IsA(UsdGeom.Camera)), None)
    if prim is None:
        raise SystemExit(f"{stage.GetRootLayer().identifier}: no camera")
    return UsdGeom.Camera(prim).GetCamera(Usd.TimeCode.EarliestTime())


def orbited(camera, centre, degrees):
    """The camera turned `degrees` about the vertical axis through `centre`."""
    moved = Gf.Camera(camera)
    turn = (Gf.Matrix4d().SetTranslate(-centre) * Gf.Matrix4d().SetRotate(Gf.Rotation(Gf.Vec3d(0, 1, 0), degrees))
            * Gf.Matrix4d().SetTranslate(centre))
    moved.transform = camera.transform * turn
    return moved


class Host:
    def __init__(self, stage, width, budget_ms):
        self.stage = stage
        parameters = UsdImagingGL.Engine.Parameters()
        parameters.gpuEnabled = False
        self.engine = UsdImagingGL.Engine(parameters)
        if not self.engine.SetRendererPlugin("HdHairRendererPlugin"):
            raise SystemExit("the HdHair plugin is not on PXR_PLUGINPATH_NAME")
        if budget_ms is not None:
            self.engine.SetRendererSetting("interactiveBudgetMs", budget_ms)
        self.camera = stage_camera(stage)
        aspect = self.camera.aspectRatio or 1.0
        self.size = (width, max(1, int(width / aspect)))  # usdrecord's height rule
        self.engine.SetRenderBufferSize(Gf.Vec2i(*self.size))
        self.engine.SetFraming(CameraUtil.Framing(Gf.Rect2i(Gf.Vec2i(0, 0), *self.size)))
        self.params = UsdImagingGL.RenderParams()
        self.params.frame = Usd.TimeCode.EarliestTime()
        self.params.clearColor = Gf.Vec4f(0, 0, 0, 0)

    def look_through(self, camera):
        frustum = camera.frustum
        self.engine.SetCameraState(frustum.ComputeViewMatrix(), frustum.ComputeProjectionMatrix())

    def images_shown(self):
        stats = self.engine.GetRenderStats()
        return stats.get("hdHairPreviews", 0) + stats.get("hdHairFullFrames", 0)

    def render(self):
        self.engine.Render(self.stage.GetPseudoRoot(), self.params)
        return self.engine.IsConverged()

    def until_converged(self, start):
        """Seconds from `start` to the first new image and to convergence."""
        before, first = self.images_shown(), None
        while True:
            converged = self.render()
            if first is None and self.images_shown() > before:
                first = time.monotonic() - start
            if converged:
                return first, time.monotonic() - start
            time.sleep(PAUSE_SECONDS)


def measure(path, args):
    stage = Usd.Stage.Open(path)
    host = Host(stage, args.imageWidth, args.budget)
    bounds = UsdGeom.BBoxCache(Usd.TimeCode.EarliestTime(), ["default", "render", "proxy"])
    centre = bounds.ComputeWorldBound(stage.GetPseudoRoot()).ComputeAlignedRange().GetMidpoint()
    row = {"stage": os.path.basename(path), "size": "%dx%d" % host.size}

    start = time.monotonic()
    host.look_through(host.camera)
    row["open"] = host.until_converged(start)

    start = time.monotonic()
    host.look_through(orbited(host.camera, centre, args.orbit))
    row["move"] = host.until_converged(start)

    # A move while a full frame renders: the move's preview, then into its
    # full frame, then the next move.
    host.look_through(orbited(host.camera, centre, args.orbit - 5.0))
    shown = host.images_shown()
    while host.images_shown() == shown:  # the preview (or the full frame, when there is none)
        host.render()
        time.sleep(PAUSE_SECONDS)
    into = time.monotonic() + (row["move"][1] - (row["move"][0] or 0.0)) / 2.0
    while time.monotonic() < into and not host.render():
        time.sleep(PAUSE_SECONDS)
    cancelled = host.engine.GetRenderStats().get("hdHairCancelledFrames", 0)
    start = time.monotonic()
    host.look_through(orbited(host.camera, centre, args.orbit - 10.0))
    row["stop"] = host.until_converged(start)
    row["stopped"] = host.engine.GetRenderStats().get("hdHairCancelledFrames", 0) - cancelled

    # The drag: a camera move every dragStepMs, a Render every 5 ms between.
    shown_before, gaps, last_image = host.images_shown(), [], time.monotonic()
    start = time.monotonic()
    step = 0
    while time.monotonic() - start < args.dragSeconds:
        step += 1
        host.look_through(orbited(host.camera, centre, args.orbit + 10.0 * math.sin(step / 5.0)))
        step_end = time.monotonic() + args.dragStepMs / 1000.0
        while time.monotonic() < step_end:
            shown = host.images_shown()
            host.render()
            if host.images_shown() > shown:
                now = time.monotonic()
                gaps.append(now - last_image)
                last_image = now
            time.sleep(PAUSE_SECONDS)
    released = time.monotonic()
    gaps.append(released - last_image)  # waiting since the last image when the drag ends
    row["drag"] = {"moves": step, "images": host.images_shown() - shown_before, "longest_wait": max(gaps)}
    row["release"] = host.until_converged(released)[1]
    stats = host.engine.GetRenderStats()
    row["previews"] = stats.get("hdHairPreviews", 0)
    row["cancelled"] = stats.get("hdHairCancelledFrames", 0)
    row["preview"] = (stats.get("hdHairPreviewPixelDivisor", 0), stats.get("hdHairPreviewCurveStride", 0))
    frame = json.loads(stats.get("hdHairFrameStats") or "{}")
    row["gl"] = frame.get("gl", "?")
    return row


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("stages", nargs="+")
    parser.add_argument("--imageWidth", type=int, default=960)
    parser.add_argument("--budget", type=int, default=None, help="interactiveBudgetMs (default: the plugin's)")
    parser.add_argument("--orbit", type=float, default=20.0, help="degrees the 'move' turns the camera")
    parser.add_argument("--dragSeconds", type=float, default=5.0)
    parser.add_argument("--dragStepMs", type=float, default=50.0)
    args = parser.parse_args()

    load_before = os.getloadavg()
    rows = [measure(path, args) for path in args.stages]
    load_after = os.getloadavg()

    def seconds(value):
        return "-" if value is None else "%.2f s" % value

    def preview(divisor, stride):
        if divisor == 0:
            return "none"
        return "1/%d across%s" % (divisor, ", every %d. curve" % stride if stride > 1 else "")

    print("| stage | size | open: first image / converged | move %g°: first image / converged "
          "| move half-way through a full frame: first image / converged | drag %g s: images shown, longest wait "
          "| drag released: converged | previews, cancelled frames | last preview |"
          % (args.orbit, args.dragSeconds))
    print("|---|---|---|---|---|---|---|---|---|")
    for row in rows:
        print("| %s | %s | %s / %s | %s / %s | %s / %s%s | %d in %d moves, %s | %s | %d, %d | %s |" % (
            row["stage"], row["size"], seconds(row["open"][0]), seconds(row["open"][1]), seconds(row["move"][0]),
            seconds(row["move"][1]), seconds(row["stop"][0]), seconds(row["stop"][1]),
            "" if row["stopped"] else " (converged before the move)", row["drag"]["images"], row["drag"]["moves"],
            seconds(row["drag"]["longest_wait"]), seconds(row["release"]), row["previews"], row["cancelled"],
            preview(*row["preview"])))
    print()
    print("machine: %d cores, %s; load average (1 min) %.1f before, %.1f after" % (
        os.cpu_count(), rows[0]["gl"], load_before[0], load_after[0]))


if __name__ == "__main__":
    main()
