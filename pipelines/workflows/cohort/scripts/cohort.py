#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""The cohort table (CSV, one row per case) and an HTML index with the thumbnails, from the cases'
summaries."""
import argparse
import csv
import html
import json
import os

COLUMNS = ["case", "status", "input", "threshold", "label", "method", "mesh", "vertices", "faces", "components",
           "is_closed", "euler_characteristic", "volume_before_mm3", "volume_after_mm3", "volume_change_percent",
           "edge_vertices", "seconds", "error"]


def row_of(summary):
    r = summary.get("result", {})
    return {
        "case": summary["case"], "status": summary["status"], "input": summary["input"],
        "threshold": summary.get("threshold") or "", "label": summary.get("label") or "", "method": summary["method"],
        "mesh": summary.get("mesh", ""), "vertices": r.get("vertices", ""), "faces": r.get("faces", ""),
        "components": r.get("components", ""), "is_closed": r.get("is_closed", ""),
        "euler_characteristic": r.get("euler_characteristic", ""),
        "volume_before_mm3": round(r["volume_before"], 2) if "volume_before" in r else "",
        "volume_after_mm3": round(r["volume_after"], 2) if "volume_after" in r else "",
        "volume_change_percent": round(r["volume_change_percent"], 3) if "volume_change_percent" in r else "",
        "edge_vertices": r.get("edge_vertices", ""), "seconds": summary.get("seconds_wall", ""),
        "error": summary.get("error", ""),
    }


def write_atomically(path, text):
    tmp = path + ".tmp"
    with open(tmp, "w", newline="") as f:
        f.write(text)
    os.replace(tmp, path)


def main():
    p = argparse.ArgumentParser(description=__doc__)
    p.add_argument("--table", required=True)
    p.add_argument("--index", required=True)
    p.add_argument("summaries", nargs="+")
    a = p.parse_args()
    rows = []
    for path in a.summaries:
        with open(path) as f:
            rows.append((path, row_of(json.load(f))))

    import io
    out = io.StringIO()
    writer = csv.DictWriter(out, fieldnames=COLUMNS, lineterminator="\n")
    writer.writeheader()
    for _, row in rows:
        writer.writerow(row)
    write_atomically(a.table, out.getvalue())

    base = os.path.dirname(os.path.abspath(a.index))
    ok = sum(1 for _, r in rows if r["status"] == "ok")
    cards = []
    for path, r in rows:
        thumb = os.path.relpath(os.path.join(os.path.dirname(path), "thumbnail.png"), base)
        facts = (f"{r['vertices']} vertices, {'closed' if r['is_closed'] else 'open'}, "
                 f"volume {r['volume_after_mm3']} mm&sup3; ({r['volume_change_percent']} %)"
                 if r["status"] == "ok" else html.escape(r["error"]))
        link = (f"<a href=\"{html.escape(os.path.relpath(r['mesh'], base))}\">mesh</a>" if r["mesh"] else "")
        cards.append(f"<figure class=\"{r['status']}\"><img src=\"{html.escape(thumb)}\" alt=\"{html.escape(r['case'])}\">"
                     f"<figcaption><b>{html.escape(r['case'])}</b> {r['status']}<br>{facts}<br>{link}</figcaption></figure>")
    page = f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>ContourMesh cohort</title>
<style>body{{font-family:sans-serif;margin:1.5em}} figure{{display:inline-block;width:260px;margin:.5em;vertical-align:top}}
figure img{{width:240px;height:240px}} figure.failed figcaption{{color:#a00}}</style></head>
<body><h1>ContourMesh cohort</h1>
<p>{len(rows)} cases: {ok} ok, {len(rows) - ok} failed. Table: <a href="{html.escape(os.path.relpath(a.table, base))}">{html.escape(os.path.basename(a.table))}</a>.</p>
{chr(10).join(cards)}
</body></html>
"""
    write_atomically(a.index, page)


if __name__ == "__main__":
    main()
