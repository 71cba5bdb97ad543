#!/usr/bin/env python3
"""Fitness curves of one or more lineage stores, as an SVG line chart.

    scripts/fitness_curves.py out.svg RUN1.db [RUN2.db ...]

For each store (its latest run): best, mean and median fitness per
generation, from the generation_statistics view (docs/lineage.md). Only the
Python standard library is used (sqlite3, xml escaping), so it runs on a
fresh Debian machine with python3.
"""

import sqlite3
import sys
from xml.sax.saxutils import escape

COLOURS = ["#1b9e77", "#d95f02", "#7570b3", "#e7298a", "#66a61e", "#e6ab02"]


def curves(path):
    db = sqlite3.connect(f"file:{path}?mode=ro", uri=True)
    run = db.execute("SELECT MAX(run_id) FROM runs").fetchone()[0]
    seed = db.execute("SELECT seed FROM runs WHERE run_id = ?", (run,)).fetchone()[0]
    rows = db.execute(
        "SELECT generation, best_fitness, mean_fitness, median_fitness"
        " FROM generation_statistics WHERE run_id = ? AND completed_at IS NOT NULL"
        " ORDER BY generation",
        (run,),
    ).fetchall()
    return seed, rows


def main(argv):
    if len(argv) < 3:
        sys.exit(__doc__)
    out, paths = argv[1], argv[2:]
    runs = [curves(p) for p in paths]
    width, height, left, bottom, top, right = 760, 420, 60, 50, 30, 170
    max_gen = max((r[-1][0] for _, r in runs if r), default=1) or 1
    max_fit = max((v for _, r in runs for row in r for v in row[1:] if v), default=1)
    plot_w, plot_h = width - left - right, height - top - bottom

    def x(g):
        return left + plot_w * g / max_gen

    def y(f):
        return top + plot_h * (1 - f / max_fit)

    parts = [
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}"'
        f' font-family="sans-serif" font-size="12">',
        f'<rect width="{width}" height="{height}" fill="white"/>',
        f'<line x1="{left}" y1="{top + plot_h}" x2="{left + plot_w}" y2="{top + plot_h}" stroke="black"/>',
        f'<line x1="{left}" y1="{top}" x2="{left}" y2="{top + plot_h}" stroke="black"/>',
        f'<text x="{left + plot_w / 2}" y="{height - 12}" text-anchor="middle">generation</text>',
        f'<text x="16" y="{top + plot_h / 2}" text-anchor="middle"'
        f' transform="rotate(-90 16 {top + plot_h / 2})">fitness (radii swum)</text>',
    ]
    for i in range(6):
        f = max_fit * i / 5
        parts.append(f'<text x="{left - 6}" y="{y(f) + 4:.1f}" text-anchor="end">{f:.2g}</text>')
        parts.append(f'<line x1="{left}" y1="{y(f):.1f}" x2="{left + plot_w}" y2="{y(f):.1f}" stroke="#eee"/>')
    for i in range(6):
        g = round(max_gen * i / 5)
        parts.append(f'<text x="{x(g):.1f}" y="{top + plot_h + 16}" text-anchor="middle">{g}</text>')
    legend_y = top
    for k, (seed, rows) in enumerate(runs):
        colour = COLOURS[k % len(COLOURS)]
        for column, dash, label in ((1, "", "best"), (2, "6,3", "mean"), (3, "2,3", "median")):
            points = " ".join(f"{x(r[0]):.1f},{y(r[column]):.1f}" for r in rows if r[column] is not None)
            if not points:
                continue
            parts.append(
                f'<polyline points="{points}" fill="none" stroke="{colour}" stroke-width="1.6"'
                + (f' stroke-dasharray="{dash}"' if dash else "") + "/>"
            )
            parts.append(
                f'<line x1="{width - right + 12}" y1="{legend_y}" x2="{width - right + 40}" y2="{legend_y}"'
                f' stroke="{colour}" stroke-width="1.6"' + (f' stroke-dasharray="{dash}"' if dash else "") + "/>"
            )
            parts.append(f'<text x="{width - right + 46}" y="{legend_y + 4}">{escape(f"seed {seed} {label}")}</text>')
            legend_y += 16
    parts.append("</svg>")
    with open(out, "w") as f:
        f.write("\n".join(parts) + "\n")


if __name__ == "__main__":
    main(sys.argv)
