#!/usr/bin/env python3
"""The strand pass drawn by the hardware rasteriser and by the compute
rasteriser (strandRaster=hardware|compute), side by side on the TressFX bear
and Ratboy at each complexity asked for, in one run.

Each configuration renders --frames frames of the stage in one hdhair-record
process (the embedded reader, GL timer queries: passTimings=true) and reports
the median strand pass over the frames after the first (which compiles its
programs), the whole frame's median, and how busy each thread of the process
was over frames 2 onwards: its CPU time (utime + stime from
/proc/PID/task/TID/stat, sampled every 10 ms from when the first frame's image
appears to the process's end) over that wall time, by role (thread_roles).
The configurations run in turn, --runs times, and the table gives medians.

  scripts/strand-raster-bench.py [--build DIR] [--assets DIR] [--out DIR] [--stages ratboy,bear]
                                 [--complexities low,high] [--width 1280] [--frames 6] [--runs 1]

Writes strand-raster.md (the table docs/performance.md shows) and
strand-raster.csv into --out (default BUILD/strand-raster). Runs on a shared
machine vary by 20 % and more: read the compute/hardware ratios.
"""

import argparse
import csv
import datetime
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
TFX = {"ratboy": "ratboy/Ratboy_mohawk.tfx", "bear": "bear/bear.tfx"}


def fail(message):
    print(f"strand-raster-bench: error: {message}", file=sys.stderr)
    sys.exit(1)


def clock_ticks():
    return os.sysconf(os.sysconf_names["SC_CLK_TCK"])


def sample_threads(pid, seen):
    """CPU ticks (utime + stime) of each live thread of pid, by thread id, into seen."""
    try:
        tids = os.listdir(f"/proc/{pid}/task")
    except FileNotFoundError:
        return
    for tid in tids:
        try:
            with open(f"/proc/{pid}/task/{tid}/stat") as stat:
                text = stat.read()
            with open(f"/proc/{pid}/task/{tid}/comm") as comm:
                name = comm.read().strip()
        except (FileNotFoundError, ProcessLookupError):
            continue
        # The name in parentheses may hold spaces: fields follow its closing one.
        fields = text[text.rindex(")") + 2:].split()
        seen[tid] = (name, int(fields[11]) + int(fields[12]))


def thread_roles(seen, pid):
    """A role for each thread id: hdHair's GL thread (named hdhair-gl, it
    issues the GL calls and, on llvmpipe, runs the draws' vertex,
    tessellation and geometry stages), the compute workers llvmpipe starts
    from it (which inherit its name; later thread ids), llvmpipe's rasteriser
    threads (llvmpipe-N), the process's main thread, and the rest."""
    gl_threads = sorted((int(tid) for tid, (name, _) in seen.items() if name == "hdhair-gl"))
    roles = {}
    for tid, (name, _) in seen.items():
        if int(tid) == pid:
            roles[tid] = "main"
        elif gl_threads and int(tid) == gl_threads[0]:
            roles[tid] = "GL thread"
        elif name == "hdhair-gl":
            roles[tid] = f"compute worker {gl_threads.index(int(tid))}"
        elif name.startswith("llvmpipe"):
            roles[tid] = name
        else:
            roles[tid] = f"other ({name})"
    return roles


def run_record(record, stage, complexity, raster, width, frames, stats_path):
    command = [record, "--reader", "embedded", "--camera", "/World/main_cam", "-w", str(width), "-c", complexity,
               "--frames", f"1:{frames}", "-s", f"strandRaster={raster}", "-s", "passTimings=true",
               "--stats", stats_path, "--", stage, os.path.join(os.path.dirname(stats_path), "frame.#.exr")]
    # The thread times are taken from when the first frame's image appears
    # (written atomically: programs compiled, stage read) to the process's
    # end, so they cover frames 2 onwards.
    first_image = os.path.join(os.path.dirname(stats_path), "frame.1.exr")
    if os.path.exists(first_image):
        os.remove(first_image)
    process = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    os.set_blocking(process.stderr.fileno(), False)
    seen, first_frame, start, output = {}, None, None, b""
    while process.poll() is None:
        sample_threads(process.pid, seen)
        output += process.stderr.read() or b""
        if start is None and os.path.exists(first_image):
            start, first_frame = time.monotonic(), dict(seen)
        time.sleep(0.01)
    wall = time.monotonic() - (start or time.monotonic())
    output += process.stderr.read() or b""
    if process.returncode != 0:
        fail(f"{' '.join(command)} failed: {output.decode(errors='replace').strip()}")
    if first_frame is None or wall <= 0.0:
        fail(f"{' '.join(command)} wrote no frame before it ended")
    with open(stats_path) as file:
        stats = json.load(file)
    strands, totals = [], []
    for frame in stats["frames"][1:]:
        if frame.get("transparency") == "opaque":
            return None  # wide opaque strands: the opaque path, which the compute rasteriser never takes
        if frame.get("strandRaster") != raster:
            fail(f"{stage} {complexity}: strandRaster={raster} rendered {frame.get('strandRaster')}")
        strands.append(sum(p["milliseconds"] for p in frame["passes"] if p["name"] == "strands"))
        totals.append(frame["totalMilliseconds"])
    # Threads by name, busiest first, as a share of the wall time.
    by_name = {}
    roles = thread_roles(seen, process.pid)
    for tid, (name, ticks) in seen.items():
        ticks -= first_frame.get(tid, (name, 0))[1]
        by_name.setdefault(roles[tid], []).append(ticks / clock_ticks() / wall)
    load = sorted(((name, share) for name, shares in by_name.items() for share in shares),
                  key=lambda item: -item[1])
    return statistics.median(strands), statistics.median(totals), wall, load


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", default=os.path.join(ROOT, "build"))
    parser.add_argument("--assets", default=None, help="converted stages (default BUILD/strand-raster/assets)")
    parser.add_argument("--out", default=None)
    parser.add_argument("--data", default=os.path.join(ROOT, "..", "shared", "data", "tressfx"))
    parser.add_argument("--stages", default="ratboy,bear")
    parser.add_argument("--complexities", default="low,high")
    parser.add_argument("--width", type=int, default=1280)
    parser.add_argument("--frames", type=int, default=6)
    parser.add_argument("--runs", type=int, default=1)
    args = parser.parse_args()
    if args.frames < 2:
        fail("--frames must be at least 2: the first frame compiles the programs and is not counted")
    record = os.path.join(args.build, "bin", "hdhair-record")
    convert = os.path.join(args.build, "bin", "hdhair-convert")
    for tool in (record, convert):
        if not os.access(tool, os.X_OK):
            fail(f"no {tool} (cmake --build {args.build} --target hdhair-record hdhair-convert)")
    out = args.out or os.path.join(args.build, "strand-raster")
    assets = args.assets or os.path.join(out, "assets")
    os.makedirs(assets, exist_ok=True)
    stages = [s for s in args.stages.split(",") if s]
    complexities = [c for c in args.complexities.split(",") if c]
    for stage in stages:
        if stage not in TFX:
            fail(f"--stages: '{stage}' is not one of {', '.join(TFX)}")
        tfx = os.path.join(args.data, TFX[stage])
        usda = os.path.join(assets, stage + ".usda")
        if not os.path.exists(tfx):
            fail(f"missing {tfx} (--data names the TressFX folder)")
        if not os.path.exists(usda) or os.path.getmtime(usda) < os.path.getmtime(tfx):
            subprocess.run([convert, tfx, usda], check=True, stdout=subprocess.DEVNULL)

    rows = {}
    with tempfile.TemporaryDirectory() as scratch:
        stats_path = os.path.join(scratch, "stats.json")
        for run in range(args.runs):
            for stage in stages:
                for complexity in complexities:
                    for raster in ("hardware", "compute"):
                        print(f"run {run + 1}/{args.runs}: {stage} {complexity} {raster}", file=sys.stderr)
                        result = run_record(record, os.path.join(assets, stage + ".usda"), complexity, raster,
                                            args.width, args.frames, stats_path)
                        rows.setdefault((stage, complexity, raster), []).append(result)

    def median(key, index):
        return statistics.median(result[index] for result in rows[key])

    def load_text(key):
        # The run whose strand pass was the median one.
        results = sorted(rows[key], key=lambda result: result[0])
        load = results[len(results) // 2][3]
        busy = [f"{name} {share:.0%}" for name, share in load if share >= 0.05]
        return ", ".join(busy) + f" (sum {sum(share for _, share in load):.2f} cores)"

    os.makedirs(out, exist_ok=True)
    cpus = os.cpu_count()
    when = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    lines = [f"Measured {when} on {cpus} cores, {args.width} px wide, frames 2-{args.frames} of one process each "
             f"(GL timer queries), median of {args.runs} run(s) taken in turn.", "",
             "| stage | complexity | strand pass: hardware | compute | compute/hardware | frame: hardware | compute "
             "| thread load, hardware (CPU time / wall time) | thread load, compute |",
             "|---|---|---|---|---|---|---|---|---|"]
    with open(os.path.join(out, "strand-raster.csv"), "w", newline="") as file:
        writer = csv.writer(file)
        writer.writerow(["stage", "complexity", "raster", "run", "strandMs", "frameMs", "wallS", "threadLoad"])
        for (stage, complexity, raster), results in rows.items():
            for run, (strand, frame, wall, load) in enumerate(r for r in results if r is not None):
                writer.writerow([stage, complexity, raster, run + 1, f"{strand:.2f}", f"{frame:.2f}", f"{wall:.2f}",
                                 ";".join(f"{name}={share:.3f}" for name, share in load)])
    for stage in stages:
        for complexity in complexities:
            hardware, compute = (stage, complexity, "hardware"), (stage, complexity, "compute")
            if any(result is None for result in rows[hardware] + rows[compute]):
                lines.append(f"| {stage} | {complexity} | opaque path (every strand opaque and at least "
                             "minPixelWidth wide): no compute rasteriser | | | | | | |")
                continue
            lines.append(f"| {stage} | {complexity} | {median(hardware, 0):.0f} ms | {median(compute, 0):.0f} ms | "
                         f"{median(compute, 0) / median(hardware, 0):.2f}x | {median(hardware, 1):.0f} ms | "
                         f"{median(compute, 1):.0f} ms | {load_text(hardware)} | {load_text(compute)} |")
    text = "\n".join(lines) + "\n"
    with open(os.path.join(out, "strand-raster.md"), "w") as file:
        file.write(text)
    print(text)


if __name__ == "__main__":
    main()
