#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""One case of the cohort workflow: `contourmesh run` on a scan, and a JSON summary that is written
whatever happens (status "ok" with the run's facts, or "failed" with the error and exit code), so
that a broken scan is reported in the cohort table instead of stopping the workflow."""
import argparse
import json
import os
import subprocess
import sys
import time


def main():
    p = argparse.ArgumentParser(description=__doc__)
    p.add_argument("--contourmesh", required=True)
    p.add_argument("--case", required=True)
    p.add_argument("--input", required=True)
    p.add_argument("--mesh", required=True)
    p.add_argument("--summary", required=True)
    p.add_argument("--threshold")
    p.add_argument("--label")
    p.add_argument("--method", default="cross-slice")
    p.add_argument("--creases", default="none", help="none | restore (passed to contourmesh run unless none)")
    p.add_argument("--threads", default="1")
    a = p.parse_args()

    os.makedirs(os.path.dirname(a.mesh), exist_ok=True)
    cmd = [a.contourmesh, "run", a.input, "-o", a.mesh, "--json", "-q", "--threads", a.threads,
           "--method", a.method]
    if a.creases != "none":  # contourmesh refuses --creases with a method it does not apply to
        cmd += ["--creases", a.creases]
    if a.label:
        cmd += ["--label", a.label]
    elif a.threshold:
        cmd += ["--threshold", a.threshold]
    summary = {"case": a.case, "input": a.input, "threshold": a.threshold, "label": a.label, "method": a.method,
               "command": cmd}
    start = time.monotonic()
    try:
        done = subprocess.run(cmd, capture_output=True, text=True)
    except OSError as e:
        done = None
        summary.update(status="failed", exit_code=None, error=f"cannot run {a.contourmesh}: {e}")
    summary["seconds_wall"] = round(time.monotonic() - start, 3)
    if done is not None:
        sys.stderr.write(done.stderr)
        summary["exit_code"] = done.returncode
        if done.returncode == 0:
            result = json.loads(done.stdout.strip().splitlines()[-1])
            if "labels" in result:  # --label: one label's mesh
                result = result["labels"][0]
            summary.update(status="ok", mesh=a.mesh, error="", result=result)
        else:
            lines = [l for l in done.stderr.splitlines() if "error" in l] or done.stderr.splitlines() or ["no message"]
            summary.update(status="failed", error=lines[-1].strip())
    tmp = a.summary + ".tmp"
    with open(tmp, "w") as f:
        json.dump(summary, f, indent=1)
    os.replace(tmp, a.summary)
    print(f"{a.case}: {summary['status']}" + (f" ({summary['error']})" if summary["status"] != "ok" else ""))


if __name__ == "__main__":
    main()
