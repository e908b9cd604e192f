#!/usr/bin/env python3
"""docs/accuracy.md, "Multiple scattering": the error against Cycles' full
path tracing with multipleScattering off and dualScattering, under the
default and the high preset, for each groom and lighting, and the frame-time
ratio dualScattering / off, from the accuracy.json of runs of
scripts/accuracy-bench.sh --cycles --grooms --lighting L
--approximations multipleScattering,multipleScattering:high.

    multiple-scattering-plot.py OUT.png OUT.md LIGHTING=ACCURACY.json ...

Writes the plot and the table (markdown) it shows."""
import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

LADDERS = [("multipleScattering", "default"), ("multipleScattering:high", "high")]


def rows_of(report):
    """(stage, preset) -> {"off": row, "dualScattering": row}."""
    table = {}
    for row in report["rows"]:
        for ladder, preset in LADDERS:
            if row["approximation"] == ladder:
                table.setdefault((row["stage"], preset), {})[row["label"]] = row
    return table


def main():
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    plot_path, table_path = sys.argv[1], sys.argv[2]
    runs = []
    for argument in sys.argv[3:]:
        lighting, path = argument.split("=", 1)
        with open(path) as file:
            runs.append((lighting, json.load(file)))
    lines = ["| groom | lighting | preset | error off | error dualScattering | change | sum off | sum dual | "
             "frame dual / off (this run) |", "|---|---|---|---|---|---|---|---|---|"]
    figure, axes = plt.subplots(1, len(runs), figsize=(5 * len(runs), 4.2), sharey=True, squeeze=False)
    for axis, (lighting, report) in zip(axes[0], runs):
        table = rows_of(report)
        labels, off, dual = [], [], []
        for (stage, preset), steps in sorted(table.items()):
            if "off" not in steps or "dualScattering" not in steps:
                continue
            o, d = steps["off"], steps["dualScattering"]
            e_off, e_dual = o["cycles"]["full"]["blockRmse"], d["cycles"]["full"]["blockRmse"]
            ratio = d["frame"]["medianMs"] / o["frame"]["medianMs"]
            lines.append(f"| {stage} | {lighting} | {preset} | {e_off:.3f} | {e_dual:.3f} | "
                         f"{(e_dual - e_off) / e_off * 100:+.0f} % | {o['cycles']['full']['sumRatio']:.2f} | "
                         f"{d['cycles']['full']['sumRatio']:.2f} | {ratio:.2f} |")
            labels.append(f"{stage.replace('_', ' ')}\n{preset}")
            off.append(e_off)
            dual.append(e_dual)
        positions = range(len(labels))
        axis.bar([p - 0.2 for p in positions], off, 0.4, label="off (single scattering)", color="#999999")
        axis.bar([p + 0.2 for p in positions], dual, 0.4, label="dualScattering", color="#d08c2a")
        axis.set_xticks(list(positions))
        axis.set_xticklabels(labels, fontsize=7)
        axis.set_title(f"lighting: {lighting}")
        axis.grid(axis="y", alpha=0.3)
    axes[0][0].set_ylabel("error against Cycles, full path tracing\n(relative RMSE over 16-px blocks)")
    axes[0][0].legend(fontsize=8)
    figure.suptitle("Multiple scattering against Cycles' full path tracing, per groom and preset")
    figure.tight_layout()
    figure.savefig(plot_path, dpi=110)
    with open(table_path, "w") as file:
        file.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
