#!/usr/bin/env python3
"""Writes docs/BENCHMARKS.md from one run folder of scripts/benchmarks.

Usage: scripts/bench_report.py RUN_DIR [DOCS_DIR] > docs/BENCHMARKS.md

Reads the run folder written by scripts/benchmarks:
  RUN/machine.txt                 the machine (CPU, memory, rustc) and benches that failed
  RUN/<crate>.stderr              what each crate's benches printed (accuracy tables)
  RUN/criterion/<crate>/...       criterion's estimates per crate
  RUN/compare/<scene>/            `mblur compare` output (results.csv, results.md, plot.*)
  RUN/goals.txt                   `key value` lines measured by scripts/benchmarks
and writes one short page to stdout: the goals, a compact error-vs-time table per scene
with a link to its plot (copied to DOCS_DIR/benchmarks/), and a few headline figures per
crate with a link to the crate's own BENCHMARKS.md, which holds the analysis.

Nothing here measures anything: every figure comes from the run folder. A figure whose
input is missing from the run is left out (a crate without any says so), except that a run
without crate benches (MBLUR_BENCH_PARTS without `crates`) keeps the page's current
per-crate section and static-scene goal.

The page's other `## ` sections (the Pareto check, curved motion, lit surfaces,
antialiasing, instruction counts, ...) each come from the command they name; this script
does not write them but carries them over from the current DOCS_DIR/BENCHMARKS.md, each
after the generated section it followed.
"""

import csv
import json
import math
import os
import re
import shutil
import sys

CRATES = [
    "edge-eqn",
    "bilinear-patch",
    "tmsnet",
    "interval-buffer",
    "resolve",
    "ewa-splat",
    "raster-hier",
    "mblur",
]
# Every built-in triangle scene (the goal says "every built-in scene"; the splat scenes have
# no analytic method); the lit ones unlit (`SCENE-unlit`), so the figures measure motion blur
# alone.
SCENES = [
    "billiards-unlit",
    "fence",
    "transparent-cubes-unlit",
    "clothball-unlit",
    "clothball-ronnow-unlit",
    "crossing-quads",
    "pills-unlit",
    "textured-quad",
    "static",
]
# Must match scripts/benchmarks.
BENCH_ARGS = "-- --warm-up-time 1 --measurement-time 3"
COMPARE_ARGS = "--traversals our,fallback --spp 1,4,16,64,256,1024"
TARGET_DB = 40.0
# Scenes where nothing moves: no motion blur to compare methods on.
MOTIONLESS = {"static"}
# Method groups of the compare tables, in table order.
GROUPS = ["analytic", "prism", "stochastic", "accum", "ewa"]
NOISE = (
    "Benchmarking ",
    "Compiling ",
    "Finished ",
    "Running ",
    "Gnuplot not found",
    "Downloaded ",
    "Downloading ",
    "Blocking waiting",
    "Updating ",
    "Locking ",
    "Adding ",
    "Fresh ",
    "warning: ",
    "Warning: Unable to complete",
    "Found ",
)


# ---------------------------------------------------------------- reading the run folder


def fmt_time(ns):
    for unit, scale in (("s", 1e9), ("ms", 1e6), ("µs", 1e3)):
        if ns >= scale:
            return f"{ns / scale:.3g} {unit}"
    return f"{ns:.3g} ns"


def fmt_ms(ms):
    """Milliseconds as `mblur compare` prints them."""
    if ms >= 100:
        return f"{ms:.0f}"
    if ms >= 10:
        return f"{ms:.1f}"
    return f"{ms:.2f}"


def fmt_db(p):
    return "inf" if math.isinf(p) else f"{p:.2f}"


def criterion(root):
    """{full_id: {"median": ns, "per": ns per element or None}} from criterion's estimates."""
    out = {}
    for dirpath, _dirs, files in os.walk(root):
        if os.path.basename(dirpath) != "new" or "benchmark.json" not in files:
            continue
        with open(os.path.join(dirpath, "benchmark.json")) as f:
            bench = json.load(f)
        with open(os.path.join(dirpath, "estimates.json")) as f:
            est = json.load(f)
        median = est["median"]["point_estimate"]
        tp = bench.get("throughput") or {}
        per = median / tp["Elements"] if tp.get("Elements") else None
        out[bench["full_id"]] = {"median": median, "per": per}
    return out


def printed_lines(path):
    """The lines a bench printed itself (accuracy tables), without cargo's and criterion's."""
    if not os.path.exists(path):
        return []
    out = []
    with open(path, errors="replace") as f:
        for line in f:
            s = line.rstrip("\n")
            if not s.strip() or s.strip().startswith(NOISE):
                continue
            out.append(s)
    return out


def read_goals(run):
    goals = {}
    path = os.path.join(run, "goals.txt")
    if os.path.exists(path):
        with open(path) as f:
            for line in f:
                if line.strip() and not line.startswith("#"):
                    key, _, value = line.strip().partition(" ")
                    goals[key] = value.strip()
    return goals


def read_machine(run):
    """The last description of the machine in machine.txt and the benches that failed."""
    fields, failed = {}, []
    path = os.path.join(run, "machine.txt")
    if os.path.exists(path):
        with open(path) as f:
            for line in f:
                key, _, value = line.strip().partition(": ")
                if key in ("cpu", "memory", "rustc"):
                    fields[key] = value
                elif line.startswith("bench failed: "):
                    failed.append(line.strip()[len("bench failed: "):].split(" ")[0])
    return fields, sorted(set(failed))


def read_csv(path):
    if not os.path.exists(path):
        return []
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def num(row, *keys):
    for k in keys:
        v = row.get(k)
        if v not in (None, "", "n/a"):
            try:
                return float(v)
            except ValueError:
                pass
    return None


def group_of(series):
    return series.split("/")[0]


def split_outside_parens(text, sep=";"):
    """`text` split at each `sep` that is not inside parentheses."""
    parts, depth, start = [], 0, 0
    for i, ch in enumerate(text):
        depth += (ch == "(") - (ch == ")")
        if ch == sep and depth == 0:
            parts.append(text[start:i])
            start = i + 1
    return parts + [text[start:]]


GENERATED = ("Goals", "Error next to time, per scene", "Per crate")


def current_sections(path):
    """The `## ` sections of the current page: {title: text}, and per generated section
    (None: the page's top) the hand sections that follow it, in order."""
    try:
        with open(path, encoding="utf-8") as f:
            text = f.read()
    except OSError:
        return {}, {}
    sections, after, last = {}, {}, None
    for part in re.split(r"(?m)^(?=## )", text)[1:]:
        title = part[3:].split("\n", 1)[0].strip()
        sections[title] = part
        if title in GENERATED:
            last = title
        else:
            after.setdefault(last, []).append(part)
    return sections, after


def short_reason(detail):
    """A skip reason without the "method X cannot render this scene:" prefix and the lists:
    its first clause, or its second when the first only says what the method renders."""
    text = detail or ""
    method = ""
    m = re.match(r"method (\S+) cannot render this scene: (.*)", text)
    if m:
        method, text = m.groups()
    clauses = [c.strip() for c in split_outside_parens(text)]
    if len(clauses) > 1 and method and clauses[0].startswith(method + " "):
        return re.sub(r"\s*\(.*\)$", "", clauses[1])
    return clauses[0]


def compare_header(path):
    """(size, reference) from the first lines of `mblur compare`'s results.md."""
    size = ref = None
    if os.path.exists(path):
        with open(path) as f:
            for line in f:
                m = re.match(r"# mblur compare: \S+ \((\d+ x \d+)\)", line)
                if m:
                    size = m.group(1).replace(" x ", "x")
                m = re.match(r"- reference: (.*)", line)
                if m:
                    ref = m.group(1).strip()
    return size, ref


# ---------------------------------------------------------------- the analytic goal


def reach_interval(pts, target):
    """When one traversal's spp ladder of (time, PSNR) runs reaches `target`, as a time
    interval (lo, hi]: a crossing between two runs, interpolated on (log time, PSNR), is
    exact (t, t); a ladder whose cheapest run is already there gives (0, t_first] (fewer
    samples might do); one that never gets there gives (t_last, inf). A crossing into an
    infinite PSNR (an exact image) is not interpolated: (t_before, t_exact]. None for an
    empty ladder.
    """
    pts = sorted(pts)
    if not pts:
        return None
    if pts[0][1] >= target:
        return (0.0, pts[0][0])
    for (t0, p0), (t1, p1) in zip(pts, pts[1:]):
        if p0 < target <= p1:
            if math.isinf(p1):
                return (t0, t1)
            f = (target - p0) / (p1 - p0)
            t = math.exp(math.log(t0) + f * (math.log(t1) - math.log(t0)))
            return (t, t)
    return (pts[-1][0], math.inf)


def stochastic_time(series, target):
    """The time stochastic needs for `target` dB, as an interval (lo, hi] over all its
    traversals (the fastest counts: the minimum of the lows and of the highs). None without
    a stochastic run.
    """
    ivs = [(name, reach_interval(pts, target)) for name, pts in series.items()]
    ivs = [(name, iv) for name, iv in ivs if iv is not None]
    if not ivs:
        return None
    lo_name, (lo, _) = min(ivs, key=lambda x: x[1][0])
    _, (_, hi) = min(ivs, key=lambda x: x[1][1])
    return {"lo": lo, "hi": hi, "lo_series": lo_name}


def compared(t_a, setting, p_a, series, target):
    """Analytic (`setting`, `p_a` dB in `t_a` s) against the time stochastic needs for
    `target` dB: the ratio t_a / t_s as an interval and the verdict on "<= 1/10" ("yes"
    when even its upper end is, "no" when even its lower end is not, else "undetermined").
    """
    st = stochastic_time(series, target)
    if st is None:
        return None
    r_lo = 0.0 if math.isinf(st["hi"]) else t_a / st["hi"]
    r_hi = math.inf if st["lo"] == 0 else t_a / st["lo"]
    verdict = "yes" if r_hi <= 0.1 else ("no" if r_lo > 0.1 else "undetermined")
    return {"setting": setting, "psnr": p_a, "t_a": t_a, "target": target,
            "r_lo": r_lo, "r_hi": r_hi, "verdict": verdict, **st}


def stochastic_cell(c, series):
    """The time stochastic needs, for the goal table."""
    lo, hi = c["lo"], c["hi"]
    if lo == hi:
        return f"{hi:.3g} s"
    if math.isinf(hi):
        pts = sorted(series[c["lo_series"]])
        best = max(p for _, p in pts)
        text = f"> {lo:.3g} s ({best:.1f} dB at most"
        if not math.isinf(c["target"]) and len(pts) >= 2 and pts[-1][1] > pts[-2][1]:
            (t0, p0), (t1, p1) = pts[-2], pts[-1]
            slope = (p1 - p0) / (math.log(t1) - math.log(t0))
            est = math.exp(math.log(t1) + (c["target"] - p1) / slope)
            text += f"; ~{est:.3g} s extrapolated"
        return text + ")"
    if lo == 0:
        return f"<= {hi:.3g} s (its cheapest run)"
    return f"{lo:.3g}-{hi:.3g} s"


def ratio_cell(c):
    lo, hi = c["r_lo"], c["r_hi"]
    if lo == hi:
        return f"{lo:.3g}"
    if lo == 0:
        return f"< {hi:.3g}"
    if math.isinf(hi):
        return f">= {lo:.3g}"
    return f"{lo:.3g}-{hi:.3g}"


RANK = {"yes": 0, "undetermined": 1, "no": 2}


def analytic_vs_stochastic(rows):
    """The goal's comparisons, from `mblur compare`'s results.csv.

    `equal` (the goal: equal PSNR): over the analytic settings that reach 40 dB, the one
    with the best verdict against the time stochastic needs for that setting's own PSNR.
    `at_target` (the comparison at 40 dB itself): the fastest analytic setting reaching
    40 dB against the time stochastic needs for 40 dB. `refused`: the reason stochastic
    gave when none of its runs finished. Returns a dict, or None without rows.
    """
    done = [r for r in rows if r.get("status") == "ok"]
    if not done:
        return None
    a = [(num(r, "time_ms") / 1e3, r.get("setting"), num(r, "psnr_db")) for r in done
         if r.get("series") == "analytic" and num(r, "time_ms") is not None and num(r, "psnr_db") is not None]
    reach = sorted(x for x in a if x[2] >= TARGET_DB)
    series = {}
    for r in done:
        if r.get("series", "").startswith("stochastic"):
            t, p = num(r, "time_ms"), num(r, "psnr_db")
            if t is not None and p is not None:
                series.setdefault(r["series"], []).append((t / 1e3, p))
    out = {"series": series, "reach": reach,
           "best_analytic": max(a, key=lambda x: x[2], default=None)}
    out["refused"] = None
    if not series:
        out["refused"] = next((short_reason(r.get("detail")) for r in rows
                               if r.get("series", "").startswith("stochastic") and r.get("detail")), None)
    equal = [c for c in (compared(t, s, p, series, p) for t, s, p in reach) if c is not None]
    out["equal"] = min(equal, key=lambda c: (RANK[c["verdict"]], c["r_hi"], c["r_lo"]), default=None)
    out["at_target"] = compared(*reach[0], series, TARGET_DB) if reach else None
    return out


def analytic_cell(c):
    return f"{c['setting']}: {fmt_db(c['psnr'])} dB in {fmt_ms(c['t_a'] * 1e3)} ms"


# ---------------------------------------------------------------- the compare tables


def pick_rows(rows):
    """The rows of one scene's compact table: per method, the fastest run reaching 40 dB
    and the most accurate run (the fastest of those with the best PSNR), each tagged with
    why it is there and whether it is on the time/PSNR front of all runs of the scene."""
    done = []
    for r in rows:
        t, p = num(r, "time_ms"), num(r, "psnr_db")
        if r.get("status") == "ok" and t is not None and p is not None:
            done.append((r, t, p))
    picked = []
    for g in GROUPS:
        mine = [x for x in done if group_of(x[0].get("series", "")) == g]
        if not mine:
            continue
        why = {}
        reach = [x for x in mine if x[2] >= TARGET_DB]
        if reach:
            first = min(reach, key=lambda x: x[1])
            why.setdefault(id(first[0]), [first, []])[1].append(f"fastest >= {TARGET_DB:.0f} dB")
        top = max(x[2] for x in mine)
        best = min((x for x in mine if x[2] == top), key=lambda x: x[1])
        why.setdefault(id(best[0]), [best, []])[1].append("most accurate")
        for x, reasons in sorted(why.values(), key=lambda v: v[0][1]):
            r, t, p = x
            # PSNR compared as the table shows it (two decimals), so a difference in the
            # fifth digit does not decide the front.
            q = lambda v: v if math.isinf(v) else round(v, 2)
            front = not any(t2 <= t and q(p2) >= q(p) and (t2 < t or q(p2) > q(p)) for _, t2, p2 in done)
            picked.append((r, t, p, ", ".join(reasons), front))
    skipped = {}
    for r in rows:
        g = group_of(r.get("series", ""))
        if r.get("status") != "ok" and not any(group_of(x[0].get("series", "")) == g for x in done):
            skipped.setdefault(g, short_reason(r.get("detail")))
    return picked, skipped


def compare_table(w, rows, quiet=()):
    """One scene's compact table; skipped methods are listed below it, except `quiet` ones."""
    picked, skipped = pick_rows(rows)
    skipped = {g: why for g, why in skipped.items() if g not in quiet}
    w("| method | setting | time (ms) | PSNR (dB) | SSIM | peak heap (MiB) | row | on the front |\n")
    w("|---|---|---:|---:|---:|---:|---|---|\n")
    for r, t, p, why, front in picked:
        ssim = num(r, "ssim")
        heap = num(r, "peak_heap_bytes")
        w(f"| {r.get('series')} | {r.get('setting')} | {fmt_ms(t)} | {fmt_db(p)} | "
          f"{'n/a' if ssim is None else f'{ssim:.4f}'} | "
          f"{'n/a' if heap is None else f'{heap / 1048576:.2f}'} | {why} | {'yes' if front else ''} |\n")
    if skipped:
        w("\nNot run: " + "; ".join(f"{g}, {why}" for g, why in skipped.items()) + ".\n")


# ---------------------------------------------------------------- per-crate headlines
#
# Each crate has a few headline sentences, each a function of the crate's criterion
# estimates `c` ({full_id: {"median", "per"}}) and printed lines `p`. A sentence whose input
# is missing from the run (a KeyError, a failed match) is left out.


def find(lines, pattern):
    """The groups of the first printed line matching `pattern` (KeyError if none)."""
    rx = re.compile(pattern)
    for line in lines:
        m = rx.search(line)
        if m:
            return m.groups()
    raise KeyError(pattern)


def block(lines, start, stop=r"^(==|##|motion |line integral|erf alone|setting )"):
    """The printed lines after the first one matching `start`, up to the next heading."""
    out, inside = [], False
    for line in lines:
        if inside and re.search(stop, line):
            break
        if inside:
            out.append(line)
        if not inside and re.search(start, line):
            inside = True
    return out


def md_rows(lines):
    """The cells of the markdown table rows among `lines`."""
    return [[c.strip() for c in l.strip().strip("|").split("|")] for l in lines if l.startswith("|")]


def per(c, key):
    v = c[key]["per"]
    if v is None:
        raise KeyError(key)
    return v


def med(c, key):
    return c[key]["median"]


def x(a, b):
    return f"{a / b:.2f}x"


def edge_eqn(c, p):
    def ratios(prec):
        rx = re.compile(r"^\s*(\d+)\s+([\d.]+)\s+([\d.]+)\s+([\d.]+)\s+([\d.]+)$")
        rs = [float(m.group(4)) for m in map(rx.match, block(p, rf"^== {prec}: cost")) if m]
        return min(rs), max(rs)

    def solve():
        (lo32, hi32), (lo64, hi64) = ratios("f32"), ratios("f64")
        return (f"One analytic coverage solve (three edge quadratics, up to four spans): "
                f"{fmt_time(per(c, 'coverage_f32/analytic'))} (f32) / {fmt_time(per(c, 'coverage_f64/analytic'))} "
                f"(f64) per pixel, the cost of {lo32:.1f}-{hi32:.1f} / {lo64:.1f}-{hi64:.1f} inside tests "
                f"(interleaved rounds, N = 1-64; goal < 8: {'yes' if max(hi32, hi64) < 8 else 'no'}).")

    def error():
        err = find(p, r"analytic f32: max \|error\| ([\d.e+-]+)")[0]
        s16 = find(p, r"stochastic N = 16: RMS error ([\d.e+-]+)")[0]
        return f"Covered-time error of the f32 solve against f64: {err} at most; 16 stochastic samples: RMS {s16}."

    def one_pass():
        sep, one, sp = find(p, r"^f32: per sample .*inside_at \+ depth_at (\S+ ns), inside_depth_at (\S+ ns) \((\S+)\)")
        return f"Inside test and depth in one pass (`inside_depth_at`, f32): {one} per sample against {sep} separately ({sp})."

    def roots():
        return (f"Quadratic solver `real_roots`: {fmt_time(per(c, 'real_roots/f32'))} (f32) / "
                f"{fmt_time(per(c, 'real_roots/f64'))} (f64) per solve.")

    return [solve, error, one_pass, roots]


def bilinear_patch(c, p):
    k = "ray_vs_patch_prepared/{}/{}"

    def fast():
        fp = [per(c, k.format(f, "fast_patch_ray_space_shared_ray")) for f in ("f32", "f64")]
        mt = [per(c, k.format(f, "two_moller_trumbore_prepared")) for f in ("f32", "f64")]
        met = "yes" if max(a / b for a, b in zip(fp, mt)) <= 1 else "no"
        return (f"Ray vs one bilinear patch, prepared, per ray: `FastPatch::intersect_ray` {fmt_time(fp[0])} (f32) / "
                f"{fmt_time(fp[1])} (f64) against two Möller-Trumbore triangle tests {fmt_time(mt[0])} / "
                f"{fmt_time(mt[1])}: {x(fp[0], mt[0])} / {x(fp[1], mt[1])} (goal \"the patch test costs no more "
                f"than the two triangle tests\": {met}).")

    def watertight():
        wp = [per(c, k.format(f, "prepared_patch")) for f in ("f32", "f64")]
        wt = [per(c, k.format(f, "two_watertight_shared_ray")) for f in ("f32", "f64")]
        return (f"Watertight: `PreparedPatch` {fmt_time(wp[0])} / {fmt_time(wp[1])} against two watertight "
                f"triangles {fmt_time(wt[0])} / {fmt_time(wt[1])} ({x(wp[0], wt[0])} / {x(wp[1], wt[1])}).")

    def prism():
        q = "coverage_per_pixel/{}/{}"
        pr = [per(c, q.format(f, "prism")) for f in ("f32", "f64")]
        ee = [per(c, q.format(f, "edge_eqn")) for f in ("f32", "f64")]
        agree = find(p, r"prism f64 vs edge-eqn f64\s+mean \S+\s+max (\S+)")[0]
        return (f"Prism coverage of a moving triangle at a pixel centre: {fmt_time(pr[0])} (f32) / "
                f"{fmt_time(pr[1])} (f64) against edge-eqn's {fmt_time(ee[0])} / {fmt_time(ee[1])} "
                f"({x(pr[0], ee[0])} / {x(pr[1], ee[1])}); they agree to {agree} of the shutter (f64, constant w).")

    return [fast, watertight, prism]


def tmsnet(c, p):
    def quality():
        rx = re.compile(r"^\s*(permuted|original|stratified)\s+(\d+)\s+(\d+)\s+([\d.]+)\s+([\d.]+)\s+([\d.]+)$")
        return {(m.group(1), m.group(2)): (m.group(4), m.group(6)) for m in map(rx.match, p) if m}

    def per_sample():
        return (f"Per sample (m = 8): incremental iterator {fmt_time(per(c, 'per_sample/incremental_iter/8'))}, "
                f"table lookup {fmt_time(per(c, 'per_sample/table_lookup/8'))}, two `SmallRng` draws "
                f"{fmt_time(per(c, 'per_sample/small_rng_2xu32/8'))}, random access `get_xy` "
                f"{fmt_time(per(c, 'per_sample/get_xy/8'))} (the paper's loop: "
                f"{fmt_time(per(c, 'per_sample/get_xy_paper_loop/8'))}).")

    def tile():
        q = quality()
        return (f"4x4-pixel tile at 16 spp: the permuted net costs {fmt_time(per(c, 'generate_tile/permuted/16'))} "
                f"per sample against {fmt_time(per(c, 'generate_tile/stratified/16'))} for stratified random, "
                f"star discrepancy {q[('permuted', '16')][0]} against {q[('stratified', '16')][0]}.")

    def distance():
        q = quality()
        return (f"Closest sample pair in a pixel at 256 spp (mean over pixels): {q[('permuted', '256')][1]} px "
                f"(permuted) against {q[('original', '256')][1]} px (original Grünschloß-Keller order).")

    return [per_sample, tile, distance]


def interval_buffer(c, p):
    def table():
        return {(r[0], r[1], r[2]): r for r in md_rows(p) if len(r) == 7}

    def paper():
        t = table()
        return (f"Compression at K = 8 (260 bytes per pixel), moving meshes: the paper's oracle, mean error "
                f"{t[('meshes', '8', 'paper')][3]} at {fmt_time(per(c, 'compress_k8/meshes_paper'))} per interval "
                f"(K = 4: {t[('meshes', '4', 'paper')][3]}, K = 16: {t[('meshes', '16', 'paper')][3]}).")

    def ours():
        t = table()
        return (f"Our coverage-preserving merge (opt-in): the fence at K = 4 {t[('fence', '4', 'coverage (ours)')][3]} "
                f"against the paper's {t[('fence', '4', 'paper')][3]}, but moving meshes at K = 8 "
                f"{t[('meshes', '8', 'coverage (ours)')][3]} against {t[('meshes', '8', 'paper')][3]}.")

    def exact():
        mean, mx = find(p, r"mean ([\d.]+) / max (\d+) per pixel")
        return (f"Exact lists (count, scan, fill, sort): {fmt_time(per(c, 'insert/exact_all_passes'))} per interval "
                f"against {fmt_time(per(c, 'insert/bounded_k8'))} for bounded K = 8 insertion with compression; "
                f"{mean} intervals per pixel on average ({mx} at most) of 32 bytes each.")

    def compact():
        s = {(r[0], r[1]): r for r in md_rows(p) if len(r) == 5}
        return (f"Compact intervals: 16 bytes (u16 times) mean error {s[('meshes', 'compact u16 times')][3]}, "
                f"12 bytes (Gribel's u8 times) {s[('meshes', 'compact u8 times (Gribel)')][3]} on meshes.")

    return [paper, ours, exact, compact]


def resolve(c, p):
    def dense():
        rows = md_rows(block(p, r"^## resolve time per pixel .*dense"))
        row = next(r for r in rows if r[0] == "1024")
        exp = next(r for r in rows if r[0].startswith("exponent"))
        nlogn = find(p, r"n log n over the same range: ([\d.]+)")[0]
        a, b = float(row[1]), float(row[2])
        return (f"Dense pixel (all n intervals overlap), n = 1024, opaque: the default sweep {b:.3g} µs against "
                f"Rønnow's Algorithm 1 (active list) {a:.4g} µs ({a / b:.0f}x); growth exponent over n = 64-1024 "
                f"{exp[2]} against {exp[1]} (n log n: {nlogn}).")

    def sparse():
        return (f"Sparse pixel (about 8 active), n = 1024: {fmt_time(med(c, 'resolve_pixel_sparse/opaque/1024'))} "
                f"opaque, {fmt_time(med(c, 'resolve_pixel_sparse/transparent+x/1024'))} transparent with "
                f"intersection handling.")

    def termination():
        et = {r[0]: r for r in md_rows(block(p, r"^## early termination"))}
        e0, e4 = et["0e0"], et["1e-4"]
        return (f"Early termination at the default threshold 1e-4 (transparent, dense, n = 256): error {e4[3]}, "
                f"{fmt_time(float(e4[4]) * 1e3)} per pixel against {fmt_time(float(e0[4]) * 1e3)} without.")

    def texture():
        tx = {r[0]: r for r in md_rows(block(p, r"^## texture filtering"))}
        return (f"Texture along 32 texels of UV motion: exact bilinear integral {float(tx['exact'][4]):.3g} µs per "
                f"pixel; 8 taps {float(tx['8 taps'][4]):.3g} µs with error {tx['8 taps'][3]}, 64 taps "
                f"{float(tx['64 taps'][4]):.3g} µs with {tx['64 taps'][3]}.")

    return [dense, sparse, termination, texture]


def ewa_splat(c, p):
    r = lambda name: med(c, f"line_integral_256_renderer/{name}")
    wd = lambda name: med(c, f"line_integral_256_wide/{name}")

    def renderer():
        lines = block(p, r"^line integral, renderer")
        err = find(lines, r"closed form, erf Full\s+(\S+)")[0]
        tuned = find(lines, r"quad_gk15_plain, tol \S+\s+(\S+)")[0]
        full, tq, rq = r("closed_form_Full"), r("quad_gk15_plain_at_1e-6"), r("quad_gk15_plain_requested_1e-6")
        return (f"Line integral (Eq. 19), 256 renderer lines: closed form {fmt_time(full)}, max relative error "
                f"{err}; adaptive G7-K15 at the loosest tolerance that meets 1e-6 ({tuned}) {fmt_time(tq)} "
                f"({x(tq, full)} the closed form), asked for 1e-6 {fmt_time(rq)} ({x(rq, full)}); "
                f"goal 20x: {'yes' if tq >= 20 * full else 'no'}.")

    def wide():
        f, q, s = wd("closed_form_Full"), wd("quad_gk15_plain_at_1e-6"), wd("quad_simpson_peak_breaks_at_1e-6")
        return (f"Wide lines (a narrow Gaussian over a long interval): closed form {fmt_time(f)} against G7-K15 "
                f"{fmt_time(q)} ({q / f:.0f}x) and adaptive Simpson {fmt_time(s)} ({s / f:.0f}x).")

    def render():
        rows = {m[0]: m for m in (l.split() for l in p) if len(m) == 4}
        k = "render_200_splats_64x64/{}"
        return (f"200 splats, 64x64: A-buffer {fmt_time(med(c, k.format('abuffer_full')))}, max error "
                f"{rows['abuffer_full'][2]}; the approximate GPU passes {fmt_time(med(c, k.format('approx_1sub')))} "
                f"with 1 subframe (max error {rows['approx_1sub'][2]}), "
                f"{fmt_time(med(c, k.format('approx_16sub')))} with 16 (max {rows['approx_16sub'][2]}).")

    return [renderer, wide, render]


def raster_hier(c, p):
    def tables():
        tests, cpu, motion, section = {}, {}, None, None
        for l in p:
            m = re.match(r"^motion (\S+) ", l)
            if m:
                motion, section = m.group(1), "tests"
            elif l.startswith("traversal ") and "min ms" in l:
                section = "time"
            elif l.startswith("1 thread"):
                section = "cpu"
            elif section == "tests" and (m := re.match(r"^(\S.*?)\s{2,}(\d+)\s+([\d.]+)\s", l)):
                tests[(motion, m.group(1))] = m.group(3)
            elif section == "cpu" and (m := re.match(r"^(\S.*?)\s{2,}([\d.]+)\s+([\d.]+)$", l)):
                cpu[(motion, m.group(1))] = m.group(3)
        return tests, cpu

    fine, lin = "OUR lin per level ↓1", "OUR lin per level"

    def samples():
        tests, _ = tables()
        return (f"Table 2 scene (Munkberg 2011), 1x motion: `RasterConfig::fine()` (levels 16 → 1) tests "
                f"{tests[('1x', fine)]} of CONVEX's samples (goal <= 1/4), the default levels 16 → 8 → 4 "
                f"{tests[('1x', lin)]}.")

    def cpu_time():
        _, cpu = tables()
        ms = [m for m in ("0.25x", "1x", "2x", "4x") if (m, fine) in cpu and (m, lin) in cpu]
        if not ms:
            raise KeyError("cpu")
        return (f"1-thread CPU time against CONVEX's at {' / '.join(ms)} motion: `fine()` "
                f"{' / '.join(cpu[(m, fine)] for m in ms)}, default levels {' / '.join(cpu[(m, lin)] for m in ms)}.")

    def threads():
        sp = find(p, r"speed-up \(wall\) ([\d.]+)")[0]
        k = "throughput_1000_tris_16spp/OUR lin, {} thread(s)"
        return (f"1000 triangles, 512x512, 16 spp: {fmt_time(med(c, k.format(1)))} per frame on 1 thread, "
                f"{fmt_time(med(c, k.format(2)))} on 2 (speed-up {sp}).")

    return [samples, cpu_time, threads]


def mblur(c, p):
    def static():
        text, ratio = find(p, r"^goal static: (.*), ratio ([\d.]+)")
        return f"Static scene through `auto` against the static path: {text}, ratio {ratio} (goal <= 1.1)."

    def accum():
        rx = re.compile(r"^accum crossing-quads \S+ N=\s*(\d+): RMS vs N=1024 even ([\d.e+-]+)")
        rms = {m.group(1): m.group(2) for m in map(rx.match, p) if m}
        return ("accum on crossing-quads 96x72, RMS against 1024 sub-frames: "
                + ", ".join(f"N = {n}: {rms[n]} in {fmt_time(med(c, f'accum/crossing-quads/N={n}'))}"
                            for n in ("4", "16", "64")) + ".")

    return [static, accum]


HEADLINES = {
    "edge-eqn": edge_eqn,
    "bilinear-patch": bilinear_patch,
    "tmsnet": tmsnet,
    "interval-buffer": interval_buffer,
    "resolve": resolve,
    "ewa-splat": ewa_splat,
    "raster-hier": raster_hier,
    "mblur": mblur,
}


def headlines(crate, c, p):
    """The crate's headline sentences whose inputs are in the run."""
    out = []
    for sentence in HEADLINES[crate](c, p):
        try:
            out.append(sentence())
        except (KeyError, IndexError, ValueError, TypeError, StopIteration, ZeroDivisionError):
            pass
    return out


# ---------------------------------------------------------------- the page


def main():
    run = sys.argv[1]
    docs = sys.argv[2] if len(sys.argv) > 2 else "docs"
    goals = read_goals(run)
    machine, failed = read_machine(run)
    os.makedirs(os.path.join(docs, "benchmarks"), exist_ok=True)
    w = sys.stdout.write
    old, carried = current_sections(os.path.join(docs, "BENCHMARKS.md"))
    crit = os.path.join(run, "criterion")
    crates_run = os.path.isdir(crit) and any(os.scandir(crit))

    def carry(after):
        for part in carried.get(after, []):
            w(part.rstrip("\n") + "\n\n")

    w("# Benchmarks\n\n")
    w("Current figures of the renderer and of every crate. The Goals tables, the per-scene\n")
    w("compare tables and the per-crate figures are generated: `scripts/benchmarks` measures them\n")
    w("and `scripts/bench_report.py` writes them,\n\n")
    w("```sh\nscripts/benchmarks   # about an hour on 2 cores; needs python3 and bc\n```\n\n")
    w("The other sections (the Pareto check, curved motion, lit surfaces, antialiasing, the\n")
    w("instruction counts and what `--intervals K` buys) each come from the command they name\n")
    w("(`scripts/pareto` for the Pareto check); the report script carries them over from the\n")
    w("current page unchanged.\n\n")
    cpu = machine.get("cpu", "")
    cpu = f"{cpu.replace(' x ', ', ')} cores" if " x " in cpu else cpu
    rustc = " ".join(machine.get("rustc", "").split()[:2])
    desc = ", ".join(v for v in (cpu, machine.get("memory", ""), rustc) if v)
    w(f"Machine: {desc or 'not recorded'}. Every table and figure below also names the command\n")
    w("that measures it alone; each crate's BENCHMARKS.md holds the analysis behind its figures.\n")
    if failed:
        w(f"Benches that failed in this run (their figures are missing): {', '.join(failed)}.\n")
    w("\n")
    carry(None)

    # Goals.
    w("## Goals\n\n")
    w("\"Analytic reaches PSNR >= 40 dB against the reference on every built-in scene except the\n")
    w("fence at small K, in at most 1/10 of the time stochastic needs for the same PSNR.\" Per scene\n")
    w("the analytic setting with the best verdict is set against the time stochastic needs for that\n")
    w("setting's own PSNR, interpolated on its spp ladder in log time (beyond the ladder only a\n")
    w("bound is known: \"<\", \">=\"); \"at 40 dB\" sets the fastest analytic setting reaching 40 dB\n")
    w("against stochastic's time for 40 dB, a harder test, since stochastic reaches 40 dB with a few\n")
    w("samples per pixel while analytic's cost depends little on its PSNR. Met when the whole ratio\n")
    w("range is <= 1/10. Times are those of the compare tables below.\n\n")
    w("| scene | analytic | stochastic, same PSNR | ratio | met? | at 40 dB: analytic | stochastic | ratio | met? |\n")
    w("|---|---|---|---:|---|---|---|---:|---|\n")
    for scene in SCENES:
        res = analytic_vs_stochastic(read_csv(os.path.join(run, "compare", scene, "results.csv")))
        if res is None:
            w(f"| {scene} | not run | | | | | | | |\n")
            continue
        eq, at = res["equal"], res["at_target"]
        na = "n/a (nothing moves)" if scene in MOTIONLESS else None
        if not res["reach"]:
            best = res["best_analytic"]
            a = f"best {best[1]}: {fmt_db(best[2])} dB" if best else "no run"
            w(f"| {scene} | {a} (below {TARGET_DB:.0f} dB) | | | {na or 'no'} | | | | |\n")
            continue
        if eq is None:
            t_a, setting, p_a = max(res["reach"], key=lambda v: v[2])
            why = res["refused"] or "no stochastic run finished"
            w(f"| {scene} | {setting}: {fmt_db(p_a)} dB in {fmt_ms(t_a * 1e3)} ms | refused: {why} | | n/a | | | | |\n")
            continue
        cells = [analytic_cell(eq), stochastic_cell(eq, res["series"]), ratio_cell(eq), na or eq["verdict"]]
        if at is not None:
            cells += [analytic_cell(at), stochastic_cell(at, res["series"]), ratio_cell(at), na or at["verdict"]]
        else:
            cells += ["", "", "", ""]
        w(f"| {scene} | " + " | ".join(cells) + " |\n")
    if any(k in goals for k in ("static_ratio", "ronnow_1024_s", "clothball_1024_s", "speedup")):
        w("\n| goal | measured | met? |\n|---|---|---|\n")
    static_goal = "| a static scene through `auto` costs <= 1.1x the static path (`cargo bench -p mblur --bench goals`) | "
    if "static_ratio" in goals:
        r = float(goals["static_ratio"])
        w(static_goal + f"{goals.get('static_text', '').rstrip(';')}: ratio {r:.3f} | {'yes' if r <= 1.1 else 'no'} |\n")
    elif not crates_run:
        w("".join(line + "\n" for line in old.get("Goals", "").splitlines() if line.startswith(static_goal)))
    ronnow = "Rønnow 2021 Table 1: 9.4 ms on an RTX 2080, 2.45 M intervals, at most 128 per pixel"
    render = ("`mblur render SCENE --method analytic --width 1024 --height 1024 --threads 2`, median of 3, "
              "scene preparation and file write included")
    if "ronnow_1024_s" in goals:
        t = float(goals["ronnow_1024_s"])
        w(f"| `clothball-ronnow-unlit` (Rønnow's scene and amount of motion) 1024x1024 analytic < 2 s on 2 cores ({ronnow}; {render}) | "
          f"{t:.2f} s; intervals: {intervals_text(goals.get('ronnow_text', ''))} | {'yes' if t < 2 else 'no'} |\n")
        w(f"| the same <= 0.2 s | {t:.2f} s | {'yes' if t <= 0.2 else 'no'} |\n")
    if "clothball_1024_s" in goals:
        t = float(goals["clothball_1024_s"])
        w(f"| the same on `clothball-unlit`, our heavy variant (moving ~400 px and spinning 35° in the shutter) | "
          f"{t:.2f} s; intervals: {intervals_text(goals.get('clothball_text', ''))} | {'yes' if t < 2 else 'no'} |\n")
    if "speedup" in goals:
        s = float(goals["speedup"])
        w(f"| 1 -> 2 threads >= 1.7x (`clothball-unlit`, as above with `--threads 1` and `2`, interleaved) | "
          f"{s:.2f}x ({goals.get('speedup_text', '').split(': ', 1)[-1]}) | {'yes' if s >= 1.7 else 'no'} |\n")
    w("\n")
    carry("Goals")

    # Compare tables.
    scene_rows = {scene: read_csv(os.path.join(run, "compare", scene, "results.csv")) for scene in SCENES}
    skips = [pick_rows(rows)[1] for rows in scene_rows.values() if rows]
    everywhere = {g: why for g, why in (skips[0].items() if skips else []) if all(g in s for s in skips)}
    w("## Error next to time, per scene\n\n")
    w("```sh\n")
    w(f"cargo run --release -p mblur-cli -- compare SCENE {COMPARE_ARGS} --out out/compare/SCENE\n")
    w("```\n\n")
    w("Each scene at its default size on 2 threads against an accum reference; time is the median\n")
    w("wall time of the repeats, PSNR (peak 1) on linear RGB, SSIM on the sRGB luma; stochastic\n")
    w("samples at the pixel centre, as the reference does. Per method the table keeps the fastest\n")
    w(f"run reaching {TARGET_DB:.0f} dB and the most accurate run; \"on the front\" marks a run that no other\n")
    w("run of the scene beats in both time and PSNR. The linked plot and the command's `results.md`\n")
    w("have every run.")
    if everywhere:
        w(" Not run on any of these scenes: " + "; ".join(f"{g}, {why}" for g, why in everywhere.items()) + ".")
    w(" The lit scenes\nare measured unlit (`SCENE-unlit`: no lights, every material unlit), so these figures\n")
    w("measure motion blur alone; what lighting costs is under "
      "[Lit surfaces](#lit-surfaces-error-and-cost-against-shading-samples).")
    w("\n\n")
    for scene in SCENES:
        d = os.path.join(run, "compare", scene)
        rows = scene_rows[scene]
        size, ref = compare_header(os.path.join(d, "results.md"))
        w(f"### {scene}\n\n")
        if not rows:
            w("Not run.\n\n")
            continue
        head = ", ".join(v for v in (size, f"reference {ref}" if ref else None) if v)
        if head:
            w(head + ".")
        for ext in ("png", "svg"):
            plot = os.path.join(d, f"plot.{ext}")
            if os.path.exists(plot):
                shutil.copy(plot, os.path.join(docs, "benchmarks", f"compare-{scene}.{ext}"))
        if os.path.exists(os.path.join(d, "plot.png")):
            w(f" Plot: [PSNR against time](benchmarks/compare-{scene}.png).")
        w("\n\n")
        compare_table(w, rows, set(everywhere))
        w("\n")

    carry("Error next to time, per scene")

    # Crates.
    if not crates_run and "Per crate" in old:
        w(old["Per crate"].rstrip("\n") + "\n\n")
        carry("Per crate")
        return
    w("## Per crate\n\n")
    for crate in CRATES:
        w(f"### {crate}\n\n")
        c = criterion(os.path.join(run, "criterion", crate))
        p = printed_lines(os.path.join(run, f"{crate}.stderr"))
        lines = headlines(crate, c, p) if (c or p) else []
        if lines:
            for s in lines:
                w(f"- {s}\n")
        else:
            w("No figures in this run.\n")
        w(f"\n`cargo bench -p {crate} {BENCH_ARGS}`; analysis: [{crate}/BENCHMARKS.md](../{crate}/BENCHMARKS.md).\n\n")
    carry("Per crate")


def intervals_text(text):
    """The interval counts from a goals.txt text (after "intervals: ")."""
    return text.split("intervals: ", 1)[-1] if "intervals: " in text else "not recorded"


if __name__ == "__main__":
    main()
