#!/usr/bin/env python3
"""Writes docs/parameters.md: every YAML parameter, its default and its valid range, by section.

Read from the sources, so the table cannot drift from the code: the keys and ranges from each
loadParams (`section.get("key", field, Range::closed(lo, hi))`, `Range::above` = open below),
the defaults from the initialisers of the struct fields. SECTIONS below says which struct each
section variable of each loader fills and where in the YAML files it lives; re-run after adding
a parameter (`python3 scripts/parameters_doc.py`). Stdlib only, but for `--check-config FILE...`
(python3-yaml): every value of a shipped config file that says it holds the built-in defaults must
equal them (a test; a drift made `radarslam localize` without its config files skip the map's
motion compensation).
"""
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SRC = os.path.join(ROOT, "libradarslam", "src")
INC = os.path.join(ROOT, "libradarslam", "include", "radarslam")

# (loader source, function or None for the only one, section variable) -> (struct, YAML paths)
SECTIONS = [
    ("radar/cartesian.cpp", None, "yaml", "CartesianParams", ["cartesian"]),
    ("frontend/odometry_params.cpp", None, "kp", "KeypointParams", ["odometry.keypoints"]),
    ("frontend/odometry_params.cpp", None, "m", "MatchParams", ["odometry.matching"]),
    ("frontend/odometry_params.cpp", None, "o", "OutlierParams", ["odometry.outliers"]),
    ("frontend/odometry_params.cpp", None, "pa", "PatchAlignParams", ["odometry.patch_alignment"]),
    ("frontend/odometry_params.cpp", None, "r", "RefineParams", ["odometry.refine"]),
    ("frontend/odometry_params.cpp", None, "k", "KeyframeParams", ["odometry.keyframes"]),
    ("frontend/odometry_params.cpp", None, "t", "TrackingParams", ["odometry.tracking"]),
    ("radar/doppler_compensation.cpp", None, "yaml", "DopplerParams", ["odometry.doppler"]),
    ("slam/slam_params.cpp", None, "slam", "SlamParams", ["slam"]),
    ("slam/slam_params.cpp", None, "lm", "LocalMappingParams", ["slam.local_mapping"]),
    ("slam/slam_params.cpp", None, "oe", "OdometryEdgeParams", ["slam.odometry_edges"]),
    ("slam/slam_params.cpp", None, "lc", "LoopClosingParams", ["slam.loop_closure"]),
    ("slam/slam_params.cpp", None, "kc", "KeyframeCullingParams", ["slam.keyframe_culling"]),
    ("radar/peak_cloud.cpp", None, "yaml", "PeakCloudParams",
     ["slam.loop_closure.peak_cloud", "localization.peak_cloud"]),
    ("loop/m2dp.cpp", None, "yaml", "M2DPParams", ["slam.loop_closure.m2dp", "localization.global.m2dp"]),
    ("loop/loop_detector.cpp", None, "yaml", "LoopDetectorParams", ["slam.loop_closure.detector"]),
    ("loop/loop_verifier.cpp", None, "yaml", "LoopVerifierParams",
     ["slam.loop_closure.verifier", "localization.global.verifier"]),
    ("backend/pose_graph.cpp", None, "yaml", "PoseGraphParams", ["slam.pose_graph"]),
    ("reloc/localizer.cpp", None, "yaml", "LocalizerParams", ["localization"]),
    ("reloc/global_localizer.cpp", None, "yaml", "GlobalLocalizerParams", ["localization.global"]),
    ("reloc/integrity.cpp", None, "yaml", "IntegrityParams", ["localization.integrity"]),
    ("reloc/map_tracker.cpp", None, "yaml", "MapTrackerParams", ["localization.tracker"]),
    ("reloc/submap_icp.cpp", "SubmapParams", "yaml", "SubmapParams", ["localization.tracker.submap"]),
    ("reloc/submap_icp.cpp", "IcpParams", "yaml", "IcpParams", ["localization.tracker.icp"]),
    ("sim/simulator.cpp", None, "y", "SimulationConfig", ["(top level)"]),
    ("sim/simulator.cpp", None, "w", "WorldParams", ["world"]),
    ("sim/simulator.cpp", None, "rw", "RouteWorldParams", ["route_world"]),
    ("sim/simulator.cpp", None, "r", "RouteParams", ["route"]),
    ("sim/radar_model.cpp", "loadGeometry", "y", "RadarGeometry", ["radar"]),
    ("sim/radar_model.cpp", "loadPhysics", "y", "RadarPhysics", ["physics"]),
    ("eval/evaluate.cpp", None, "section", "EvalParams", ["(library: EvalParams)"]),
    ("map/map_layers.cpp", None, "yaml", "MapLayerParams", ["map_layers"]),
    ("map/map_from_trajectory.cpp", None, "yaml", "KeyframeInsertionParams",
     ["(library: KeyframeInsertionParams)"]),
]

# Nested parameter structs a loader fills through a member: (struct, member) -> member's struct.
NESTED = {("LoopVerifierParams", "information"): "AlignmentInformationParams",
          ("MapLayerParams", "grid"): "GridExportParams", ("MapLayerParams", "octomap"): "OctomapExportParams",
          ("MapLayerParams", "tiling"): "GridTilingParams",
          ("RefineParams", "structure"): "StructureInformationParams"}

# Enum parameters read as strings: (struct, key) -> default shown.
ENUM_DEFAULTS = {("MapLayerParams", "octomap_fill"): '"grid_columns"'}

FILES = [
    ("Odometry and SLAM: config/<sensor>.yaml (`radarslam odometry`, `map`, `localize`)",
     lambda paths: not paths[0].startswith(("localization", "(", "world", "route", "radar", "physics"))),
    ("Localization: config/localization.yaml (`radarslam localize`)",
     lambda paths: paths[0].startswith("localization")),
    ("Simulator: config/sim.yaml (`radarslam simulate --config`)",
     lambda paths: paths[0] in ("(top level)", "world", "route_world", "route", "radar", "physics")),
    ("Library only (no shipped command reads these from a file)", lambda paths: paths[0].startswith("(library")),
]


def read(path):
    with open(path, encoding="utf-8") as f:
        return f.read()


def function_body(text, name):
    """Text of the loader function `name` (loadGeometry, or loadParams(..., NameParams&))."""
    for m in re.finditer(r"\nvoid (\w+)\(([^)]*)\) \{", text):
        if name is None and m.group(1).startswith("load") or name in (m.group(1),) or \
                (name and name + "&" in m.group(2).replace(" &", "&")):
            end = text.index("\n}\n", m.end())
            return text[m.end():end]
    raise SystemExit("no loader %s" % name)


def struct_defaults():
    """{struct: {field: (default text, comment)}} from every header."""
    out = {}
    for d, _, files in os.walk(INC):
        for fn in files:
            text = read(os.path.join(d, fn))
            for m in re.finditer(r"\nstruct (\w+) \{\n(.*?)\n\};", text, re.S):
                fields = {}
                body = re.sub(r"=\s*\n\s*", "= ", m.group(2))  # "x =\n    1.0;  ///< ..." (clang-format)
                block = []  # a "/// ..." comment block above a field without a trailing ///<
                for line in body.split("\n"):
                    if line.strip().startswith("/// "):
                        block.append(line.strip()[4:])
                        continue
                    code, _, comment = line.partition("///<")
                    if not comment.strip() and block:  # its first sentence, without the valid range
                        text = re.sub(r";?\s*valid [\[(].*$", "", " ".join(block))
                        comment = re.split(r"(?<=[a-z)])\. ", text)[0].rstrip(".")
                    block = []
                    code = code.split("//")[0].strip()
                    fm = re.match(r"[\w:<>, ]+?\s+(\w+\s*(=|\{).*);$", code)
                    if not fm or "(" in code.split("=")[0]:
                        continue
                    for decl in re.split(r",\s*(?=\w+\s*=)", fm.group(1)):
                        dm = re.match(r"(\w+)\s*(?:=\s*(.*)|(\{.*\}))$", decl.strip())
                        if dm:
                            fields[dm.group(1)] = ((dm.group(2) or dm.group(3)).strip(), comment.strip())
                out[m.group(1)] = fields
    return out


def range_text(expr):
    m = re.match(r"Range::(closed|above)\(([^,]+),\s*(.+)\)$", expr.strip())
    if not m:
        return expr
    lo, hi = (re.sub(r"\.0$", "", v.strip()) for v in (m.group(2), m.group(3)))
    return ("(" if m.group(1) == "above" else "[") + lo + ", " + hi + "]"


def number(text):
    """A default's C++ literal as a Python value (None when it is not a plain number or bool)."""
    text = text.strip().rstrip("f").replace("'", "")
    if text in ("true", "false"):
        return text == "true"
    try:
        return float(text)
    except ValueError:
        return None


def check_config(path, documented):
    """Every value of a config file that says it holds the built-in defaults equals them."""
    import yaml  # python3-yaml (scripts/install-deps.sh)
    with open(path, encoding="utf-8") as f:
        data = yaml.safe_load(f)
    wrong = []

    def walk(node, prefix):
        for key, value in node.items():
            dotted = prefix + "." + key if prefix else key
            if isinstance(value, dict):
                walk(value, dotted)
                continue
            if dotted not in documented:
                wrong.append("%s: no documented default (not read by any loader?)" % dotted)
                continue
            expected = number(documented[dotted])
            if expected is None:
                continue  # a string, an enum, a list: compared by the C++ tests where they matter
            got = value if isinstance(value, bool) else float(value)
            if got != expected:
                wrong.append("%s: %s in the file, %s built in" % (dotted, value, documented[dotted]))
    walk(data, "")
    for w in wrong:
        print("%s: %s" % (os.path.relpath(path, ROOT), w))
    return not wrong


def main():
    defaults = struct_defaults()
    by_file = {title: [] for title, _ in FILES}
    documented = {}  # dotted YAML key -> default's C++ text
    for src, func, var, struct, paths in SECTIONS:
        body = function_body(read(os.path.join(SRC, src)), func)
        rows = []
        for m in re.finditer(r"\b" + var + r"\.get\(\"(\w+)\",\s*([^;]*)\);", body):
            key, rest = m.group(1), re.sub(r"\s+", " ", m.group(2))
            parts = [p.strip() for p in re.split(r",(?![^(]*\))", rest)]
            path = parts[0].split(".")
            field = path[-1]
            rng = range_text(parts[1]) if len(parts) > 1 else "-"
            if len(parts) > 2:
                rng += " each, at most %s values" % parts[2]
            fields = defaults.get(NESTED.get((struct, path[-2]), struct) if len(path) > 2 else struct, {})
            name = field if field in fields else key if key in fields else key.replace("kitti_", "")
            if name == "step_frames" or name == "lengths_m":
                default, comment = defaults["KittiParams"].get(name, ("?", ""))
            else:
                default, comment = fields.get(name, ("?", ""))
            default = ENUM_DEFAULTS.get((struct, key), default)
            if default.startswith("static_cast"):
                default = "?"
            comment = re.sub(r";?\s*valid .*$", "", comment).strip()  # the range is its own column
            for p in paths:
                documented[key if p == "(top level)" else p + "." + key] = default
            rows.append((key, default.rstrip("f") if re.match(r"^[\d.e+-]+f$", default) else default, rng, comment))
        if not rows:
            continue
        for title, pred in FILES:
            if pred(paths):
                by_file[title].append((paths, struct, src, rows))
                break
    out = ["# Parameters", "",
           "Every parameter a YAML file can set, with its default and the values it accepts. Generated",
           "by `scripts/parameters_doc.py` from the loaders (`loadParams` in libradarslam/src) and the",
           "parameter structs (libradarslam/include): do not edit by hand, re-run the script.", "",
           "`[a, b]` is a closed range, `(a, b]` excludes `a`. A value outside its range, a value of the",
           "wrong type, NaN or an unknown key is an error naming the file and the dotted key, e.g.",
           "`radarslam: error: my.yaml: key 'odometry.keypoints.max_keypoints': 1000000000 is out of range",
           "[10, 100000]`. Keys that are absent keep the default. Cross-field rules are listed under",
           "their section. A config file must be UTF-8 text, a map at the top level (an empty file means",
           "all defaults), and nested at most 64 levels deep (docs/hardening.md).", ""]
    cross = {
        "LocalMappingParams": "`interval_keyframes` <= `window_keyframes`.",
        "PeakCloudParams": "`max_range_m` is 0 (full range) or > `min_range_m`.",
        "LoopVerifierParams": "`max_translation_m / vote_cell_m` <= 2000 (size of the Hough vote grid).",
        "IcpParams": "`max_correspondence_m` >= `inlier_distance_m`.",
        "WorldParams": "`block_max_m` >= `block_min_m`; `street_half_width_max_m` >= `street_half_width_min_m`.",
        "RouteParams": "`stop_max_s` >= `stop_min_s`.",
        "KeypointParams": "`detector` is one of orb, akaze, brisk, fast_orb.",
        "OutlierParams": "`consistency` is `distance` or `displacement`.",
        "MapLayerParams": "The layers saved with a map (`radarslam map`, `map-synth --config`, `map-layers "
                          "--config`; maps/README.md). `octomap_fill` is `grid_columns` (default: the grid's "
                          "cells as a one-voxel slab) or `point_rays` (slow).",
    }
    for title, _ in FILES:
        if not by_file[title]:
            continue
        out += ["## " + title, ""]
        for paths, struct, src, rows in by_file[title]:
            out += ["### " + ", ".join("`%s`" % p if not p.startswith("(") else p for p in paths), "",
                    "`%s`, read by libradarslam/src/%s." % (struct, src) +
                    (" " + cross[struct] if struct in cross else ""), "",
                    "| key | default | valid | meaning |", "|---|---|---|---|"]
            for key, default, rng, comment in rows:
                out.append("| `%s` | %s | %s | %s |" % (key, default.replace("|", "\\|"), rng, comment.replace("|", "\\|")))
            out.append("")
    if len(sys.argv) > 2 and sys.argv[1] == "--check-config":
        sys.exit(0 if all([check_config(p, documented) for p in sys.argv[2:]]) else 1)
    text = "\n".join(out)
    target = os.path.join(ROOT, "docs", "parameters.md")
    if len(sys.argv) > 1 and sys.argv[1] == "--check":
        sys.exit(0 if read(target) == text else "docs/parameters.md is out of date: run scripts/parameters_doc.py")
    with open(target, "w", encoding="utf-8") as f:
        f.write(text)


if __name__ == "__main__":
    main()
