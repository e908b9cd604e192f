#!/usr/bin/env python3
"""Runs usdrecord as it is, and prints how long each frame took inside it.

    python3 scripts/usdrecord-timed.py /opt/usd-24.08/bin/usdrecord [usdrecord's arguments...]

The frame is usdrecord's UsdAppUtils.FrameRecorder.Record() call: the
renderer syncing the stage, rendering until it converges, and the image
read back and written; not Python's start, OpenUSD's plugin loading or
opening the stage. Timed the same way for every renderer, so Storm's frame
and hdHair's compare (scripts/storm-comparison.sh). Each frame prints
`usdrecord-timed: frame <time code> took <milliseconds> ms` on stderr;
usdrecord's own exit status is this script's.
"""

import os
import runpy
import sys
import time


def main():
    if len(sys.argv) < 2 or not os.path.isfile(sys.argv[1]):
        print("usage: usdrecord-timed.py USDRECORD [ARGUMENTS...]", file=sys.stderr)
        return 2
    from pxr import UsdAppUtils

    record = UsdAppUtils.FrameRecorder.Record

    def timedRecord(self, stage, camera, timeCode, outputPath, *rest, **named):
        start = time.perf_counter()
        try:
            return record(self, stage, camera, timeCode, outputPath, *rest, **named)
        finally:
            milliseconds = (time.perf_counter() - start) * 1000.0
            print(f"usdrecord-timed: frame {timeCode} took {milliseconds:.1f} ms", file=sys.stderr, flush=True)

    UsdAppUtils.FrameRecorder.Record = timedRecord
    usdrecord = sys.argv[1]
    sys.argv = sys.argv[1:]
    try:
        runpy.run_path(usdrecord, run_name="__main__")
    except SystemExit as exit:
        return exit.code if isinstance(exit.code, int) else (0 if exit.code is None else 1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
