#!/usr/bin/python3
"""What a studio deploys, used from where it was deployed (cmake/Install.cmake).

- `cmake --install` into a temporary prefix: hdhair-record renders from there
  the same pixels the build tree's does, and hdhair-convert converts an asset
  that the installed hdhair-record then renders;
- with OpenUSD: usdrecord loads the installed plugin and the HdHairAPI schema
  with PXR_PLUGINPATH_NAME naming only <prefix>/plugin/usd, and the
  installed hdhair-record's default reader (OpenUSD) finds the installed
  plugin beside itself;
- without OpenUSD: the Debian package CPack makes holds what README says,
  depends on Debian packages only, and its hdhair-record renders once
  extracted (dpkg-deb -x; it is never installed on the machine).

CTest sets HDHAIR_BUILD_DIR, HDHAIR_SOURCE_DIR, HDHAIR_CMAKE, HDHAIR_CPACK,
HDHAIR_WITH_USD and, with OpenUSD, HDHAIR_PXR_BIN and PYTHONPATH.
"""
import os
import re
import shutil
import struct
import subprocess
import tempfile
import unittest

BUILD = os.environ["HDHAIR_BUILD_DIR"]
SOURCE = os.environ["HDHAIR_SOURCE_DIR"]
CMAKE = os.environ["HDHAIR_CMAKE"]
CPACK = os.environ["HDHAIR_CPACK"]
WITH_USD = os.environ.get("HDHAIR_WITH_USD") == "1"
STAGE = os.path.join(SOURCE, "examples", "straight_strands.usda")
DOCS = "share/doc/hdhair/docs/"


def readmeDocLinks(readme):
    """The files under docs/ that a README links to, without anchors."""
    with open(readme, encoding="utf-8") as text:
        return sorted(set(re.findall(r"\]\((docs/[^)#\s]+)", text.read())))


def run(command, environment=None, cwd=None):
    """Runs a command; fails the test with its output when it fails."""
    result = subprocess.run(command, capture_output=True, text=True, env=environment, cwd=cwd)
    if result.returncode != 0:
        raise AssertionError("%s exited %d:\n%s%s" % (" ".join(command), result.returncode, result.stdout,
                                                      result.stderr))
    return result.stdout + result.stderr


def idiffAgree(a, b, threshold):
    """OpenImageIO's idiff (openimageio-tools): no pixel more than `threshold` apart."""
    result = subprocess.run(["idiff", "-fail", str(threshold), "-warn", str(threshold), a, b],
                            capture_output=True, text=True)
    return result.returncode == 0, result.stdout + result.stderr


def coveredPixels(path):
    """Pixels with alpha above 1e-6: oiiotool scales alpha up and clamps it
    to 1, so the mean times the pixel count counts them."""
    out = run(["oiiotool", path, "--ch", "A", "--mulc", "1e6", "--clamp:min=0:max=1", "--printstats"])
    lines = out.splitlines()
    width, height = (int(v) for v in lines[0].split(",")[0].split(":")[-1].split("x"))
    average = next(float(line.split(":")[1].split()[0]) for line in lines if "Stats Avg" in line)
    return round(average * width * height)


def writeYukselHair(path):
    """A two-strand Cem Yuksel .hair file: 128-byte header, then points."""
    hairs, segments = 2, 3
    points = hairs * (segments + 1)
    header = b"HAIR" + struct.pack("<IIII", hairs, points, 1 << 1, segments)
    header += struct.pack("<ff3f", 0.05, 0.0, 0.4, 0.25, 0.1)
    header += b"install test".ljust(88, b"\0")
    assert len(header) == 128
    body = b""
    for h in range(hairs):
        for s in range(segments + 1):
            body += struct.pack("<3f", 0.3 * h, 0.3 * s, 0.05 * s * s)
    with open(path, "wb") as f:
        f.write(header + body)


class InstallPrefix(unittest.TestCase):
    def setUp(self):
        self.work = tempfile.mkdtemp(prefix="hdhair-install-")
        self.prefix = os.path.join(self.work, "prefix")

    def tearDown(self):
        shutil.rmtree(self.work)

    def install(self, component=None):
        command = [CMAKE, "--install", BUILD, "--prefix", self.prefix]
        if component:
            command += ["--component", component]
        run(command)

    def test_installedToolsRenderWhatTheBuildTreeRenders(self):
        self.install("tools")
        for name in ["bin/hdhair-record", "bin/hdhair-convert", "bin/hdhair-farm", "share/doc/hdhair/README.md",
                     "share/doc/hdhair/LICENSE", "share/hdhair/ocio/config.ocio",
                     "share/hdhair/cycles/renderCyclesScene.py"]:
            self.assertTrue(os.path.isfile(os.path.join(self.prefix, name)), name)
        # The installed README's links into docs/ hold.
        links = readmeDocLinks(os.path.join(self.prefix, "share/doc/hdhair/README.md"))
        self.assertIn("docs/settings.md", links)
        for link in links:
            self.assertTrue(os.path.isfile(os.path.join(self.prefix, "share/doc/hdhair", link)), link)
        # The tools component is the tools alone.
        self.assertFalse(os.path.exists(os.path.join(self.prefix, "plugin")))
        installed, built = os.path.join(self.work, "installed.exr"), os.path.join(self.work, "built.exr")
        arguments = ["--reader", "embedded"] if WITH_USD else []
        arguments += ["--camera", "/World/main_cam", "--imageWidth", "160", STAGE]
        run([os.path.join(self.prefix, "bin", "hdhair-record")] + arguments + [installed])
        run([os.path.join(BUILD, "bin", "hdhair-record")] + arguments + [built])
        same, report = idiffAgree(installed, built, 0.0)
        self.assertTrue(same, report)
        self.assertGreater(coveredPixels(installed), 100)
        # The installed hdhair-farm checks its arguments with the hdhair-record
        # beside it: an output without '#' is refused by that check's report.
        farm = subprocess.run([os.path.join(self.prefix, "bin", "hdhair-farm"), "submit", "--frames", "1", "--"] +
                              arguments + [os.path.join(self.work, "farm.exr")], capture_output=True, text=True)
        self.assertEqual(farm.returncode, 1, farm.stderr)
        self.assertIn("has no '#' for the frame number", farm.stderr)

    def test_installedConverterFeedsTheInstalledRenderer(self):
        self.install("tools")
        hair, stage, image = (os.path.join(self.work, name) for name in ("two.hair", "two.usda", "two.png"))
        writeYukselHair(hair)
        run([os.path.join(self.prefix, "bin", "hdhair-convert"), hair, stage])
        reader = ["--reader", "embedded"] if WITH_USD else []
        run([os.path.join(self.prefix, "bin", "hdhair-record")] + reader +
            ["--camera", "/World/main_cam", "--imageWidth", "120", stage, image])
        self.assertGreater(coveredPixels(image), 20)

    @unittest.skipUnless(WITH_USD, "the plugin is built and installed only with OpenUSD")
    def test_usdrecordLoadsTheInstalledPluginAndSchemaFromThePrefixAlone(self):
        self.install()
        pluginRoot = os.path.join(self.prefix, "plugin", "usd")
        for name in ["plugInfo.json", "hdHair.so", "hdHair/resources/plugInfo.json",
                     "hdHairSchema/resources/plugInfo.json", "hdHairSchema/resources/generatedSchema.usda"]:
            self.assertTrue(os.path.isfile(os.path.join(pluginRoot, name)), name)
        environment = dict(os.environ, PXR_PLUGINPATH_NAME=pluginRoot, HOME=self.work)
        environment.pop("HDHAIR_PLUGIN_RESOURCES", None)
        theirs, ours = os.path.join(self.work, "usdrecord.exr"), os.path.join(self.work, "embedded.exr")
        run([os.path.join(os.environ["HDHAIR_PXR_BIN"], "usdrecord"), "--renderer", "HdHair", "--disableGpu",
             "--camera", "/World/main_cam", "--imageWidth", "160", STAGE, theirs], environment)
        run([os.path.join(self.prefix, "bin", "hdhair-record"), "--reader", "embedded", "--camera",
             "/World/main_cam", "--imageWidth", "160", STAGE, ours])
        # The reader-parity test's threshold: float rounding of transforms.
        same, report = idiffAgree(theirs, ours, 2.0 / 255.0)
        self.assertTrue(same, report)
        self.assertGreater(coveredPixels(theirs), 100)
        # The schema, through the same single path.
        probe = ("from pxr import Usd; import sys; "
                 "sys.exit(0 if Usd.SchemaRegistry().FindAppliedAPIPrimDefinition('HdHairAPI') else 1)")
        run(["/usr/bin/python3", "-c", probe], environment)

    @unittest.skipUnless(WITH_USD, "the plugin is built and installed only with OpenUSD")
    def test_installedRecorderFindsTheInstalledPluginBesideItself(self):
        self.install()
        environment = dict(os.environ, HOME=self.work)
        environment.pop("HDHAIR_PLUGIN_RESOURCES", None)
        environment.pop("PXR_PLUGINPATH_NAME", None)
        # Moving the prefix proves the plugin is found relative to the
        # executable, not at a path compiled in.
        moved = os.path.join(self.work, "moved")
        shutil.move(self.prefix, moved)
        image = os.path.join(self.work, "usd.exr")
        output = run([os.path.join(moved, "bin", "hdhair-record"), "--reader", "usd", "--verbose", "--camera",
                      "/World/main_cam", "--imageWidth", "160", STAGE, image], environment)
        self.assertGreater(coveredPixels(image), 100, output)


@unittest.skipIf(WITH_USD, "the Debian package is made from a build without OpenUSD")
class DebianPackage(unittest.TestCase):
    def setUp(self):
        self.work = tempfile.mkdtemp(prefix="hdhair-deb-")

    def tearDown(self):
        shutil.rmtree(self.work)

    def test_packageHoldsTheToolsAndTheirExtractedRendererWorks(self):
        run([CPACK, "-G", "DEB", "-B", self.work, "--config", os.path.join(BUILD, "CPackConfig.cmake")])
        packages = [name for name in os.listdir(self.work) if name.endswith(".deb")]
        self.assertEqual(len(packages), 1, packages)
        self.assertTrue(packages[0].startswith("hdhair-tools_"), packages[0])
        deb = os.path.join(self.work, packages[0])
        files = sorted(line.split()[-1] for line in run(["dpkg-deb", "-c", deb]).splitlines()
                       if not line.startswith("d"))
        # The documentation README links to, beside it; the rest exactly.
        docs = [name for name in files if name.startswith("./usr/" + DOCS)]
        for link in readmeDocLinks(os.path.join(SOURCE, "README.md")):
            self.assertIn("./usr/share/doc/hdhair/" + link, docs)
        files = [name for name in files if name not in docs]
        self.assertEqual(files, ["./usr/bin/hdhair-convert", "./usr/bin/hdhair-farm", "./usr/bin/hdhair-record",
                                 "./usr/share/doc/hdhair/LICENSE", "./usr/share/doc/hdhair/README.md",
                                 "./usr/share/hdhair/cycles/renderCyclesScene.py",
                                 "./usr/share/hdhair/ocio/config.ocio"])
        depends = run(["dpkg-deb", "-f", deb, "Depends"])
        for package in ["libopenimageio", "libtbb", "libegl-mesa0", "libgl1-mesa-dri"]:
            self.assertIn(package, depends)
        self.assertNotIn("usd", depends.lower())
        root = os.path.join(self.work, "root")
        run(["dpkg-deb", "-x", deb, root])
        image = os.path.join(self.work, "deb.png")
        # OCIO through the config the package carries beside its binary.
        environment = dict(os.environ)
        environment.pop("OCIO", None)
        run([os.path.join(root, "usr", "bin", "hdhair-record"), "--camera", "/World/main_cam", "--imageWidth",
             "120", "--colorCorrectionMode", "openColorIO", "--ocioView", "ACES 1.0 SDR-video", STAGE, image],
            environment)
        self.assertGreater(coveredPixels(image), 50)


if __name__ == "__main__":
    unittest.main(verbosity=2)
