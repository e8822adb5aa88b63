#!/usr/bin/env python3
"""Checks a scrape of /metrics as Prometheus text exposition format 0.0.4 and prints samples.

Usage: prometheus_check.py FILE [NAME{LABELS} ...]
Rules checked (exit 1 with the offending line otherwise):
- every line is a comment (# HELP / # TYPE name type), blank, or `name{labels} value`;
- every sample's metric family has a # TYPE line before it, each family's TYPE once;
- counter family names end in _total; counter values are >= 0;
- a histogram's samples are name_bucket{...,le=...}, name_sum, name_count; per label set the
  buckets are non-decreasing in le, the last is le="+Inf" and equals name_count;
- litamin2_build_info is there with a version label and the value 1.
For each further argument (a sample as written, e.g. 'x_total{stream="a"}') prints
"<sample> <value>", or "<sample> absent".
"""
import math
import re
import sys

NAME = r"[a-zA-Z_:][a-zA-Z0-9_:]*"
SAMPLE = re.compile(r"^(" + NAME + r")(\{(.*)\})? (\S+)$")
LABEL = re.compile(r'([a-zA-Z_][a-zA-Z0-9_]*)="((?:[^"\\]|\\.)*)"')


def fail(lineno, line, why):
    print(f"line {lineno}: {why}: {line}")
    sys.exit(1)


def parse_labels(text, lineno, line):
    labels = []
    pos = 0
    while pos < len(text):
        m = LABEL.match(text, pos)
        if not m:
            fail(lineno, line, "malformed labels")
        labels.append((m.group(1), m.group(2)))
        pos = m.end()
        if pos < len(text):
            if text[pos] != ",":
                fail(lineno, line, "malformed labels")
            pos += 1
    return labels


def number(text, lineno, line):
    if text in ("+Inf", "-Inf", "NaN"):
        return float(text.replace("Inf", "inf").replace("NaN", "nan"))
    try:
        return float(text)
    except ValueError:
        fail(lineno, line, "value is not a number")


def main():
    types = {}
    samples = {}
    histograms = {}  # (family, labels without le) -> {"buckets": [(le, v)], "count": v}
    with open(sys.argv[1]) as f:
        lines = f.read().split("\n")
    if lines and lines[-1] == "":
        lines.pop()
    for lineno, line in enumerate(lines, 1):
        if line == "":
            continue
        if line.startswith("#"):
            parts = line.split(" ", 3)
            if len(parts) >= 3 and parts[1] == "TYPE":
                if len(parts) != 4 or parts[3] not in ("counter", "gauge", "histogram",
                                                       "summary", "untyped"):
                    fail(lineno, line, "bad TYPE line")
                if parts[2] in types:
                    fail(lineno, line, "TYPE given twice")
                if parts[3] == "counter" and not parts[2].endswith("_total"):
                    fail(lineno, line, "counter name does not end in _total")
                types[parts[2]] = parts[3]
            elif len(parts) >= 3 and parts[1] == "HELP":
                pass
            else:
                fail(lineno, line, "comment is neither HELP nor TYPE")
            continue
        m = SAMPLE.match(line)
        if not m:
            fail(lineno, line, "not a sample line")
        name, labels_text, value_text = m.group(1), m.group(3) or "", m.group(4)
        labels = parse_labels(labels_text, lineno, line)
        value = number(value_text, lineno, line)
        family, suffix = name, ""
        if name not in types:
            for s in ("_bucket", "_sum", "_count"):
                if name.endswith(s) and types.get(name[: -len(s)]) == "histogram":
                    family, suffix = name[: -len(s)], s
                    break
        if family not in types:
            fail(lineno, line, "sample without a # TYPE for its metric")
        kind = types[family]
        if kind == "histogram" and suffix == "":
            fail(lineno, line, "histogram sample without _bucket/_sum/_count")
        if kind == "counter" and not value >= 0:
            fail(lineno, line, "negative counter")
        key = name + ("{" + labels_text + "}" if labels_text else "")
        samples[key] = value
        if kind == "histogram":
            rest = tuple(l for l in labels if l[0] != "le")
            h = histograms.setdefault((family, rest), {"buckets": [], "count": None})
            if suffix == "_bucket":
                le = [v for k, v in labels if k == "le"]
                if len(le) != 1:
                    fail(lineno, line, "bucket without one le label")
                h["buckets"].append((number(le[0], lineno, line), value))
            elif suffix == "_count":
                h["count"] = value
    for (family, rest), h in histograms.items():
        where = f"histogram {family}{dict(rest)}"
        b = h["buckets"]
        if not b or not math.isinf(b[-1][0]):
            print(f"{where}: no le=\"+Inf\" bucket last")
            sys.exit(1)
        for (le0, v0), (le1, v1) in zip(b, b[1:]):
            if not le1 > le0 or v1 < v0:
                print(f"{where}: buckets not increasing in le or decreasing in count")
                sys.exit(1)
        if h["count"] is None or h["count"] != b[-1][1]:
            print(f"{where}: le=\"+Inf\" ({b[-1][1]}) differs from _count ({h['count']})")
            sys.exit(1)
    info = [k for k in samples if k.startswith("litamin2_build_info{")]
    if not info or 'version="' not in info[0] or samples[info[0]] != 1:
        print("no litamin2_build_info{version=...} 1")
        sys.exit(1)
    print(f"ok: {len(types)} families, {len(samples)} samples, {len(histograms)} histogram(s)")
    for want in sys.argv[2:]:
        v = samples.get(want)
        print(want, "absent" if v is None else int(v) if v.is_integer() else v)


if __name__ == "__main__":
    main()
