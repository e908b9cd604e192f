#!/usr/bin/python3
"""Plots of hdhair-bench --accuracy's report (hdHair/tools/AccuracyReport.h).

    /usr/bin/python3 scripts/accuracy-plots.py accuracy.json OUT_FOLDER

Writes accuracy-<stage>.png per stage (error against time: each approximation's
ladder as a line from its cheapest step toward the reference, the default
circled, the Pareto front as a dashed staircase, the quality presets labelled)
and accuracy.png, every stage side by side (the headline plot README shows).
Error is RMSE on pre-multiplied linear RGBA against the stage's reference; the
reference preset's own error (about 1e-5, the benchmark's microradian light
turn) is drawn at the axis' floor. Needs Debian's python3-matplotlib.
"""
import json
import sys

import matplotlib

matplotlib.use("Agg")  # no display: files only
import matplotlib.pyplot as plt  # noqa: E402

FLOOR = 1e-4  # the plots' least error: the reference against itself sits here


def error_of(row):
    return max(row["error"]["rmse"], FLOOR)


def draw_stage(axes, report, stage):
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
            if row["isDefault"] and not approximation["base"]:
                axes.plot(row["frame"]["medianMs"], error_of(row), "o", markersize=9, markerfacecolor="none",
                          markeredgecolor="black", linewidth=0.8)
    front = sorted((row for row in rows if row["pareto"]), key=lambda row: row["frame"]["medianMs"])
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
    axes.set_xscale("log")
    axes.set_yscale("log")
    axes.set_xlabel("frame time, median (ms)")
    axes.set_ylabel("RMSE against reference")
    axes.set_title(f"{stage['name']} ({stage['width']}x{stage['height']})", fontsize=10)
    axes.grid(True, which="both", linewidth=0.3)


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: accuracy-plots.py accuracy.json OUT_FOLDER")
    with open(sys.argv[1]) as handle:
        report = json.load(handle)
    out = sys.argv[2]
    stages = report["stages"]
    for stage in stages:
        figure, axes = plt.subplots(figsize=(7, 5))
        draw_stage(axes, report, stage)
        axes.legend(fontsize=7, loc="upper right")
        figure.tight_layout()
        figure.savefig(f"{out}/accuracy-{stage['name']}.png", dpi=110)
        plt.close(figure)
    columns = min(3, len(stages))
    rows = (len(stages) + columns - 1) // columns
    figure, grid = plt.subplots(rows, columns, figsize=(5.5 * columns, 4.2 * rows), squeeze=False)
    for index, stage in enumerate(stages):
        draw_stage(grid[index // columns][index % columns], report, stage)
    for index in range(len(stages), rows * columns):
        grid[index // columns][index % columns].axis("off")
    handles, labels = grid[0][0].get_legend_handles_labels()
    figure.legend(handles, labels, loc="lower center", ncol=6, fontsize=8)
    figure.suptitle("hdHair: error against time per approximation (each varied alone from the defaults)")
    figure.tight_layout(rect=(0, 0.06, 1, 0.97))
    figure.savefig(f"{out}/accuracy.png", dpi=100)
    plt.close(figure)
    print(f"accuracy-plots: wrote {out}/accuracy.png and {len(stages)} stage plots")


if __name__ == "__main__":
    main()
