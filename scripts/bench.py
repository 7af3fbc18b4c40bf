#!/usr/bin/env python3
"""The accuracy benchmark (issue 13, item 5): odometry, SLAM and relocalisation over the fixed
list of simulated sequences in config/bench/sequences.yaml, split into train and test.

    scripts/bench.py [--split test|train|all] [--reduced] [--only NAME] [--out out/bench]
                     [--radarslam build/apps/radarslam] [--check]

--reduced runs each sequence's `ci_scans` (sequences with ci_scans 0 are left out); CI runs
`--reduced --check --baseline config/bench/baseline_reduced.json`. Every run reports (as
"VIOLATION" lines) what must always hold and does not yet: SLAM's KITTI errors and ATE no worse than its
own odometry's, no false loop left in the graph, no relocalised scan reported as tracking or
global_fix more than 2 m / 2 deg off the map (also when started from scratch at 10 evenly spaced
scans, `localize --first N --count 10`, which measures the first fix). The odometry is also run
alone on the relocalisation drive (traversal 2, in the sequence's localize_weather): column "reloc
drive odometry". --check fails (exit 1) on a regression against the
baseline (a result of an earlier run, --write-baseline): KITTI errors more than 10 % + 0.05 %
(0.0005 deg/m) worse (also the relocalisation drive's odometry), more false loops or wrongly trusted scans, revisit consistency or loop
recall more than 0.05 lower, or a sequence missing from the baseline. Simulations are
cached in OUT/<name>/sim (re-used when the options and the simulator's sources and configs are the same). Results: a Markdown table on
stdout and OUT/results.json.
"""
import argparse
import glob
import hashlib
import json
import math
import re
import os
import shutil
import subprocess
import sys
import time

import yaml

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def fail(msg):
    print(f"bench.py: {msg}", file=sys.stderr)
    sys.exit(2)


def load_sequences(path):
    try:
        with open(path, encoding="utf-8") as f:
            doc = yaml.safe_load(f)
    except (OSError, yaml.YAMLError) as e:
        fail(f"{path}: {e}".replace("\n", " "))
    defaults = doc.get("defaults", {})
    known = {"name", "split", "seed", "weather", "scans", "ci_scans", "simulate", "localize", "localize_weather"}
    seqs = []
    for s in doc.get("sequences", []):
        unknown = set(s) - known
        if unknown:
            fail(f"{path}: sequence {s.get('name')}: unknown keys {sorted(unknown)}")
        if s.get("split") not in ("train", "test"):
            fail(f"{path}: sequence {s.get('name')}: split must be train or test")
        seqs.append({**defaults, **s})
    names = [s["name"] for s in seqs]
    if len(set(names)) != len(names):
        fail(f"{path}: duplicate sequence names")
    return seqs


def run(cmd, log):
    with open(log, "a", encoding="utf-8") as f:
        f.write("$ " + " ".join(cmd) + "\n")
        f.flush()
        r = subprocess.run(cmd, stdout=f, stderr=subprocess.STDOUT)
    if r.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} failed ({r.returncode}); see {log}")


def simulator_version():
    """A hash of what decides a simulation: the simulator's sources and its configs."""
    h = hashlib.sha256()
    paths = []
    for sub in ("libradarslam/src/sim", "libradarslam/include/radarslam/sim"):
        for dirpath, _, files in os.walk(os.path.join(ROOT, sub)):
            paths += [os.path.join(dirpath, f) for f in files]
    paths += glob.glob(os.path.join(ROOT, "config", "sim*.yaml"))
    for path in sorted(paths):
        h.update(os.path.relpath(path, ROOT).encode())
        with open(path, "rb") as f:
            h.update(f.read())
    return h.hexdigest()[:16]


def simulate(exe, seq, scans, traversal, weather, out, log):
    """Simulates into `out` unless it already holds the same simulation."""
    shared = os.path.join(os.path.dirname(ROOT), "shared")
    extra = [str(a).replace("SHARED/", shared + "/") for a in seq["simulate"]]
    args = ["--seed", str(seq["seed"]), "--scans", str(scans), "--weather", weather,
            "--traversal", str(traversal)] + extra
    stamp = os.path.join(out + ".args")
    key = " ".join(args) + " simulator " + simulator_version()
    if os.path.isdir(out) and os.path.exists(stamp):
        with open(stamp, encoding="utf-8") as f:
            if f.read() == key:
                return
    if os.path.exists(stamp):
        os.remove(stamp)
    run([exe, "simulate", out, "--force"] + args, log)
    with open(stamp, "w", encoding="utf-8") as f:
        f.write(key)


def localization_metrics(eval_dir):
    """From `radarslam localize --eval-dir`: errors.csv (map-relative errors) and summary.txt."""
    summary = {}
    nees = {}
    with open(os.path.join(eval_dir, "summary.txt"), encoding="utf-8") as f:
        for line in f:
            parts = line.split()
            if len(parts) == 2:
                summary[parts[0]] = parts[1]
            # "consistency    vs the map: NEES mean 3.31 (3 if calibrated), 90.6 % within the chi2(3) 95 % bound; ..."
            m = re.search(r"vs the map: NEES mean ([0-9.]+) .*?, ([0-9.]+) % within", line)
            if m:
                nees = {"nees_mean": float(m.group(1)), "nees_within_95": float(m.group(2)) / 100}
    trusted = good = bad = scans = 0
    with open(os.path.join(eval_dir, "errors.csv"), encoding="utf-8") as f:
        for line in f:
            if line.startswith("#"):
                continue
            c = line.split()
            status, pos, head = c[2], float(c[9]), float(c[10])
            if math.isnan(pos):
                continue
            scans += 1
            if status in ("tracking", "global_fix"):
                trusted += 1
                if pos > 2.0 or head > 2.0:
                    bad += 1
            if status == "tracking" and pos <= 0.3 and head <= 0.5:
                good += 1
    total = int(summary.get("scans", "0"))
    return {
        "scans": total,
        "tracking_within_0.3m_0.5deg": good / total if total else None,
        "trusted_over_2m_or_2deg": bad,
        "first_fix_scan": int(summary.get("first_fix_scan", "-1")),
        "first_trusted_scan": int(summary.get("first_trusted_scan", "-1")),
        "contested_fixes": int(summary.get("contested_fixes", "0")),
        "scans_per_s": float(summary.get("scans_per_s", "nan")),
        **nees,
    }


def clear_localize_outputs(poses, eval_dir=None):
    """Removes the pose files of `localize -o poses` (and its --eval-dir, when given)."""
    if eval_dir:
        shutil.rmtree(eval_dir, ignore_errors=True)
    for f in (poses, poses + ".csv", poses + ".boreas.txt"):
        if os.path.exists(f):
            os.remove(f)


def first_fixes(exe, map_dir, sim2, scans, d, log, starts=10, window=10):
    """Global localisation from scratch at `starts` evenly spaced scans of the second traversal
    (issue 14: first fix within 3 scans from any start point): `localize --first N --count window`.
    Per start: the first fix's index in the run (-1 = none in the window) and whether any pose
    reported as tracking or global_fix was more than 2 m / 2 deg off the map."""
    out = []
    for k in range(starts):
        first = k * max(1, (scans - window) // starts)
        ev = os.path.join(d, f"start_{first}")
        poses = os.path.join(d, f"start_{first}.tum")
        clear_localize_outputs(poses, ev)
        run([exe, "localize", map_dir, sim2, "-o", poses, "-q", "--eval-dir", ev, "--first", str(first),
             "--count", str(window)], log)
        m = localization_metrics(ev)
        out.append({"first": first, "first_fix_scan": m["first_fix_scan"],
                    "first_trusted_scan": m["first_trusted_scan"],
                    "trusted_over_2m_or_2deg": m["trusted_over_2m_or_2deg"]})
        clear_localize_outputs(poses)  # the eval dir stays: its summary is the record
    return out


def drive_odometry(exe, sim2, d, log):
    """The odometry alone on the relocalisation drive (traversal 2, in `localize_weather`): the
    localiser's dead reckoning, and the benchmark's odometry in a second weather (issue 13: clear
    and fog). KITTI errors (None when the drive is shorter than 100 m), ATE and per-frame RPE max."""
    ev = os.path.join(d, "odometry2_eval")
    tum = os.path.join(d, "odometry2.tum")
    clear_localize_outputs(tum, ev)
    run([exe, "odometry", sim2, "-o", tum, "-q", "--eval-dir", ev], log)
    with open(os.path.join(ev, "report.json"), encoding="utf-8") as f:
        r = json.load(f)
    kitti = r.get("kitti") or {}
    return {"kitti_t_percent": kitti.get("t_err_percent"), "kitti_r_deg_per_m": kitti.get("r_err_deg_per_m"),
            "ate_rmse_m": r["ate"]["trans_m"]["rmse"], "rpe_max_m": r["rpe"]["trans_m"]["max"],
            "path_m": r["gt_path_length_m"]}


def run_sequence(exe, seq, scans, out_root):
    d = os.path.join(out_root, seq["name"])
    os.makedirs(d, exist_ok=True)
    log = os.path.join(d, "log.txt")
    open(log, "w").close()
    t0 = time.time()
    simulate(exe, seq, scans, 1, seq["weather"], os.path.join(d, "sim"), log)
    map_dir = os.path.join(d, "map")
    run([exe, "map", os.path.join(d, "sim"), "-o", map_dir, "--force", "--threads", "1"], log)
    with open(os.path.join(map_dir, "eval", "slam_quality.json"), encoding="utf-8") as f:
        result = json.load(f)
    with open(os.path.join(map_dir, "summary.txt"), encoding="utf-8") as f:
        for line in f:
            if line.strip().startswith("speed"):
                result["slam_scans_per_s"] = float(line.split()[1])
    if seq["localize"]:
        sim2 = os.path.join(d, "sim2")
        simulate(exe, seq, scans, 2, seq["localize_weather"], sim2, log)
        ev = os.path.join(d, "localize_eval")
        poses = os.path.join(d, "localize.tum")
        clear_localize_outputs(poses, ev)
        run([exe, "localize", map_dir, sim2, "-o", poses, "-q", "--eval-dir", ev], log)
        result["localization"] = localization_metrics(ev)
        result["localization"]["starts"] = first_fixes(exe, map_dir, sim2, scans, d, log)
        result["localization"]["drive_odometry"] = drive_odometry(exe, sim2, d, log)
    result["wall_s"] = time.time() - t0
    return result


def regressions(name, r):
    """What must hold on every sequence, whatever its length."""
    out = []
    o, s = r["odometry"], r["slam"]
    for key in ("kitti_t_percent", "kitti_r_deg_per_m", "ate_rmse_m"):  # issue 13: never worse, ATE lower
        if o.get(key) is not None and s.get(key) is not None and s[key] > o[key]:
            out.append(f"{name}: SLAM {key} {s[key]:.4g} worse than its odometry's {o[key]:.4g}")
    if r["loops"]["false_in_graph"] > 0:
        out.append(f"{name}: {r['loops']['false_in_graph']} false loops left in the graph")
    loc = r.get("localization")
    if loc and loc["trusted_over_2m_or_2deg"] > 0:
        out.append(f"{name}: {loc['trusted_over_2m_or_2deg']} relocalised scans trusted but > 2 m / 2 deg off")
    for st in (loc or {}).get("starts", []):
        if st["trusted_over_2m_or_2deg"] > 0:
            out.append(f"{name}: start at scan {st['first']}: {st['trusted_over_2m_or_2deg']} scans trusted but > 2 m / 2 deg off")
    return out


def against_baseline(name, r, base):
    """What got worse than the baseline run (tolerances in the module docstring)."""
    if base is None:
        return [f"{name}: not in the baseline (run --write-baseline)"]
    out = []
    for part in ("odometry", "slam"):
        for key, slack in (("kitti_t_percent", 0.05), ("kitti_r_deg_per_m", 0.0005)):
            now, was = r[part][key], base[part][key]
            if now is not None and was is not None and now > 1.1 * was + slack:
                out.append(f"{name}: {part} {key} {now:.4g} (baseline {was:.4g})")
    if r["loops"]["false_in_graph"] > base["loops"]["false_in_graph"]:
        out.append(f"{name}: {r['loops']['false_in_graph']} false loops left (baseline {base['loops']['false_in_graph']})")
    for key, now, was in (("loop recall", r["loops"]["recall"], base["loops"]["recall"]),
                          ("revisit consistency", r["map_consistency"]["revisits"]["fraction"],
                           base["map_consistency"]["revisits"]["fraction"])):
        if now is not None and was is not None and now < was - 0.05:
            out.append(f"{name}: {key} {now:.3f} (baseline {was:.3f})")
    loc, bl = r.get("localization"), base.get("localization")
    if loc and bl:
        if loc["trusted_over_2m_or_2deg"] > bl["trusted_over_2m_or_2deg"]:
            out.append(f"{name}: {loc['trusted_over_2m_or_2deg']} trusted scans > 2 m off (baseline {bl['trusted_over_2m_or_2deg']})")
        if "starts" in bl and fixes_within_3(loc) < fixes_within_3(bl) - 2:
            out.append(f"{name}: first fix within 3 scans from {fixes_within_3(loc)} of {len(loc['starts'])} starts "
                       f"(baseline {fixes_within_3(bl)})")
        now, was = (loc.get("drive_odometry") or {}).get("kitti_t_percent"), (bl.get("drive_odometry") or {}).get(
            "kitti_t_percent")
        if now is not None and was is not None and now > 1.1 * was + 0.05:
            out.append(f"{name}: odometry of the relocalisation drive kitti_t_percent {now:.4g} (baseline {was:.4g})")
        if loc["tracking_within_0.3m_0.5deg"] < bl["tracking_within_0.3m_0.5deg"] - 0.05:
            out.append(f"{name}: relocalisation within 0.3 m / 0.5 deg {loc['tracking_within_0.3m_0.5deg']:.3f} "
                       f"(baseline {bl['tracking_within_0.3m_0.5deg']:.3f})")
    return out


def fixes_within_3(loc, key="first_fix_scan"):
    """Starts whose first fix (any status; key first_trusted_scan: tracking or global_fix) came within 3 scans
    (index 0..2 of the run)."""
    return sum(1 for st in loc.get("starts", []) if 0 <= st.get(key, -1) <= 2)


def fmt(v, spec):
    return "-" if v is None else format(v, spec)


def table(results):
    rows = ["| sequence | split | km | odometry % / deg/m | SLAM % / deg/m | ATE odo / SLAM m | per-frame RPE max m "
            "| loops: recall, false | revisit pairs consistent | reloc tracking ok, trusted > 2 m, first fix ≤ 3 scans (trusted) "
            "| reloc drive odometry % / deg/m | SLAM scans/s |",
            "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for name, split, r in results:
        o, s, l, mc = r["odometry"], r["slam"], r["loops"], r["map_consistency"]["revisits"]
        loc = r.get("localization")
        reloc = "-" if not loc else (f"{100 * loc['tracking_within_0.3m_0.5deg']:.1f} %, {loc['trusted_over_2m_or_2deg']}, "
                                     f"{fixes_within_3(loc)} ({fixes_within_3(loc, 'first_trusted_scan')}) of "
                                     f"{len(loc.get('starts', []))} starts")
        drive = (loc or {}).get("drive_odometry")
        drive_cell = "-" if not drive else (f"{fmt(drive['kitti_t_percent'], '.2f')} / "
                                            f"{fmt(drive['kitti_r_deg_per_m'], '.4f')}")
        rows.append(
            f"| {name} | {split} | {o['path_m'] / 1000:.2f} | {fmt(o['kitti_t_percent'], '.2f')} / "
            f"{fmt(o['kitti_r_deg_per_m'], '.4f')} | {fmt(s['kitti_t_percent'], '.2f')} / "
            f"{fmt(s['kitti_r_deg_per_m'], '.4f')} | {o['ate_rmse_m']:.2f} / {s['ate_rmse_m']:.2f} | "
            f"{o['rpe_max_m']:.2f} | {fmt(l['recall'], '.2f')}, {l['false_in_graph']} | "
            f"{100 * mc['fraction']:.1f} % of {mc['pairs']} | {reloc} | {drive_cell} | "
            f"{fmt(r.get('slam_scans_per_s'), '.1f')} |")
    return "\n".join(rows)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    ap.add_argument("--sequences", default=os.path.join(ROOT, "config", "bench", "sequences.yaml"))
    ap.add_argument("--split", choices=("train", "test", "all"), default="test")
    ap.add_argument("--reduced", action="store_true", help="each sequence's ci_scans (CI)")
    ap.add_argument("--only", action="append", default=[], metavar="NAME", help="just these sequences")
    ap.add_argument("--out", default=os.path.join(ROOT, "out", "bench"))
    ap.add_argument("--radarslam", default=os.path.join(ROOT, "build", "apps", "radarslam"))
    ap.add_argument("--check", action="store_true", help="exit 1 on a regression against --baseline")
    ap.add_argument("--baseline", help="results.json of an earlier run to compare with")
    ap.add_argument("--write-baseline", metavar="FILE", help="also write this run's results here")
    a = ap.parse_args()
    if not os.access(a.radarslam, os.X_OK):
        fail(f"{a.radarslam}: not an executable (build first, or pass --radarslam)")
    if a.check and not a.baseline:
        fail("--check needs --baseline")
    baseline = None
    if a.baseline:
        try:
            with open(a.baseline, encoding="utf-8") as f:
                baseline = json.load(f)
        except (OSError, ValueError) as e:
            fail(f"{a.baseline}: {e}")
    seqs = load_sequences(a.sequences)
    unknown = set(a.only) - {s["name"] for s in seqs}
    if unknown:
        fail(f"--only: unknown sequences {sorted(unknown)}")
    chosen = [s for s in seqs if (a.split == "all" or s["split"] == a.split) and (not a.only or s["name"] in a.only)]
    if a.reduced:
        chosen = [s for s in chosen if s.get("ci_scans", 0) > 0]
    if not chosen:
        fail("no sequence selected")
    os.makedirs(a.out, exist_ok=True)
    results, problems, violations = [], [], []
    for i, s in enumerate(chosen):
        scans = s["ci_scans"] if a.reduced else s["scans"]
        print(f"bench: [{i + 1}/{len(chosen)}] {s['name']} ({s['split']}, {scans} scans)", file=sys.stderr, flush=True)
        try:
            r = run_sequence(a.radarslam, s, scans, a.out)
        except (RuntimeError, OSError, KeyError, ValueError) as e:
            fail(str(e))
        results.append((s["name"], s["split"], r))
        violations += regressions(s["name"], r)
        if baseline is not None:
            problems += against_baseline(s["name"], r, baseline.get(s["name"]))
        print(f"bench: {s['name']} done in {r['wall_s']:.0f} s", file=sys.stderr, flush=True)
    doc = {n: {"split": sp, **r} for n, sp, r in results}
    for path in filter(None, (os.path.join(a.out, "results.json"), a.write_baseline)):
        with open(path, "w", encoding="utf-8") as f:
            json.dump(doc, f, indent=1)
    print(table(results))
    for v in violations:
        print(f"bench: VIOLATION {v}", file=sys.stderr)
    for p in problems:
        print(f"bench: REGRESSION {p}", file=sys.stderr)
    if a.check and problems:
        sys.exit(1)


if __name__ == "__main__":
    main()
