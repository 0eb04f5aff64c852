#!/usr/bin/python3
"""Plots and tables for docs/accuracy.md from lockbox_accuracy's CSVs.

usage: /usr/bin/python3 bench/accuracy/plot_accuracy.py bench/results/<machine>

For each scene: a PNG of the primary error against ms/step for both engines, every sweep
point labelled, the Pareto front (no other point is both faster and more accurate) drawn as
a line; a sweep table; and the cost-of-effects table (stage shares of the step, and what each
effect switch saves in time and costs in accuracy, with the work counters that show an idle
stage doing zero work). The Markdown goes between the markers in docs/accuracy.md.
"""
import csv
import math
import os
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
STAGES = ["collide", "broadphase", "solveInit", "solveVelocity", "solvePosition", "solveTOI"]
COUNTERS = ["contactsUpdated", "manifolds", "contactConstraints", "jointConstraints",
            "velocityIterations", "positionIterations", "toiCandidates", "toiCalls", "toiSubSteps"]


def fnum(s):
    try:
        return float(s)
    except (TypeError, ValueError):
        return math.nan


def pareto(points):
    """Indices of the points no other point beats on both time and error."""
    order = sorted(range(len(points)), key=lambda i: (points[i][0], points[i][1]))
    front, best = [], math.inf
    for i in order:
        if points[i][1] < best:
            front.append(i)
            best = points[i][1]
    return front


def main():
    rdir = os.path.abspath(sys.argv[1])
    machine = os.path.basename(rdir)
    rows = list(csv.DictReader(open(os.path.join(rdir, "accuracy.csv"))))
    eff = defaultdict(dict)
    for r in csv.DictReader(open(os.path.join(rdir, "effects.csv"))):
        eff[(r["scene"], r["engine"], r["config"])][r["stage"]] = fnum(r["value"])
    scenes = []
    for r in rows:
        if r["scene"] not in scenes:
            scenes.append(r["scene"])

    md = [f"Machine `{machine}`; data: `bench/results/{machine}/accuracy.csv`, `effects.csv`.\n"]
    for scene in scenes:
        srows = [r for r in rows if r["scene"] == scene]
        metric = srows[0]["primary_metric"]
        fig, ax = plt.subplots(figsize=(7, 4.5))
        for engine, color in (("lockbox", "tab:blue"), ("box2d-float", "tab:orange")):
            er = [r for r in srows if r["engine"] == engine and not math.isnan(fnum(r["primary"]))]
            if not er:
                continue
            # Cost per simulated second (ms/step x steps per second), so that a smaller time
            # step is charged for the extra steps it needs.
            pts = [(fnum(r["ms_per_step"]) * fnum(r["hz"]), max(fnum(r["primary"]), 1e-7)) for r in er]
            ax.scatter([p[0] for p in pts], [p[1] for p in pts], color=color, s=18, label=engine)
            for r, p in zip(er, pts):
                ax.annotate(r["config"], p, fontsize=6, color=color, xytext=(2, 2), textcoords="offset points")
            front = pareto(pts)
            ax.plot([pts[i][0] for i in front], [pts[i][1] for i in front], color=color, lw=1,
                    marker="o", markersize=9, markerfacecolor="none", label=f"{engine} Pareto front")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("ms per simulated second (ms/step x Hz)")
        ax.set_ylabel(metric)
        ax.set_title(f"{scene}: {metric} vs cost")
        ax.legend(fontsize=7)
        fig.tight_layout()
        png = f"accuracy_{scene}.png"
        fig.savefig(os.path.join(rdir, png), dpi=110)
        plt.close(fig)

        md.append(f"\n### {scene}\n")
        md.append(f"![{scene}](../bench/results/{machine}/{png})\n")
        md.append(f"| config | lockbox ms/step | lockbox {metric} | float ms/step | float {metric} | "
                  f"max_pen lockbox/float | asleep at step lockbox/float |")
        md.append("| --- | ---: | ---: | ---: | ---: | --- | --- |")
        configs = []
        for r in srows:
            if r["config"] not in configs:
                configs.append(r["config"])
        by = {(r["engine"], r["config"]): r for r in srows}
        for c in configs:
            lb, fl = by.get(("lockbox", c)), by.get(("box2d-float", c))
            def g(r, k, fmt="{:.4g}"):
                return fmt.format(fnum(r[k])) if r else "n/a"
            md.append(f"| {c} | {g(lb, 'ms_per_step', '{:.4f}')} | {g(lb, 'primary')} | "
                      f"{g(fl, 'ms_per_step', '{:.4f}')} | {g(fl, 'primary')} | {g(lb, 'max_pen')}/{g(fl, 'max_pen')} | "
                      f"{g(lb, 'all_asleep_step', '{:.0f}')}/{g(fl, 'all_asleep_step', '{:.0f}')} |")

        # Cost of effects (lockbox).
        base = eff.get((scene, "lockbox", "base"))
        if not base:
            md.append("\nCost of effects: lockbox cannot run this scene yet (joints missing).\n")
            continue
        step = base.get("step_ms", 0) or 1e-12
        md.append("\nCost of effects on lockbox: each stage's share of the step at the defaults, with its work "
                  "per step (an idle stage must show 0).\n")
        md.append("| stage | ms/step | share | work per step |")
        md.append("| --- | ---: | ---: | --- |")
        work = {"collide": ["contactsUpdated", "manifolds"], "broadphase": ["pairsFound"],
                "solveInit": ["contactConstraints", "jointConstraints"],
                "solveVelocity": ["velocityIterations", "jointVelocityIterations"], "solvePosition": ["positionIterations"],
                "solveTOI": ["toiCandidates", "toiCalls", "toiSubSteps"]}
        for s in STAGES:
            v = base.get(s + "_ms", 0)
            w = ", ".join(f"{k}={base.get('n_' + k, 0):.1f}" for k in work[s])
            md.append(f"| {s} | {v:.4f} | {100 * v / step:.0f}% | {w} |")
        md.append("\n| switch | ms/step | time saved | " + metric + " | max_pen | TOI calls/step |")
        md.append("| --- | ---: | ---: | ---: | ---: | ---: |")
        md[-2] = md[-2].replace("| max_pen | max_pen |", "| max_pen | max_pen (same) |")
        lbb = by.get(("lockbox", "base"))
        for c in ("base", "warm=off", "continuous=off", "substep=on"):
            e = eff.get((scene, "lockbox", c))
            r = by.get(("lockbox", c))
            if not e or not r:
                continue
            saved = 100 * (1 - e.get("step_ms", 0) / step)
            md.append(f"| {c} | {e.get('step_ms', 0):.4f} | {saved:+.0f}% | {fnum(r['primary']):.4g} | "
                      f"{fnum(r['max_pen']):.4g} | {e.get('n_toiCalls', 0):.2f} |")
    text = "\n".join(md) + "\n"
    doc = os.path.join(ROOT, "docs", "accuracy.md")
    old = open(doc).read() if os.path.exists(doc) else "# Accuracy versus time\n\n"
    b, e = "<!-- sweeps:begin -->", "<!-- sweeps:end -->"
    if b in old and e in old:
        old = old[: old.index(b)] + b + "\n" + text + old[old.index(e):]
    else:
        old += "\n" + b + "\n" + text + e + "\n"
    open(doc, "w").write(old)
    print("wrote", doc)


if __name__ == "__main__":
    main()
