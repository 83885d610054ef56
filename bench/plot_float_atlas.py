"""Plots and tabulates the float-failure atlas (bench/float_atlas.cpp's CSV).

Usage (Debian's python3, which has matplotlib):
  build/bench/float_atlas 20 1 60 > bench/results/float_atlas.csv
  /usr/bin/python3 bench/plot_float_atlas.py bench/results/float_atlas.csv bench/results/float_atlas

Writes PREFIX.svg (error rate against k, one panel per degeneracy family and encoding, one
line per tolerance; both sides of the degeneracy pooled) and PREFIX.md (the table).
"""
import collections
import csv
import sys

import matplotlib

matplotlib.use("svg")
import matplotlib.pyplot as plt  # noqa: E402

FAMILIES = ["tangency", "node", "acnode", "cusp", "double_conic"]
ENCODINGS = ["double", "exact"]


def main(path, prefix):
    # (family, encoding, k, tol) -> [wrong, total], k = 0 for the degenerate point itself
    cells = collections.defaultdict(lambda: [0, 0])
    tols = set()
    for row in csv.DictReader(open(path)):
        key = (row["family"], row["encoding"], int(row["k"]), float(row["tolerance"]))
        cells[key][0] += int(row["wrong"])
        cells[key][1] += int(row["total"])
        tols.add(float(row["tolerance"]))
    tols = sorted(tols, reverse=True)
    ks = sorted({k for (_, _, k, _) in cells if k > 0})

    fig, axes = plt.subplots(len(ENCODINGS), len(FAMILIES), figsize=(17, 6.5), sharex=True,
                             sharey=True)
    for i, enc in enumerate(ENCODINGS):
        for j, fam in enumerate(FAMILIES):
            ax = axes[i][j]
            for tol in tols:
                rate = [cells[(fam, enc, k, tol)][0] / max(1, cells[(fam, enc, k, tol)][1])
                        for k in ks]
                ax.plot(ks, rate, marker=".", linewidth=1.2,
                        label=f"tol {tol:g}" + (" (default)" if tol == 1e-8 else ""))
            ax.set_ylim(-0.03, 1.03)
            ax.grid(alpha=0.3)
            if i == 0:
                ax.set_title(fam)
            if i == len(ENCODINGS) - 1:
                ax.set_xlabel("k (gap ±2^-k to the degeneracy)")
            if j == 0:
                ax.set_ylabel(f"{enc} input\nwrong Tu case (rate)")
    axes[0][-1].legend(fontsize=8, loc="lower right")
    fig.suptitle("surfcert float mode against the certified label, per degeneracy family "
                 "(surfcert generate --family F; both sides pooled)")
    fig.tight_layout()
    fig.savefig(prefix + ".svg")

    bands = [(2, 10), (12, 20), (22, 30), (32, 40), (42, 50), (52, 60)]
    lines = ["| family | input | tolerance | at g = 0 | "
             + " | ".join(f"k {a}–{b}" for a, b in bands) + " |",
             "|---|---|---|---|" + "---|" * len(bands)]
    for fam in FAMILIES:
        for enc in ENCODINGS:
            for tol in tols:
                zero = cells[(fam, enc, 0, tol)]
                row = [fam, enc, f"{tol:g}", f"{zero[0]}/{zero[1]}"]
                for a, b in bands:
                    w = sum(cells[(fam, enc, k, tol)][0] for k in ks if a <= k <= b)
                    t = sum(cells[(fam, enc, k, tol)][1] for k in ks if a <= k <= b)
                    row.append(f"{100 * w / t:.0f}%" if t else "")
                lines.append("| " + " | ".join(row) + " |")
    with open(prefix + ".md", "w") as out:
        out.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
