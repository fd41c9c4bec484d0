#!/usr/bin/python3
"""The model drawn before solving (called by `tsmframe plot MODEL.json`; Debian python3-matplotlib).

    /usr/bin/python3 scripts/plot_model.py DRAWING.json OUT.png|svg|pdf

DRAWING.json: the model's drawing document (tsmframe-drawing/1) that `tsmframe plot` writes;
the picture is python/tsmframe/model_plot.py's (Model.plot() draws the same), written whole
(a temporary beside OUT, then one rename); exit 3, said on stderr, where OUT cannot be written.
"""
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from shapes import model_plot  # noqa: E402  (the package's drawing, loaded by its path)


def main(drawing_path, out):
    with open(drawing_path) as f:
        drawing = json.load(f)
    xs = [n["x"] for n in drawing["nodes"]] or [0.0]
    ys = [n["y"] for n in drawing["nodes"]] or [0.0]
    width, height = max(xs) - min(xs), max(ys) - min(ys)
    aspect = height / width if width > 0 else 1.0  # a long flat model in a flat picture
    fig, ax = plt.subplots(figsize=(9, min(9.0, max(3.5, 9 * aspect + 2.0))))
    model_plot().plot_model(drawing, ax)
    fig.tight_layout()
    root, extension = os.path.splitext(out)
    temporary = f"{root}.tmp-{os.getpid()}{extension}"
    try:
        fig.savefig(temporary, dpi=130, bbox_inches="tight")
        os.replace(temporary, out)
    except OSError as e:  # the command's one line and its exit code for what the system refuses
        print(f"tsmframe: {out}: cannot write: {e.strerror}", file=sys.stderr)
        sys.exit(3)
    finally:
        if os.path.exists(temporary):
            os.remove(temporary)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
