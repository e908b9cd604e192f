#!/usr/bin/python3
"""Plots of hdhair-bench --accuracy's report (hdHair/bench/AccuracyReport.h).

    /usr/bin/python3 scripts/accuracy-plots.py accuracy.json OUT_FOLDER

Writes accuracy-<stage>.png per stage (error against time: each approximation's
ladder as a line from its cheapest step toward the reference, the default
circled, the Pareto front as a dashed staircase, the quality presets labelled)
and accuracy.png, every stage side by side (the headline plot README shows).
Error is RMSE on pre-multiplied linear RGBA against the stage's reference; the
reference preset's own error (about 1e-5, the benchmark's microradian light
turn) is drawn at the axis' floor. A report with a Cycles comparison
(hdhair-bench --accuracy --cycles) also gets accuracy-cycles-<stage>.png and
accuracy-cycles.png: the same ladders against Cycles' full path tracing
(relative RMSE over blocks), its front, and two lines: Cycles' noise floor (two
seeds) and single scattering's own error against full path tracing. Needs
Debian's python3-matplotlib.
"""
import json
import sys

import matplotlib

matplotlib.use("Agg")  # no display: files only
import matplotlib.pyplot as plt  # noqa: E402

FLOOR = 1e-4  # the plots' least error: the reference against itself sits here


def own_error(row):
    return max(row["error"]["rmse"], FLOOR)


def cycles_error(row):
    return row["cycles"]["full"]["blockRmse"]


OWN = {"error": own_error, "front": "pareto", "ylabel": "RMSE against reference", "file": "accuracy"}
CYCLES = {"error": cycles_error, "front": "cyclesPareto", "ylabel": "relative block RMSE against Cycles",
          "file": "accuracy-cycles"}


def draw_stage(axes, report, stage, kind=OWN):
    error_of, front_key = kind["error"], kind["front"]
    rows = [row for row in report["rows"] if row["stage"] == stage["name"]]
    colours = plt.get_cmap("tab10")
    for index, approximation in enumerate(report["approximations"]):
        ladder = [next(r for r in rows if r["approximation"] == approximation["name"] and r["label"] == label)
                  for label in approximation["steps"]]
        xs = [row["frame"]["medianMs"] for row in ladder]
        ys = [error_of(row) for row in ladder]
        axes.plot(xs, ys, "-o", color=colours(index % 10), markersize=3, linewidth=1,
                  label=approximation["name"])
        for row in ladder:
            if row["isDefault"] and (kind is CYCLES or not approximation["base"]):
                axes.plot(row["frame"]["medianMs"], error_of(row), "o", markersize=9, markerfacecolor="none",
                          markeredgecolor="black", linewidth=0.8)
    front = sorted((row for row in rows if row.get(front_key)), key=lambda row: row["frame"]["medianMs"])
    xs, ys = [], []
    for row in front:
        if xs:
            xs.append(row["frame"]["medianMs"])
            ys.append(ys[-1])
        xs.append(row["frame"]["medianMs"])
        ys.append(error_of(row))
    axes.plot(xs, ys, "--", color="black", linewidth=1, label="Pareto front")
    for row in rows:
        if row["approximation"] != "preset":
            continue
        x, y = row["frame"]["medianMs"], error_of(row)
        axes.plot(x, y, "s", color="black", markersize=6)
        axes.annotate(row["label"].replace("quality=", ""), (x, y), textcoords="offset points", xytext=(5, 5),
                      fontsize=8, fontweight="bold")
    if kind is CYCLES:
        cycles = stage["cycles"]
        axes.axhline(cycles["noiseFloor"]["blockRmse"], color="grey", linestyle=":", linewidth=1.2,
                     label="Cycles noise floor (two seeds)")
        axes.axhline(cycles["singleAgainstFull"]["blockRmse"], color="firebrick", linestyle="-.", linewidth=1,
                     label="Cycles single scattering")
    axes.set_xscale("log")
    axes.set_yscale("log")
    axes.set_xlabel("frame time, median (ms)")
    axes.set_ylabel(kind["ylabel"])
    axes.set_title(f"{stage['name']} ({stage['width']}x{stage['height']})", fontsize=10)
    axes.grid(True, which="both", linewidth=0.3)


def draw(report, out, kind, title):
    stages = [stage for stage in report["stages"] if kind is OWN or "cycles" in stage]
    for stage in stages:
        figure, axes = plt.subplots(figsize=(7, 5))
        draw_stage(axes, report, stage, kind)
        axes.legend(fontsize=7, loc="upper right")
        figure.tight_layout()
        figure.savefig(f"{out}/{kind['file']}-{stage['name']}.png", dpi=110)
        plt.close(figure)
    columns = min(3, len(stages))
    rows = (len(stages) + columns - 1) // columns
    figure, grid = plt.subplots(rows, columns, figsize=(5.5 * columns, 4.2 * rows), squeeze=False)
    for index, stage in enumerate(stages):
        draw_stage(grid[index // columns][index % columns], report, stage, kind)
    for index in range(len(stages), rows * columns):
        grid[index // columns][index % columns].axis("off")
    handles, labels = grid[0][0].get_legend_handles_labels()
    figure.legend(handles, labels, loc="lower center", ncol=6, fontsize=8)
    figure.suptitle(title)
    figure.tight_layout(rect=(0, 0.06, 1, 0.97))
    figure.savefig(f"{out}/{kind['file']}.png", dpi=100)
    plt.close(figure)
    print(f"accuracy-plots: wrote {out}/{kind['file']}.png and {len(stages)} stage plots")


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: accuracy-plots.py accuracy.json OUT_FOLDER")
    with open(sys.argv[1]) as handle:
        report = json.load(handle)
    out = sys.argv[2]
    draw(report, out, OWN, "hdHair: error against time per approximation (each varied alone from the defaults)")
    if any("cycles" in stage for stage in report["stages"]):
        draw(report, out, CYCLES, "hdHair against Cycles' path-traced frame: error against time per approximation")


if __name__ == "__main__":
    main()
