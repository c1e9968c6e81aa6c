# SPDX-License-Identifier: GPL-3.0-or-later
"""Check the add-on zip against Blender's extension rules, without Blender.

    python3 tests/blender/check_manifest.py build/conica-blender.zip
    python3 tests/blender/check_manifest.py build/conica-blender-windows-x64.zip

Blender 4.2+ installs a zip as an extension when it holds a
blender_manifest.toml (at the top or in one folder) next to the add-on's
__init__.py; Blender 3.x installs the same zip as a legacy add-on through
bl_info. The rules are those of Blender's extension docs ("How to Create
Extensions", the manifest schema 1.0.0, "Extensions Tags"): the required
fields and their forms, the tagline (at most 64 characters, not ending in
punctuation), the permission reasons (the same), the tag and platform
names. On top, what this package promises: the manifest and bl_info agree
on the version, and the binary matches the manifest's platform (ELF
machine of a Linux .so, PE machine of a Windows .pyd).

Prints `PASS name` or `FAIL name: why` per rule and a SUMMARY line, as
tests/blender/test_addon.py does; tests/cli/blender.sh runs it.
"""
import ast
import re
import sys
import tomllib
import zipfile

RESULTS = []

REQUIRED = ("schema_version", "id", "version", "name", "tagline", "maintainer", "type",
            "blender_version_min", "license")
TYPES = ("add-on", "theme")
PLATFORMS = ("windows-x64", "windows-arm64", "macos-x64", "macos-arm64", "linux-x64")
PERMISSIONS = ("files", "network", "clipboard", "camera", "microphone")
ADDON_TAGS = ("3D View", "Add Curve", "Add Mesh", "Animation", "Bake", "Camera",
              "Compositing", "Development", "Game Engine", "Geometry Nodes",
              "Grease Pencil", "Import-Export", "Lighting", "Material", "Modeling", "Mesh",
              "Node", "Object", "Paint", "Pipeline", "Physics", "Render", "Rigging", "Scene",
              "Sculpt", "Sequencer", "System", "Text Editor", "Tracking", "User Interface",
              "UV")
SHORT_TEXT_MAX = 64  # tagline and permission reasons
SEMVER = re.compile(r"^(0|[1-9]\d*)\.(0|[1-9]\d*)\.(0|[1-9]\d*)"
                    r"(-[0-9A-Za-z.-]+)?(\+[0-9A-Za-z.-]+)?$")
# ELF e_machine of the binary for each Linux platform (x86-64: 62, AArch64: 183)
ELF_MACHINE = {"linux-x64": 62, "linux-arm64": 183}


def report(name, ok, why=""):
    RESULTS.append(ok)
    print(("PASS %s" % name) if ok else ("FAIL %s: %s" % (name, why)), flush=True)


def short_text_problem(text):
    """Why a tagline or permission reason breaks the rules, or None."""
    if not isinstance(text, str) or not text.strip():
        return "must be a non-empty string"
    if len(text) > SHORT_TEXT_MAX:
        return "%d characters, at most %d" % (len(text), SHORT_TEXT_MAX)
    if not text[-1].isalnum() and text[-1] not in ")]'\"":
        return "must not end with punctuation (%r)" % text[-1]
    return None


def version_tuple(text):
    m = re.match(r"^(\d+)\.(\d+)\.(\d+)$", text) if isinstance(text, str) else None
    return tuple(int(x) for x in m.groups()) if m else None


def check_manifest(man):
    missing = [k for k in REQUIRED if k not in man]
    report("manifest_required_fields", not missing, "missing: %s" % ", ".join(missing))
    report("manifest_schema_version", man.get("schema_version") == "1.0.0",
           repr(man.get("schema_version")))
    ident = man.get("id", "")
    report("manifest_id", isinstance(ident, str) and ident.isidentifier() and
           not ident.startswith("_") and not ident.endswith("_") and "__" not in ident,
           "%r is not an identifier without leading, trailing or double underscores" % ident)
    report("manifest_version_semver", bool(SEMVER.match(str(man.get("version", "")))),
           repr(man.get("version")))
    for key in ("name", "maintainer"):
        v = man.get(key)
        report("manifest_%s" % key, isinstance(v, str) and v.strip() != "", repr(v))
    why = short_text_problem(man.get("tagline"))
    report("manifest_tagline", why is None, "tagline %r: %s" % (man.get("tagline"), why))
    report("manifest_type", man.get("type") in TYPES, repr(man.get("type")))
    vmin = version_tuple(man.get("blender_version_min"))
    report("manifest_blender_version_min", vmin is not None and vmin >= (4, 2, 0),
           "%r: must be X.Y.Z and at least 4.2.0" % man.get("blender_version_min"))
    if "blender_version_max" in man:
        vmax = version_tuple(man["blender_version_max"])
        report("manifest_blender_version_max", vmax is not None and vmin is not None and
               vmax > vmin, repr(man["blender_version_max"]))
    lic = man.get("license")
    report("manifest_license", isinstance(lic, list) and lic != [] and
           all(isinstance(x, str) and x.startswith("SPDX:") and len(x) > 5 for x in lic),
           "%r: a list of SPDX:identifier strings" % (lic,))
    plats = man.get("platforms")
    if plats is not None:
        report("manifest_platforms", isinstance(plats, list) and plats != [] and
               all(p in PLATFORMS for p in plats), "%r not among %s" % (plats, PLATFORMS))
    tags = man.get("tags", [])
    allowed = ADDON_TAGS if man.get("type") == "add-on" else ()
    bad = [t for t in tags if t not in allowed] if isinstance(tags, list) else [tags]
    report("manifest_tags", not bad, "unknown tags %r" % bad)
    perms = man.get("permissions", {})
    problems = []
    if not isinstance(perms, dict):
        problems.append("permissions must be a table of name = reason")
    else:
        for k, reason in perms.items():
            if k not in PERMISSIONS:
                problems.append("unknown permission %r" % k)
            why = short_text_problem(reason)
            if why:
                problems.append("reason for %s: %s" % (k, why))
    report("manifest_permissions", not problems, "; ".join(problems))
    known = set(REQUIRED) | {"website", "tags", "blender_version_max", "copyright",
                             "platforms", "wheels", "permissions", "build"}
    report("manifest_no_unknown_fields", set(man) <= known,
           "unknown: %s" % sorted(set(man) - known))


def bl_info_of(source):
    for node in ast.parse(source).body:
        if isinstance(node, ast.Assign) and any(
                isinstance(t, ast.Name) and t.id == "bl_info" for t in node.targets):
            return ast.literal_eval(node.value)
    return None


def main(path):
    with zipfile.ZipFile(path) as z:
        names = z.namelist()
        tops = {n.split("/", 1)[0] for n in names}
        report("zip_one_folder", tops == {"conica"}, "top-level entries %s" % sorted(tops))
        man_name, init_name = "conica/blender_manifest.toml", "conica/__init__.py"
        report("zip_manifest_next_to_init", man_name in names and init_name in names,
               "zip holds %s" % names)
        if man_name not in names or init_name not in names:
            return
        man = tomllib.loads(z.read(man_name).decode("utf-8"))
        check_manifest(man)
        info = bl_info_of(z.read(init_name).decode("utf-8"))
        report("legacy_bl_info", isinstance(info, dict) and
               all(k in info for k in ("name", "blender", "version", "category")),
               "bl_info %r" % (info,))
        if isinstance(info, dict):
            report("manifest_version_is_bl_info_version",
                   version_tuple(man.get("version")) == tuple(info.get("version", ())),
                   "%r vs %r" % (man.get("version"), info.get("version")))
        bins = [n for n in names if n.startswith("conica/_conica.")]
        report("zip_one_stable_abi_binary", bins in (["conica/_conica.abi3.so"],
                                                     ["conica/_conica.pyd"]),
               "binaries %s" % bins)
        plats = man.get("platforms") or []
        if bins == ["conica/_conica.abi3.so"]:
            head = z.read(bins[0])[:20]
            machine = int.from_bytes(head[18:20], "little") if head[:4] == b"\x7fELF" else None
            want = [ELF_MACHINE.get(p) for p in plats]
            if machine is not None:
                report("binary_matches_platform", len(plats) == 1 and machine in want,
                       "ELF machine %s, manifest platforms %s" % (machine, plats))
            else:  # a Mach-O module of a macOS build
                report("binary_matches_platform", len(plats) == 1 and
                       plats[0].startswith("macos-"), "not ELF, platforms %s" % plats)
        elif bins == ["conica/_conica.pyd"]:
            machine = pe_machine(z.read(bins[0]))
            want = [PE_MACHINE.get(p) for p in plats]
            report("binary_matches_platform", len(plats) == 1 and machine is not None and
                   machine in want, "PE machine %s, manifest platforms %s" % (machine, plats))


# PE/COFF Machine of the DLL for each Windows platform (AMD64, ARM64)
PE_MACHINE = {"windows-x64": 0x8664, "windows-arm64": 0xAA64}


def pe_machine(data):
    """The COFF Machine field of a PE image (a .pyd is a DLL), or None."""
    if data[:2] != b"MZ" or len(data) < 0x40:
        return None
    off = int.from_bytes(data[0x3C:0x40], "little")
    if data[off:off + 4] != b"PE\0\0":
        return None
    return int.from_bytes(data[off + 4:off + 6], "little")


if __name__ == "__main__":
    try:
        main(sys.argv[1])
    except Exception as exc:  # noqa: BLE001 - a broken zip is a failure, not a crash
        report("manifest_readable", False, "%s: %s" % (type(exc).__name__, exc))
    print("SUMMARY %d passed, %d failed" % (RESULTS.count(True), RESULTS.count(False)))
