"""What scripts/compare-peers makes of its runs: medians and ratios, the check of issue 9's goals,
the markdown report and the log-log plots (SVG, written by hand: no plotting library here).

Rows are dicts; every row of a comparison has
  case      unique name, e.g. "unstructured wigley.iges 2000 gmsh-nt1"
  section   import, tessellate, unstructured, structured or coarsen
  input     the input's file name; size: the size asked for (triangles, panels, fine triangles)
  peer      the peer's label
  tools     {"hullmesh": summary, peer: summary}, summaries as summarize() gives them
  time_ratio, memory_ratio   peer / hullmesh (above 1: hullmesh is faster or leaner)
  quality   {"hullmesh": figures, "peer": figures} (figures as QUALITY_FIGURES names them)
  counts    {"hullmesh": faces out, "peer": faces out}
  note      why the row has no comparison, or what happened in calibration
The coarsen section's time_ratio is of the stages alone (stage_median_s); see compare-peers.
"""
import math
import statistics

SECTIONS = ("import", "tessellate", "unstructured", "structured", "coarsen")

# (key, label, higher is better). Keys of judge()'s figures.
QUALITY_FIGURES = (
    ("angles_20", "min angle >= 20 deg", True),
    ("angles_30", "min angle >= 30 deg", True),
    ("angles_40", "min angle >= 40 deg", True),
    ("side_ratio_4", "quad side ratio < 4", True),
    ("area_ratio_2", "neighbour area ratio < 2", True),
    ("watertight", "watertight", True),
    ("dev_max_rel", "max deviation / L", False),
    ("dev_mean_rel", "mean deviation / L", False),
)

# Issue 9's per-stage speed goals: peer time / hullmesh time at least this.
SPEED_GOALS = {
    "tessellate": (10, "at least 10x faster than gmsh -2"),
    "unstructured": (10, "at least 10x faster than gmsh -2"),
    "structured": (5, "at least 5x faster than gmsh's quad meshing"),
    "coarsen": (5, "at least 5x faster than CGAL's fastest policy"),
}


def summarize(runs):
    """One tool's runs ({"seconds", "rss_mib", "status"[, "stage_s"]}) as medians over the good
    ones; failures are kept by their status, never dropped."""
    ok = [r for r in runs if r["status"] == "ok"]
    s = {
        "median_s": statistics.median(r["seconds"] for r in ok) if ok else None,
        "peak_rss_mib": max(r["rss_mib"] for r in ok) if ok else None,
        "failures": [r["status"] for r in runs if r["status"] != "ok"],
        "runs": len(runs),
    }
    if any("stage_s" in r for r in runs):
        s["stage_median_s"] = statistics.median(r["stage_s"] for r in ok) if ok else None
        s["stage_runs_s"] = [r.get("stage_s") for r in runs]
    return s


def ratio(hullmesh, peer):
    """peer / hullmesh, None when either is missing or zero."""
    return peer / hullmesh if hullmesh and peer else None


def fmt(x, spec):
    if x is None:
        return "n/a"
    if isinstance(x, bool):
        return "yes" if x else "no"
    return format(x, spec)


def times(r):
    return "n/a" if r is None else f"{r:.2f}x"


def failures_text(tools):
    """["gmsh ...: 5 of 5 failed (killed by SIGSEGV)", ...] for each tool of a row that failed."""
    return [f"{k}: {len(v['failures'])} of {v.get('runs', len(v['failures']))} failed "
            f"({', '.join(sorted(set(v['failures'])))})" for k, v in tools.items() if v["failures"]]


def geomean(xs):
    xs = [x for x in xs if x]
    return math.exp(sum(math.log(x) for x in xs) / len(xs)) if xs else None


# ---- goals -----------------------------------------------------------------------------------

def stage_ratios(rows, section):
    """[(case, ratio or None, why)] of one stage: one entry per case. For coarsen the peer is
    CGAL's fastest policy on that case; for structured gmsh's fastest algorithm that produced a
    mesh. None: no ratio (why says who failed)."""
    by_case = {}
    for r in rows:
        if r.get("section") != section:
            continue
        key = r["case"]
        if section in ("coarsen", "structured", "unstructured"):
            key = f"{section} {r.get('input')} {r.get('size')}"
        by_case.setdefault(key, []).append(r)
    out = []
    for key, group in by_case.items():
        stage = section == "coarsen"

        def seconds(summary):
            return summary and (summary.get("stage_median_s") if stage else summary["median_s"])

        hm = next((r["tools"]["hullmesh"] for r in group if "hullmesh" in r.get("tools", {})), None)
        # Each row against its own hullmesh runs (structured runs hullmesh once per algorithm).
        peers = [(seconds(r["tools"][r["peer"]]), seconds(r["tools"]["hullmesh"]), r["peer"])
                 for r in group if r.get("peer") in r.get("tools", {})]
        peers = [(t, h, label) for t, h, label in peers if t and h]
        if not seconds(hm) and not peers:
            out.append((key, None, "hullmesh failed" if hm else group[0].get("note", "no run")))
        elif not peers:
            out.append((key, None, "every peer failed"))
        else:
            t, h, label = min(peers)
            out.append((key, t / h, label))
    return out


def quality_verdicts(rows, section):
    """{figure key: (better or equal, rows compared, [worse cases])} over a stage's rows."""
    out = {}
    for key, _, higher in QUALITY_FIGURES:
        good, n, worse = 0, 0, []
        for r in rows:
            if r.get("section") != section or "quality" not in r:
                continue
            a, b = r["quality"]["hullmesh"].get(key), r["quality"]["peer"].get(key)
            if a is None or b is None:
                continue
            n += 1
            a, b = float(a), float(b)
            if (a >= b) if higher else (a <= b):
                good += 1
            else:
                worse.append(f"{r['case']} ({fmt(a, '.3g')} vs {fmt(b, '.3g')})")
        if n:
            out[key] = (good, n, worse)
    return out


def goals(rows):
    """The check of issue 9's goals against the rows: one entry per stage."""
    result = []
    for section, (target, text) in SPEED_GOALS.items():
        entries = stage_ratios(rows, section)
        if not entries:
            continue
        got = [x for _, x, _ in entries if x is not None]
        missing = [(k, why) for k, x, why in entries if x is None]
        behind = [(k, x) for k, x, _ in entries if x is not None and x < target]
        quality = quality_verdicts(rows, section)
        q_miss = {k: v for k, v in quality.items() if v[0] < v[1]}
        result.append({
            "stage": section, "goal": text, "target": target, "cases": len(entries),
            "geomean_ratio": geomean(got), "min_ratio": min(got) if got else None,
            "max_ratio": max(got) if got else None, "behind": behind,
            "hullmesh_failed": [k for k, why in missing if why == "hullmesh failed"],
            "peer_failed": [k for k, why in missing if why == "every peer failed"],
            # No run at all (a fine mesh hullmesh merge could not make, gmsh unreadable): why.
            "not_compared": [(k, why) for k, why in missing
                             if why not in ("hullmesh failed", "every peer failed")],
            "speed_met": bool(got) and not behind and not any(
                why == "hullmesh failed" for _, why in missing),
            "quality": {k: {"better_or_equal": v[0], "compared": v[1], "worse": v[2]}
                        for k, v in quality.items()},
            "quality_met": not q_miss and bool(quality),
        })
    return result


def goals_lines(summary):
    lines = ["## Goals (issue 9)", "",
             "Per stage, peer time / hullmesh time over the cases run (for coarsening, CGAL's "
             "fastest policy on each case; for structured, gmsh's fastest algorithm that made a "
             "mesh): geometric mean and range. Quality: in how many rows hullmesh is at least as "
             "good as the peer on each figure (`hullmesh quality` on both outputs).", "",
             "| stage | goal | cases | ratio (geomean, min - max) | speed | quality |",
             "|---|---|---|---|---|---|"]
    for g in summary:
        rng = (f"{fmt(g['geomean_ratio'], '.2f')}x ({fmt(g['min_ratio'], '.2f')} - "
               f"{fmt(g['max_ratio'], '.2f')})")
        q = "met" if g["quality_met"] else ("missed" if g["quality"] else "not measured")
        lines.append(f"| {g['stage']} | {g['goal']} | {g['cases']} | {rng} | "
                     f"{'met' if g['speed_met'] else 'missed'} | {q} |")
    lines += ["", "Stages that miss:", ""]
    missed = False
    for g in summary:
        if not g["speed_met"]:
            missed = True
            parts = [f"{k} {x:.2f}x" for k, x in g["behind"]]
            parts += [f"{k}: hullmesh failed" for k in g["hullmesh_failed"]]
            lines.append(f"- **{g['stage']}**, speed ({g['goal']}): geometric mean "
                         f"{fmt(g['geomean_ratio'], '.2f')}x; behind the goal on "
                         f"{len(g['behind']) + len(g['hullmesh_failed'])} of {g['cases']} cases: "
                         + "; ".join(parts))
        for key, label, _ in QUALITY_FIGURES:
            v = g["quality"].get(key)
            if v and v["better_or_equal"] < v["compared"]:
                missed = True
                lines.append(f"- **{g['stage']}**, quality ({label}): hullmesh behind in "
                             f"{v['compared'] - v['better_or_equal']} of {v['compared']} rows: "
                             + "; ".join(v["worse"][:4]) + ("; ..." if len(v["worse"]) > 4 else ""))
        for k, why in g.get("not_compared", []):
            missed = True
            lines.append(f"- {g['stage']}: no comparison on {k}: {why[:200]}")
        if g["peer_failed"]:
            lines.append(f"- {g['stage']}: every peer failed on {', '.join(g['peer_failed'])} "
                         "(not counted for or against)")
    if not missed:
        lines.append("- none")
    return lines


# ---- markdown --------------------------------------------------------------------------------

def pair(q, key, spec):
    a, b = q["hullmesh"].get(key), q["peer"].get(key)
    return f"{fmt(a, spec)} / {fmt(b, spec)}"


SECTION_TEXT = {
    "import": "Reading the IGES alone: `hullmesh info` against `gmsh -0` (Open CASCADE).",
    "tessellate": "Surface triangulation at the same triangle count: `hullmesh tessellate` "
                  "(2 threads) against `gmsh -2` (Frontal-Delaunay, 2 threads), its size "
                  "calibrated to hullmesh's count.",
    "unstructured": "IGES to a triangle panel mesh of N triangles: `hullmesh unstructured "
                    "--panels N` (2 threads) against `gmsh -2` (Frontal-Delaunay) at 1 and 2 "
                    "threads, its size calibrated to about N triangles.",
    "structured": "IGES to a quad panel mesh of about N panels: `hullmesh structured --panels N` "
                  "(2 threads) against `gmsh -2` recombined by blossom (2 threads), one row per "
                  "gmsh 2D algorithm.",
    "coarsen": "A fine merged triangulation to 4,000 triangles: hullmesh's coarsening "
               "(`hullmesh unstructured --triangles FINE`, 2 threads) against CGAL edge_collapse "
               "(serial, borders constrained). Times are of the stages alone: hullmesh's "
               "`coarsen` line against the driver's edge_collapse call; whole runs (hullmesh's "
               "includes import, tessellation and merge) in the next column.",
}


def section_lines(rows, section, repeat):
    rows = [r for r in rows if r.get("section") == section]
    if not rows:
        return []
    lines = ["", f"## {section}", "", SECTION_TEXT[section] + f" Medians of {repeat} alternating "
             "runs; ratios peer / hullmesh. Quality pairs are hullmesh / peer.", ""]
    quality = section != "import"
    head = "| case | peer | hullmesh s | peer s | time ratio | memory ratio |"
    rule = "|---|---|---|---|---|---|"
    if section == "coarsen":
        head += " whole run s (hullmesh / peer) |"
        rule += "---|"
    if quality:
        head += (" faces out | >= 20 / 30 / 40 deg (hullmesh) | >= 20 / 30 / 40 deg (peer) "
                 "| side ratio < 4 | area ratio < 2 | watertight | max dev / L | mean dev / L |")
        rule += "---|---|---|---|---|---|---|---|"
    lines += [head + " failures, notes |", rule + "---|"]
    for r in rows:
        notes = failures_text(r.get("tools", {}))
        if r.get("note"):
            notes.append(r["note"])
        tools = r.get("tools", {})
        if "hullmesh" not in tools or r.get("peer") not in tools:
            cells = head.count("|") - 3
            lines.append(f"| {r['case']} | {r.get('peer', '')} |" + " |" * cells +
                         f" {'; '.join(notes)} |")
            continue
        th, tp = tools["hullmesh"], tools[r["peer"]]
        stage = section == "coarsen"
        key = "stage_median_s" if stage else "median_s"
        line = (f"| {r['case']} | {r['peer']} | {fmt(th.get(key), '.3f')} | "
                f"{fmt(tp.get(key), '.3f')} | {times(r.get('time_ratio'))} | "
                f"{times(r.get('memory_ratio'))} |")
        if stage:
            line += f" {fmt(th['median_s'], '.2f')} / {fmt(tp['median_s'], '.2f')} |"
        if quality:
            q = r.get("quality") or {"hullmesh": {}, "peer": {}}
            c = r.get("counts", {})
            ang = {k: "/".join(fmt(q[k].get(f"angles_{a}"), ".3f") for a in (20, 30, 40))
                   for k in ("hullmesh", "peer")}
            line += (f" {fmt(c.get('hullmesh'), 'd')} / {fmt(c.get('peer'), 'd')} | "
                     f"{ang['hullmesh']} | {ang['peer']} | {pair(q, 'side_ratio_4', '.3f')} | "
                     f"{pair(q, 'area_ratio_2', '.3f')} | {pair(q, 'watertight', '')} | "
                     f"{pair(q, 'dev_max_rel', '.2e')} | {pair(q, 'dev_mean_rel', '.2e')} |")
        lines.append(line + f" {'; '.join(notes)} |")
    return lines


def markdown(rows, meta, repeat, plots):
    lines = ["# hullmesh against its peers", "",
             f"Run {meta['date']} on {meta['machine']}; wall time {meta.get('wall_s', 0) / 60:.1f} "
             f"min ({', '.join(f'{k} {v:.0f} s' for k, v in meta.get('section_s', {}).items())}). "
             f"Peers: {meta.get('peers', '')}. Made by `scripts/compare-peers "
             f"{meta.get('command') or '--sections all'}`."]
    if meta.get("load_avg"):
        lines[-1] += (" Load average (1 min) before the run and after each section: " +
                      ", ".join(f"{k} {v:.2f}" for k, v in meta["load_avg"].items()) +
                      " (2 cores: above about 2.3, something else competed with the tools).")
    lines.append("")
    lines += goals_lines(goals(rows))
    if plots:
        lines += ["", "## Plots", ""] + [f"![{t}]({f})" for f, t in plots]
    for s in SECTIONS:
        lines += section_lines(rows, s, repeat)
    return "\n".join(lines) + "\n"


# ---- SVG -------------------------------------------------------------------------------------

COLOURS = ("#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b")


def esc(text):
    return str(text).replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")


def tick(v):
    """A decade's label: 0.01, 0.1, 1, 10, 100, 1k, 10k, 100k, 1M, 10M."""
    for unit, suffix in ((1e6, "M"), (1e3, "k")):
        if v >= unit:
            return f"{v / unit:g}{suffix}"
    return f"{v:g}"


def svg_loglog(title, xlabel, ylabel, series, width=780, height=440):
    """A log-log plot: every point of each series as a dot, and a line through the series'
    median y at each x. series: {label: [(x, y), ...]}, x and y > 0 (others are left out)."""
    pts = {k: [(x, y) for x, y in v if x and y and x > 0 and y > 0] for k, v in series.items()}
    allx = [x for v in pts.values() for x, _ in v]
    ally = [y for v in pts.values() for _, y in v]
    left, right, top, bottom = 70, 290, 40, 55
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" '
           f'viewBox="0 0 {width} {height}" font-family="sans-serif" font-size="12">',
           f'<rect width="{width}" height="{height}" fill="white"/>',
           f'<text x="{left}" y="22" font-size="14">{esc(title)}</text>']
    if not allx:
        out.append(f'<text x="{left}" y="{height / 2}">no data</text></svg>')
        return "\n".join(out) + "\n"
    x0, x1 = math.floor(math.log10(min(allx))), math.ceil(math.log10(max(allx)))
    y0, y1 = math.floor(math.log10(min(ally))), math.ceil(math.log10(max(ally)))
    x1, y1 = max(x1, x0 + 1), max(y1, y0 + 1)
    pw, ph = width - left - right, height - top - bottom

    def px(x):
        return left + (math.log10(x) - x0) / (x1 - x0) * pw

    def py(y):
        return top + ph - (math.log10(y) - y0) / (y1 - y0) * ph

    out.append(f'<rect x="{left}" y="{top}" width="{pw}" height="{ph}" fill="none" '
               'stroke="#444"/>')
    for e in range(x0, x1 + 1):
        x = px(10 ** e)
        out.append(f'<line x1="{x:.1f}" y1="{top}" x2="{x:.1f}" y2="{top + ph}" stroke="#ddd"/>')
        out.append(f'<text x="{x:.1f}" y="{top + ph + 16}" text-anchor="middle">'
                   f'{tick(10 ** e)}</text>')
    for e in range(y0, y1 + 1):
        y = py(10 ** e)
        out.append(f'<line x1="{left}" y1="{y:.1f}" x2="{left + pw}" y2="{y:.1f}" stroke="#ddd"/>')
        out.append(f'<text x="{left - 6}" y="{y + 4:.1f}" text-anchor="end">'
                   f'{tick(10 ** e)}</text>')
    out.append(f'<text x="{left + pw / 2}" y="{height - 15}" text-anchor="middle">'
               f'{esc(xlabel)}</text>')
    out.append(f'<text transform="translate(18 {top + ph / 2}) rotate(-90)" '
               f'text-anchor="middle">{esc(ylabel)}</text>')
    for i, (label, v) in enumerate(pts.items()):
        colour = COLOURS[i % len(COLOURS)]
        by_x = {}
        for x, y in v:
            by_x.setdefault(x, []).append(y)
        xs = sorted(by_x)
        if len(xs) > 1:
            path = " ".join(f"{px(x):.1f},{py(statistics.median(by_x[x])):.1f}" for x in xs)
            out.append(f'<polyline points="{path}" fill="none" stroke="{colour}" '
                       'stroke-width="1.5"/>')
        for x, y in v:
            out.append(f'<circle cx="{px(x):.1f}" cy="{py(y):.1f}" r="3" fill="{colour}" '
                       'fill-opacity="0.7"/>')
        ly = top + 10 + 18 * i
        out.append(f'<circle cx="{left + pw + 15}" cy="{ly}" r="4" fill="{colour}"/>')
        out.append(f'<text x="{left + pw + 24}" y="{ly + 4}">{esc(label)}</text>')
    out.append("</svg>")
    return "\n".join(out) + "\n"


def plot_series(rows, section):
    """{tool: [(size, seconds)]} of a section: x is the size asked for (triangles out for
    meshing, fine triangles for coarsening; the counts each tool reached are in the tables), so
    that the line through the medians of the inputs at each size is a ladder; y is the median
    time (the stage time for coarsening)."""
    series = {}
    seen = set()
    for r in rows:
        if r.get("section") != section or r.get("peer") not in r.get("tools", {}):
            continue
        stage = section == "coarsen"
        for label in ("hullmesh", r["peer"]):
            if label == "hullmesh" and (r["input"], r["size"]) in seen:
                continue  # hullmesh's runs are shared by the case's peer rows
            t = r["tools"][label]
            y = t.get("stage_median_s") if stage else t["median_s"]
            series.setdefault(label, []).append((r.get("size"), y))
        seen.add((r["input"], r["size"]))
    return series
