#!/usr/bin/env python3
# The plan pages a committed bench result links (SCENE/PIPELINE.plan.html beside
# results.md), made again without the GPU it was measured on: `rgraph explain --format html`
# with the adapter's saved profile (`rgraph adapters --save-profile`) and the result's own
# per-pass times. For results measured before the bench wrote its pages, or whose pages a
# machine handing back few files could not return.
#
#   scripts/plan-pages.py RESULTS_DIR PROFILE.json [RGRAPH]
#   scripts/plan-pages.py bench/results/h200/every-4x bench/results/h200/profile.json
#
# Each page is compiled from the pipeline files of this checkout for the row's scene at
# the result's resolution; a scene that is a file must be where the result names it.
import json
import os
import subprocess
import sys

results_dir, profile = sys.argv[1], sys.argv[2]
rgraph = sys.argv[3] if len(sys.argv) > 3 else "target/release/rgraph"
results_json = os.path.join(results_dir, "results.json")
results = json.load(open(results_json))
width, height = results["resolution"]


def slug(text):
    return "".join(c if c.isascii() and (c.isalnum() or c in "-.") else "_" for c in text)


failed = 0
for row in results["rows"]:
    if row["status"] != "ok" or row.get("sweep"):
        continue
    page = os.path.join(results_dir, slug(row["scene"]), slug(row["pipeline"]) + ".plan.html")
    os.makedirs(os.path.dirname(page), exist_ok=True)
    command = [
        rgraph, "explain", "--pipeline", row["file"], "--scene", row["scene"],
        "--size", f"{width}x{height}", "--profile", profile, "--output", "color",
        "--format", "html", "--timings", results_json, "--out", page,
    ]
    done = subprocess.run(command, capture_output=True, text=True)
    if done.returncode != 0:
        failed += 1
        print(f"{page}: {done.stderr.strip()}", file=sys.stderr)
    else:
        print(page)
sys.exit(1 if failed else 0)
