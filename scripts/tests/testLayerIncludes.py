#!/usr/bin/python3
"""No folder of hdHair/ includes from a folder above it.

The layers are hdHair/CMakeLists.txt's `foreach(layer ...)` list, lowest
first: a layer's files (its tests too) include only headers of its own layer
and of the layers before it. Prints each include that breaks that, with its
file and line, and exits 1 when there is one; 0 with a count otherwise.
"""
import pathlib
import re
import sys

root = pathlib.Path(__file__).resolve().parents[2]
cmake = (root / "hdHair" / "CMakeLists.txt").read_text()
match = re.search(r"foreach\(layer ([^)]*)\)", cmake)
if not match:
    print("testLayerIncludes: no foreach(layer ...) list in hdHair/CMakeLists.txt")
    sys.exit(1)
layers = match.group(1).split()
rank = {layer: i for i, layer in enumerate(layers)}
include = re.compile(r'^\s*#\s*include\s+"hdHair/([^/"]+)/')
problems, checked = [], 0
for layer in layers:
    folder = root / "hdHair" / layer
    if not folder.is_dir():
        print(f"testLayerIncludes: the layer list names {layer}, which is no folder of hdHair/")
        sys.exit(1)
    for path in sorted(folder.rglob("*")):
        if path.suffix not in (".h", ".cpp", ".hpp", ".inl"):
            continue
        for number, line in enumerate(path.read_text(errors="replace").splitlines(), 1):
            found = include.match(line)
            if not found:
                continue
            checked += 1
            target = found.group(1)
            if target not in rank:
                problems.append(f"{path.relative_to(root)}:{number}: includes hdHair/{target}/, which is no layer")
            elif rank[target] > rank[layer]:
                problems.append(f"{path.relative_to(root)}:{number}: {layer}/ includes from {target}/, a layer above it")
for problem in problems:
    print(problem)
folders = {p.name for p in (root / "hdHair").iterdir() if p.is_dir()}
for folder in sorted(folders - set(layers)):
    print(f"testLayerIncludes: hdHair/{folder}/ is in no layer of hdHair/CMakeLists.txt")
    problems.append(folder)
print(f"testLayerIncludes: {checked} includes in {len(layers)} layers, {len(problems)} upward")
sys.exit(1 if problems else 0)
