"""Plots and tabulates the float-failure atlas (bench/float_atlas.cpp's CSV).

Usage (Debian's python3, which has matplotlib):
  build/bench/float_atlas 20 1 60 2 > bench/results/float_atlas.csv 2> run.txt
  /usr/bin/python3 bench/plot_float_atlas.py bench/results/float_atlas.csv bench/results/float_atlas

Writes PREFIX.svg: the rate of wrong answers against k, both sides of the degeneracy pooled.
Rows 1-2: the classify families (double and exact input), one line per float-mode tolerance,
the default tolerance's give-ups (undecided) dashed, Open CASCADE's wrong branch counts in
black (double input only). Row 3: the distance families, surfcert's float distance mode, FCL's
distance and collide (wrong) and FCL's crashes (libccd aborts, dotted). Prints the tables
(markdown) on stdout: "w% + g%" is wrong + gave up (+ "c%" crashed where FCL crashed).
"""
import collections
import csv
import sys

import matplotlib

matplotlib.use("svg")
import matplotlib.pyplot as plt  # noqa: E402

FAMILIES = ["tangency", "node", "acnode", "cusp", "double_conic"]
DISTANCE_FAMILIES = ["touching", "nested"]
ENCODINGS = ["double", "exact"]
DEFAULT = "surfcert_float tol=1e-08"


def main(path, prefix):
    # (family, encoding, k, method) -> [wrong, gave_up, total, crashed], k = 0 at the degeneracy
    cells = collections.defaultdict(lambda: [0, 0, 0, 0])
    methods = set()
    for row in csv.DictReader(open(path)):
        key = (row["family"], row["encoding"], int(row["k"]), row["method"])
        for i, f in enumerate(("wrong", "gave_up", "total", "crashed")):
            cells[key][i] += int(row.get(f) or 0)
        methods.add(row["method"])
    tols = sorted((m for m in methods if m.startswith("surfcert_float tol=")),
                  key=lambda m: -float(m.split("=")[1]))
    ks = sorted({k for (_, _, k, _) in cells if k > 0})

    def rate(fam, enc, method, what=0, shift=0.0):
        # shift: a small vertical offset per method, so that lines on the same rates (most
        # often 0 or 1) stay visible side by side instead of hiding one another
        xs, ys = [], []
        for k in ks:
            c = cells.get((fam, enc, k, method))
            if c and c[2]:
                xs.append(k)
                ys.append(c[what] / c[2] + shift)
        return xs, ys

    fig, axes = plt.subplots(3, len(FAMILIES), figsize=(18, 9.5), sharex=True, sharey=True)
    for i, enc in enumerate(ENCODINGS):
        for j, fam in enumerate(FAMILIES):
            ax = axes[i][j]
            for t, m in enumerate(tols):
                tol = m.split("=")[1]
                ax.plot(*rate(fam, enc, m, 0, 0.012 * (t - 2)), marker=".", linewidth=1.2,
                        label=f"float tol {tol}" + (" (default)" if m == DEFAULT else ""))
            ax.plot(*rate(fam, enc, DEFAULT, 1), linestyle="--", color="grey", linewidth=1,
                    label="float tol 1e-08: gave up (undecided)")
            if enc == "double" and (fam, enc, ks[0], "occt_intss") in cells:
                ax.plot(*rate(fam, enc, "occt_intss", 0, 0.04), color="black", marker="s",
                        markersize=3, linewidth=1.5, label="Open CASCADE IntSS branches")
            ax.set_ylim(-0.06, 1.08)
            ax.grid(alpha=0.3)
            if i == 0:
                ax.set_title(fam)
            if j == 0:
                ax.set_ylabel(f"{enc} input\nwrong (rate)")
    for j in range(len(FAMILIES)):
        ax = axes[2][j]
        if j >= len(DISTANCE_FAMILIES):
            ax.axis("off")
            if j == len(DISTANCE_FAMILIES):  # the classify rows' legend, in the free space
                ax.legend(*axes[0][0].get_legend_handles_labels(), fontsize=9,
                          loc="center left", title="rows 1-2 (classify families)")
            continue
        fam = DISTANCE_FAMILIES[j]
        ax.plot(*rate(fam, "double", "surfcert_float", 0, -0.03), marker=".",
                label="surfcert float (wrong)")
        ax.plot(*rate(fam, "double", "surfcert_float", 1, -0.015), linestyle="--", color="grey",
                label="surfcert float: gave up")
        if (fam, "double", ks[0], "fcl_distance") in cells:
            ax.plot(*rate(fam, "double", "fcl_distance", 0, 0.015), color="tab:red", marker="s",
                    markersize=3, label="FCL distance, libccd (wrong)")
            ax.plot(*rate(fam, "double", "fcl_collide", 0, 0.03), color="tab:purple", marker="^",
                    markersize=3, label="FCL collide (wrong)")
            ax.plot(*rate(fam, "double", "fcl_distance", 3, 0.045), color="tab:orange",
                    linestyle=":", linewidth=2, label="FCL crashed (libccd abort)")
        ax.set_title(f"distance: {fam}")
        ax.grid(alpha=0.3)
        ax.set_xlabel("k (gap ±2^-k to the degeneracy)")
        if j == 0:
            ax.set_ylabel("double input\nwrong verdict or\ndistance off > 1%")
        ax.set_ylim(-0.06, 1.08)
        if j == 0:  # the distance row's legend, in the free space at the row's end
            axes[2][len(FAMILIES) - 1].legend(*ax.get_legend_handles_labels(), fontsize=9,
                                              loc="center left", title="row 3 (distance)")
    for j in range(len(FAMILIES)):
        axes[1][j].set_xlabel("k (gap ±2^-k to the degeneracy)")
        axes[1][j].xaxis.set_tick_params(labelbottom=True)
    fig.suptitle("Float methods against the certified label near degeneracies "
                 "(surfcert generate --family F; both sides pooled; lines offset slightly so that "
                 "equal rates stay visible)")
    fig.tight_layout()
    fig.savefig(prefix + ".svg")

    bands = [(2, 10), (12, 20), (22, 30), (32, 40), (42, 50), (52, 60)]

    def row_of(fam, enc, m, label):
        zero = cells.get((fam, enc, 0, m), [0, 0, 0, 0])
        row = [fam, enc, label, f"{zero[0]}+{zero[1]}/{zero[2]}"
               + (f" ({zero[3]} crashed)" if zero[3] else "")]
        for a, b in bands:
            def tot(i):
                return sum(cells.get((fam, enc, k, m), [0, 0, 0, 0])[i]
                           for k in ks if a <= k <= b)
            w, g, t, c = tot(0), tot(1), tot(2), tot(3)
            txt = f"{100 * w / t:.0f}% + {100 * g / t:.0f}%" if t else ""
            if c:
                txt += f" + {100 * c / t:.0f}% c"
            row.append(txt)
        return "| " + " | ".join(row) + " |"

    head = ("| family | input | method | at g = 0 | "
            + " | ".join(f"k {a}–{b}" for a, b in bands) + " |\n|---|---|---|---|"
            + "---|" * len(bands))
    lines = [head]
    for fam in FAMILIES:
        for enc in ENCODINGS:
            for m in tols:
                lines.append(row_of(fam, enc, m, "float " + m.split("=")[1]))
            if (fam, enc, 0, "occt_intss") in cells:
                lines.append(row_of(fam, enc, "occt_intss", "Open CASCADE"))
    lines += ["", head]
    for fam in DISTANCE_FAMILIES:
        for m, label in (("surfcert_float", "surfcert float"), ("fcl_distance", "FCL distance"),
                         ("fcl_collide", "FCL collide")):
            if (fam, "double", 0, m) in cells:
                lines.append(row_of(fam, "double", m, label))
    print("\n".join(lines))


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
