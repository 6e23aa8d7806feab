#!/usr/bin/env python3
"""Planning horizon H and model depth d for Obie's match (thesis §7.4, Figs. 7.4-7.11).

Runs `parlee run` on the football domain and the §7.4 match for H in {3,5,7} x d in {0,1,2,H-1}
(and the domain's `not-lose` goal kept or removed, Obie's surprise alpha 0.1/0.4), prints one
markdown table of measurements and, with --charts DIR, writes the neutral Obie's chart of each
(H, d) as DIR/H<h>_d<d>.png (shipped goals, alpha 0.4) and H7_dH-1_win_only.png.

Usage (from the repository root, after building `parlee`):
  python3 scripts/parlee_sweep.py --parlee build/apps/parlee/parlee [--charts docs/img/parlee/sweep]
"""
import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile

DATA = "data/parlee"


def win_only_domain(tmp):
    """The football domain without the `not-lose` goal (Obie's only goal is `win`, as in §7.4)."""
    text = open(f"{DATA}/football.domain").read()
    start = text.index("(goal not-lose")
    end = text.index("(goal against-wins")
    path = os.path.join(tmp, "football_win_only.domain")
    with open(path, "w") as f:
        f.write(text[:start] + text[end:])
    return path


def run(exe, agent, h, d, domain, tmp, plot=None):
    path = os.path.join(tmp, "agent.json")
    with open(path, "w") as f:
        json.dump(agent, f)
    out = os.path.join(tmp, "t.ndjson")
    cmd = [exe, "run", "--domain", domain, "--agent", path, "--events",
           f"{DATA}/match.ndjson", "--out", out, "--horizon", str(h), "--depth", str(d)]
    if plot:
        cmd += ["--plot", plot]
    subprocess.run(cmd, check=True)
    return [json.loads(l) for l in open(out) if l.startswith('{"agent"')]


def measure(rows):
    esv = {r["time"]: r["esv"] for r in rows}
    last = {}
    for r in rows:  # several rows may share a time; keep the last one
        last[r["time"]] = r
    def mx(e, a, b):
        return max((last[t]["esv"][e] for t in last if a <= t < b), default=0.0)
    def mean(e, a, b):
        v = [last[t]["esv"][e] for t in last if a <= t <= b]
        return sum(v) / len(v)
    surprises = sum(1 for t in last if t > 0 and last[t]["esv"]["surprise"] > 0.05)
    return {
        "fear 2-39": mean("fear", 2, 39), "fear 41-79": mean("fear", 41, 79),
        "fear 81-90": mean("fear", 81, 90),
        "P(win) 40'": last[40]["goals"]["win"]["p"],
        "hap. 40'-39'": last[40]["esv"]["happiness"] - last[39]["esv"]["happiness"],
        "hap. 30'": last[30]["esv"]["happiness"],
        "hap. 40.5'": last[40.5]["esv"]["happiness"], "hap. 90'": last[90]["esv"]["happiness"],
        "sur. 40'": max(last[40]["esv"]["surprise"], last[40.5]["esv"]["surprise"]),
        "#sur.>0.05": surprises, "sad. 80'": last[80]["esv"]["sadness"],
        "sad. 12'": last[12]["esv"]["sadness"],
    }


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--parlee", default="build/apps/parlee/parlee")
    ap.add_argument("--charts", default="")
    a = ap.parse_args()
    tmp = tempfile.mkdtemp()
    try:
        table = []
        for not_lose in (False, True):
            for alpha in (0.1, 0.4):
                for h in (3, 5, 7):
                    for d in (0, 1, 2, -1):
                        agent = {"format": "emoface.parlee_agent", "version": "1.1", "self": "agent",
                                 "seed": 7, "name": "neutral", "appraisal": {"compound": "standards"},
                                 "emotions": {"alpha": {"surprise": alpha}}}
                        domain = f"{DATA}/football.domain" if not_lose else win_only_domain(tmp)
                        plot = None
                        if a.charts and alpha == 0.4 and (not_lose or (h, d) == (7, -1)):
                            plot = os.path.join(tmp, "plot")
                        rows = run(a.parlee, agent, h, d, domain, tmp, plot)
                        if plot:
                            os.makedirs(a.charts, exist_ok=True)
                            shutil.copy(os.path.join(plot, "neutral.png"),
                                        os.path.join(a.charts, f"H{h}_d{'H-1' if d < 0 else d}{'' if not_lose else '_win_only'}.png"))
                        table.append(({"not-lose": "yes" if not_lose else "no", "alpha_sur": alpha,
                                       "H": h, "d": d if d >= 0 else f"H-1={h - 1}"}, measure(rows)))
        keys = list(table[0][0]) + list(table[0][1])
        print("| " + " | ".join(keys) + " |")
        print("|" + "---|" * len(keys))
        for k, m in table:
            vals = list(k.values()) + [f"{v:.2f}" if isinstance(v, float) else str(v) for v in m.values()]
            print("| " + " | ".join(str(v) for v in vals) + " |")
    finally:
        shutil.rmtree(tmp)


if __name__ == "__main__":
    sys.exit(main())
