#!/usr/bin/python3
"""The HdHairAPI schema as OpenUSD sees it (run only with OpenUSD; CTest puts
OpenUSD's Python modules on PYTHONPATH and schemas/HdHairAPI on
PXR_PLUGINPATH_NAME).

- usdGenSchema, run on schema.usda, writes exactly the checked-in
  generatedSchema.usda, and the checked-in plugInfo.json is its template with
  the paths filled in for a codeless resource plugin;
- UsdSchemaRegistry finds HdHairAPI as a single-apply API schema, with every
  property schema.usda declares, its type and allowed tokens;
- applying it to a BasisCurves prim gives the prim those properties, and the
  primvars API sees them as primvars hdHair:NAME (what Hydra hands the
  plugin).
"""
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import unittest

from pxr import Sdf, Usd, UsdGeom

SCHEMA_DIR = os.environ["HDHAIR_SCHEMA_DIR"]
USD_GEN_SCHEMA = os.environ["HDHAIR_USD_GEN_SCHEMA"]

# What schema.usda declares: name -> (type, allowed tokens or None).
EXPECTED_PROPERTIES = {
    "primvars:hdHair:shadingModel": ("token", ["kajiyaKay", "marschner", "flat"]),
    "primvars:hdHair:melanin": ("float[]", None),
    "primvars:hdHair:melaninRedness": ("float[]", None),
    "primvars:hdHair:absorption": ("color3f[]", None),
    "primvars:hdHair:eta": ("float[]", None),
    "primvars:hdHair:longitudinalShift": ("float[]", None),
    "primvars:hdHair:longitudinalWidth": ("float[]", None),
    "primvars:hdHair:kajiyaKay:diffuse": ("float[]", None),
    "primvars:hdHair:kajiyaKay:specular": ("float[]", None),
    "primvars:hdHair:kajiyaKay:shininess": ("float[]", None),
}


class GeneratedFiles(unittest.TestCase):
    def test_usdGenSchemaWritesTheCheckedInFiles(self):
        work = tempfile.mkdtemp(prefix="hdhair-usdGenSchema-")
        try:
            shutil.copy(os.path.join(SCHEMA_DIR, "schema.usda"), work)
            result = subprocess.run([sys.executable, USD_GEN_SCHEMA, "schema.usda", "."], cwd=work,
                                    capture_output=True, text=True)
            self.assertEqual(result.returncode, 0, result.stdout + result.stderr)
            with open(os.path.join(work, "generatedSchema.usda")) as generated, \
                    open(os.path.join(SCHEMA_DIR, "generatedSchema.usda")) as checkedIn:
                self.assertEqual(generated.read(), checkedIn.read(),
                                 "generatedSchema.usda is stale: run usdGenSchema schema.usda . in schemas/HdHairAPI")
            with open(os.path.join(work, "plugInfo.json")) as template:
                text = template.read()
            # A codeless schema is a resource plugin found beside its files.
            text = text.replace("@PLUG_INFO_LIBRARY_PATH@", "").replace("@PLUG_INFO_RESOURCE_PATH@", ".") \
                       .replace("@PLUG_INFO_ROOT@", ".")
            strip = lambda t: json.loads(re.sub(r"^#.*$", "", t, flags=re.M))
            with open(os.path.join(SCHEMA_DIR, "plugInfo.json")) as checkedIn:
                self.assertEqual(strip(text), strip(checkedIn.read()))
        finally:
            shutil.rmtree(work)


class Registry(unittest.TestCase):
    def test_theRegistryKnowsHdHairApiAndItsProperties(self):
        registry = Usd.SchemaRegistry()
        self.assertEqual(registry.GetSchemaKind("HdHairAPI"), Usd.SchemaKind.SingleApplyAPI)
        definition = registry.FindAppliedAPIPrimDefinition("HdHairAPI")
        self.assertIsNotNone(definition)
        self.assertEqual(sorted(definition.GetPropertyNames()), sorted(EXPECTED_PROPERTIES))
        for name, (typeName, tokens) in EXPECTED_PROPERTIES.items():
            spec = definition.GetSchemaAttributeSpec(name)
            self.assertIsNotNone(spec, name)
            self.assertEqual(str(spec.typeName), typeName, name)
            # No fallbacks: an unauthored parameter means the renderer's own value.
            self.assertFalse(spec.HasDefaultValue(), name)
            if tokens is not None:
                self.assertEqual(list(spec.allowedTokens), tokens, name)

    def test_applyingItGivesACurvesPrimItsPrimvars(self):
        stage = Usd.Stage.CreateInMemory()
        curves = UsdGeom.BasisCurves.Define(stage, "/hair")
        prim = curves.GetPrim()
        self.assertFalse(prim.HasAPI("HdHairAPI"))
        self.assertTrue(prim.ApplyAPI("HdHairAPI"))
        self.assertTrue(prim.HasAPI("HdHairAPI"))
        self.assertIn("HdHairAPI", prim.GetAppliedSchemas())
        melanin = prim.GetAttribute("primvars:hdHair:melanin")
        self.assertTrue(melanin.IsDefined())
        self.assertEqual(melanin.GetTypeName(), Sdf.ValueTypeNames.FloatArray)
        primvar = UsdGeom.PrimvarsAPI(prim).GetPrimvar("hdHair:melanin")
        self.assertTrue(primvar.IsDefined())
        primvar.Set([0.6])
        primvar.SetInterpolation(UsdGeom.Tokens.constant)
        self.assertEqual(list(UsdGeom.PrimvarsAPI(prim).GetPrimvar("hdHair:melanin").Get()), [0.6000000238418579])
        self.assertEqual(prim.GetAttribute("primvars:hdHair:shadingModel").GetMetadata("allowedTokens"),
                         ["kajiyaKay", "marschner", "flat"])


if __name__ == "__main__":
    unittest.main(verbosity=2)
