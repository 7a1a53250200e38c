#!/usr/bin/env python3
"""Turns ProxyGIBenchSH's JSON into the tables of Documentation/AccuracyTime.md.

Replaces the text between '<!-- BEGIN name -->' and '<!-- END name -->'
markers; everything else in the document is left as written.
  bench_report.py sh.json Documentation/AccuracyTime.md
"""
import json
import re
import sys
from collections import defaultdict


def load(path):
    data = json.load(open(path))
    rows = {}
    for b in data["benchmarks"]:
        if b.get("run_type") == "aggregate" and b.get("aggregate_name") != "mean":
            continue
        name = b.get("run_name", b["name"]).replace("_mean", "")
        rows[name] = b
    return data["context"], rows


def ns(b):
    scale = {"ns": 1.0, "us": 1e3, "ms": 1e6, "s": 1e9}[b["time_unit"]]
    return b["cpu_time"] * scale


def exp_table(rows):
    by_order = defaultdict(dict)
    for name, b in rows.items():
        m = re.match(r"Exp/(.+)/order:(\d+)$", name)
        if m:
            by_order[int(m.group(2))][m.group(1)] = b
    out = []
    for order in sorted(by_order):
        methods = by_order[order]
        hyb = ns(methods["HYB"])
        prod = rows.get(f"AccumulateProduct/order:{order}", {}).get("rms_err")
        norm = methods["HYB"].get("mean_norm", 0.0)
        out.append(f"**Order {order}** (mean |f^| of the workload {norm:.2f}; "
                   f"product-space accumulation error {prod:.4f})\n" if prod is not None else
                   f"**Order {order}**\n")
        out.append("| method | ns per exp | time / HYB | RMS visibility error |")
        out.append("|---|---:|---:|---:|")
        for name, b in methods.items():
            out.append(f"| {name} | {ns(b):.0f} | {ns(b) / hyb:.2f} | {b['rms_err']:.4f} |")
        out.append("")
    return "\n".join(out)


def accumulation_table(rows):
    out = ["| order | log space: ns per blocker | product space: ns per blocker | "
           "product / log | eigen log of one cap (table build), us |",
           "|---:|---:|---:|---:|---:|"]
    orders = sorted({int(n.split(":")[1]) for n in rows if n.startswith("AccumulateLog/")})
    for o in orders:
        lg = ns(rows[f"AccumulateLog/order:{o}"]) / 256
        pr = ns(rows[f"AccumulateProduct/order:{o}"]) / 256
        eig = ns(rows[f"Log/order:{o}"]) / 1e3
        out.append(f"| {o} | {lg:.1f} | {pr:.1f} | {pr / lg:.1f} | {eig:.1f} |")
    return "\n".join(out)


def replace(doc, name, body):
    pattern = re.compile(rf"(<!-- BEGIN {name} -->\n).*?(<!-- END {name} -->)", re.S)
    if not pattern.search(doc):
        sys.exit(f"bench_report: marker {name} missing in the document")
    return pattern.sub(lambda m: m.group(1) + body.rstrip() + "\n" + m.group(2), doc)


def main():
    if sys.argv[1] == "--section":
        # bench_report.py --section NAME TABLE.md DOCUMENT.md: a program's
        # own Markdown output between the NAME markers.
        doc = open(sys.argv[4]).read()
        doc = replace(doc, sys.argv[2], open(sys.argv[3]).read())
        open(sys.argv[4], "w").write(doc)
        return
    context, rows = load(sys.argv[1])
    doc = open(sys.argv[2]).read()
    machine = (f"{context.get('num_cpus')} CPUs at {context.get('mhz_per_cpu')} MHz, "
               f"{context.get('date', '')}")
    doc = replace(doc, "sh-exp", f"Measured on {machine}.\n\n" + exp_table(rows))
    doc = replace(doc, "sh-accumulation", accumulation_table(rows))
    open(sys.argv[2], "w").write(doc)


if __name__ == "__main__":
    main()
