"""A glowing torus around a Kerr hole, split by image order: the direct image and the photon rings of its light.

Every pixel's ray is integrated with the torus's light (grtrace-render --scene torus), which is also cut into the
orders of the images it belongs to (intensity_n0, _n1, _n2, _n3_up: the direct image, the first and second photon
rings, the rest). Run it with Debian's python3 once the module is installed (bash cmake/quickstart.sh python):

    python3 examples/python/torus_orders.py          # writes torus_orders.png beside where it runs

GRTRACE_EXAMPLE_SIZE sets the frame's size (default 384): the test suite runs it small.
"""
import os
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import grtrace

SIZE = int(os.environ.get("GRTRACE_EXAMPLE_SIZE", "384"))
# A Polish doughnut (inner edge 6 M, pressure maximum 10 M, optically thin) around a = 0.9, seen from 100 M at 80
# degrees: the torus fills the frame; the photon rings lie inside its inner edge.
SCENE = dict(scene="torus", metric="kerr", spin=0.9, camera_r=100, camera_theta=80, fov=36, width=SIZE, height=SIZE)

start = time.perf_counter()
frame = grtrace.render(**SCENE)
seconds = time.perf_counter() - start
orders = ["n0", "n1", "n2", "n3_up"]
flux = {n: frame.report["flux_" + n] for n in orders}
total = frame.report["flux"]
print(f"torus {SIZE}x{SIZE} in {seconds:.1f} s; flux {total:.4g}, by order "
      + ", ".join(f"{n} {flux[n]:.4g} ({flux[n] / total:.2%})" for n in orders))

# The total and the three brightest orders, each on its own scale (the rings are fainter), the square root of the
# intensity over its 99.5th percentile (the thin rings' few brightest pixels would set the scale otherwise) lifting
# the faint gas.
panels = [("all orders", frame["intensity"]), ("n = 0: direct", frame["intensity_n0"]),
          ("n = 1: first ring", frame["intensity_n1"]),
          ("n >= 2", frame["intensity_n2"] + frame["intensity_n3_up"])]
fig, axes = plt.subplots(1, 4, figsize=(13, 3.6))
for ax, (title, image) in zip(axes, panels):
    lit = image[image > 0]
    scale = float(np.percentile(lit, 99.5)) if lit.size else 1.0
    ax.imshow(np.sqrt(np.clip(image / scale, 0, 1)), cmap="afmhot", origin="upper", vmin=0, vmax=1)
    share = float(np.sum(image)) / max(float(np.sum(frame["intensity"])), 1e-300)
    ax.set_title(f"{title}\n{share:.2%} of the light", fontsize=10)
    ax.set_xticks([])
    ax.set_yticks([])
fig.suptitle("A glowing torus around a = 0.9 at 80 degrees, by image order (each panel on its own scale)",
             fontsize=11)
fig.tight_layout(rect=(0, 0, 1, 0.93))
fig.savefig("torus_orders.png", dpi=100)
print("wrote torus_orders.png")
