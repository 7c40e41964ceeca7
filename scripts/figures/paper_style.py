"""Shared style and output options of the figure scripts (not a script itself).

Sizes are for a two-column paper: SINGLE = 3.5 in (one column), DOUBLE =
7.0 in (both columns), drawn at that size, so 8 pt text is 8 pt in print.
Every script reads the same command line, `SCRIPT.py [OPTIONS] [RESULTS_DIR]`
(parse_arguments; the output options alone: add_arguments), and saves through
save(): --format png|pdf|svg, --dpi (PNG resolution and that of rasterised
parts in PDF/SVG), --out (figures root), --no-title (drop the figure title,
for a LaTeX caption). Artists with more than LARGE points (long time series,
scatters) are rasterised in vector output by rasterize_large(); scatters of
that size are drawn as density (hexbin) by density().
"""
import argparse
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.colors import LogNorm  # noqa: E402

SINGLE = 3.5  # in, one column
DOUBLE = 7.0  # in, two columns
FORMATS = ("png", "pdf", "svg")
DEFAULT_DPI = 300
# Above this many points a scatter becomes a hexbin density and a line or
# collection is rasterised in vector output (an SVG of an 86,000-point line
# is megabytes and slow to open).
LARGE = 2000

RC = {
    "font.size": 8,
    "axes.titlesize": 8,
    "axes.labelsize": 8,
    "xtick.labelsize": 7,
    "ytick.labelsize": 7,
    "legend.fontsize": 7,
    "figure.titlesize": 9,
    "lines.linewidth": 1.0,
    "axes.linewidth": 0.6,
    "xtick.major.width": 0.6,
    "ytick.major.width": 0.6,
    "xtick.minor.width": 0.4,
    "ytick.minor.width": 0.4,
    "grid.linewidth": 0.4,
    "legend.frameon": True,
    "legend.framealpha": 0.85,
    "legend.handlelength": 1.6,
    "mathtext.default": "regular",
    "pdf.fonttype": 42,  # TrueType: text stays text (searchable, editable)
    "svg.fonttype": "none",
    "savefig.bbox": None,  # constrained layout already fits; "tight" would lay out twice
    "savefig.pad_inches": 0.03,
}

# The papers' colours where a caption names them (seed 002 Figs. 8, 9, 13).
ACTUAL = "tab:blue"
PREDICTED = "tab:green"
ERROR = "tab:red"


def parse_arguments(description):
    """The command line of every figure script (scripts/figures/run's contract):
    `SCRIPT.py [--format F] [--dpi N] [--out DIR] [--no-title] [RESULTS_DIR]`,
    RESULTS_DIR defaulting to results/ of the working directory. `description`
    is the script's __doc__ (its --help)."""
    parser = argparse.ArgumentParser(description=description,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("results", nargs="?", default="results",
                        help="results folder (default: results)")
    add_arguments(parser)
    return parser.parse_args()


def add_arguments(parser):
    """The output options every figure script takes."""
    g = parser.add_argument_group("output")
    g.add_argument("--format", choices=FORMATS, default="png",
                   help="file format (default png; pdf and svg are vector, large "
                        "point sets rasterised inside them)")
    g.add_argument("--dpi", type=positive_int, default=DEFAULT_DPI,
                   help=f"resolution of PNGs and of rasterised parts (default {DEFAULT_DPI})")
    g.add_argument("--out", metavar="DIR",
                   help="figures root: writes DIR/<topic>/ (default RESULTS_DIR/figures)")
    g.add_argument("--no-title", action="store_true",
                   help="no figure title (the caption carries it)")


def positive_int(text):
    value = int(text)
    if value <= 0:
        raise ValueError(text)
    return value


def apply():
    plt.rcParams.update(RC)


class Output:
    """Where and how a script's figures are written: OUT/<topic>/<stem>.<format>."""

    def __init__(self, args, results, topic):
        self.dir = os.path.join(args.out or os.path.join(results, "figures"), topic)
        self.format, self.dpi, self.titles = args.format, args.dpi, not args.no_title

    def title(self, fig, text):
        if self.titles:
            fig.suptitle(text)

    def save(self, fig, stem):
        """Write atomically (a temporary name, then rename: never half a file).
        PDF and SVG carry no date, so the same figure gives the same bytes."""
        os.makedirs(self.dir, exist_ok=True)
        name = f"{stem}.{self.format}"
        path = os.path.join(self.dir, name)
        tmp = os.path.join(self.dir, f".{name}.partial.{self.format}")
        metadata = {"png": None, "pdf": {"CreationDate": None}, "svg": {"Date": None}}
        fig.savefig(tmp, format=self.format, dpi=self.dpi, metadata=metadata[self.format])
        plt.close(fig)
        os.replace(tmp, path)
        print(f"figures: wrote {path}")
        return path


def rasterize_large(artists, points):
    """Rasterise artists drawing more than LARGE points (no effect on PNG)."""
    if points > LARGE:
        for a in artists if isinstance(artists, (list, tuple)) else [artists]:
            a.set_rasterized(True)


def density(ax, x, y, extent, gridsize=45):
    """x against y: a hexbin of log counts above LARGE points, else a scatter.
    Returns the hexbin (for a shared colour scale, see share_clim) or None."""
    if x.size <= LARGE:
        ax.scatter(x, y, s=3, alpha=0.5, linewidths=0, color=ACTUAL)
        return None
    hb = ax.hexbin(x, y, gridsize=gridsize, extent=extent, mincnt=1, norm=LogNorm(),
                   cmap="viridis", linewidths=0)
    hb.set_rasterized(True)
    return hb


def share_clim(fig, hexbins, axes, label="samples per bin"):
    """One colour scale (1 .. the largest bin) for the panels' hexbins and one
    colour bar beside `axes`."""
    hexbins = [h for h in hexbins if h is not None]
    if not hexbins:
        return
    top = max(float(np.max(h.get_array())) for h in hexbins)
    for h in hexbins:
        h.set_clim(1, max(top, 2))
    bar = fig.colorbar(hexbins[0], ax=axes, shrink=0.9, pad=0.02, aspect=25)
    bar.set_label(label)


if __name__ == "__main__":
    # A module, not a figure script; answers --help like every script does.
    import sys

    print(__doc__)
    sys.exit(0 if sys.argv[1:] in (["--help"], ["-h"]) else 2)
