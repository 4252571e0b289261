"""A Kerr black hole's thin disk from Python: render it, look at it, trace a few rays, and fit the spin and the
inclination to a synthetic image with scipy.optimize.

The plain-script twin of kerr_disk_fit.ipynb (the same cells, in order). Run it with Debian's python3 once the
module is installed (bash cmake/quickstart.sh python):

    python3 examples/python/kerr_disk_fit.py            # writes kerr_disk_*.png beside where it runs

GRTRACE_EXAMPLE_SIZE sets the rendered frames' size (default 256) and GRTRACE_EXAMPLE_FIT_SIZE the fit's (default
64): the test suite runs the notebook small.
"""

# %% [markdown]
# # A Kerr disk, its rays, and a fit of spin and inclination
#
# grtrace traces light backwards from a camera through the Kerr metric (Boyer-Lindquist coordinates, the reduced
# Mino-time tracer where it applies) until each ray reaches the horizon, the thin Keplerian disk (from the ISCO out
# to 20 M) or the sky. `grtrace.render` takes grtrace-render's options as keywords and returns the channels as numpy
# arrays: the colour, which object each pixel sees, and the redshift g = f_obs / f_emit of the disk's light.

# %%
import os
import time

import matplotlib

AS_SCRIPT = "__file__" in globals()  # a notebook's cells run without a file
if AS_SCRIPT:
    matplotlib.use("Agg")  # the script writes PNGs; the notebook shows the figures inline
import matplotlib.pyplot as plt
import numpy as np
import scipy.ndimage
import scipy.optimize

import grtrace

SIZE = int(os.environ.get("GRTRACE_EXAMPLE_SIZE", "256"))
FIT_SIZE = int(os.environ.get("GRTRACE_EXAMPLE_FIT_SIZE", "64"))
CAMERA = dict(scene="disk", camera_r=60, fov=24)  # a camera 60 M from the hole, 24 degrees across
print(f"grtrace {grtrace.__version__}; device choices {grtrace.devices()}; frames {SIZE}x{SIZE}")

# %% [markdown]
# ## The disk of a hole spinning at a = 0.9, seen from 80 degrees

# %%
frame = grtrace.render(metric="kerr", spin=0.9, camera_theta=80, width=SIZE, height=SIZE, **CAMERA)
report = frame.report
print(f"{report['tracer']} tracer on {report['device']}: {report['seconds']:.3f} s, "
      f"{report['status_counts']['hit']} pixels on the disk, {report['status_counts']['captured']} in the shadow")

rgb = frame.rgb()
g = np.where(frame["object"] == 2, frame["redshift"], np.nan)  # the redshift where the disk is seen
fig, axes = plt.subplots(1, 2, figsize=(11, 4.8))
axes[0].imshow(np.clip(rgb / np.percentile(rgb, 99.5), 0, 1) ** (1 / 2.2))
axes[0].set_title("the disk (linear colour, tone-mapped)")
image = axes[1].imshow(g, cmap="coolwarm_r")
axes[1].set_title("redshift g = f_obs / f_emit on the disk")
fig.colorbar(image, ax=axes[1])
for ax in axes:
    ax.set_axis_off()
fig.tight_layout()
if AS_SCRIPT:
    fig.savefig("kerr_disk_frame.png", dpi=100)

# %% [markdown]
# ## A few rays of the middle column, traced one by one
#
# `grtrace.trace_ray(pixel=(column, row), ...)` integrates one pixel's ray with the general tracer and returns its
# path: coordinates, momenta and affine parameter as arrays, and where it ended. Seen from the side (the camera's
# x, z plane), the rays above the shadow bend over the hole onto the far side of the disk.

# %%
column = SIZE // 2
rays = [grtrace.trace_ray(pixel=(column, row), metric="kerr", spin=0.9, camera_theta=80, width=SIZE, height=SIZE,
                          **CAMERA) for row in np.linspace(0, SIZE - 1, 11).astype(int)]
fig, ax = plt.subplots(figsize=(8, 5))
r_plus = 1 + np.sqrt(1 - 0.9**2)
ax.add_patch(plt.Circle((0, 0), r_plus, color="black"))
isco = float(frame.header["disk_inner"])
for sign in (-1, 1):
    ax.plot([sign * isco, sign * 20], [0, 0], color="orange", lw=4, solid_capstyle="butt")
colours = {"disk": "tab:blue", "horizon": "black", "sky": "tab:gray"}
for ray in rays:
    ax.plot(ray.cartesian[:, 0], ray.cartesian[:, 2], lw=1, color=colours.get(ray.outcome["object"], "red"))
ax.set_xlim(-25, 62)
ax.set_ylim(-16, 24)
ax.set_aspect("equal")
ax.set_title("rays of the middle column, from the side (x, z in M): disk orange, horizon black")
if AS_SCRIPT:
    fig.savefig("kerr_disk_rays.png", dpi=100)
for ray in rays:
    print(f"{len(ray):4d} samples, {ray.outcome['status']:8s} {ray.outcome['object']:8s} "
          f"r = {ray.outcome['radius']:8.3f} M, g = {ray.outcome['redshift']:.4f}")

# %% [markdown]
# ## Fitting the spin and the inclination
#
# A synthetic observation: the disk's redshift map for a = 0.7 seen from 72 degrees, at FIT_SIZE x FIT_SIZE pixels.
# The model renders the same camera for trial (a, theta) and compares the maps (blurred by two pixels, so that the
# disk's edges move smoothly as the parameters do); Nelder-Mead finds the minimum.

# %%
TRUTH = (0.7, 72.0)


def redshift_map(spin, theta):
    """The disk's redshift where it is seen (0 elsewhere), blurred by two pixels."""
    f = grtrace.render(metric="kerr", spin=spin, camera_theta=theta, width=FIT_SIZE, height=FIT_SIZE, **CAMERA)
    g = np.where(f["object"] == 2, f["redshift"], 0.0)
    return scipy.ndimage.gaussian_filter(g.astype(np.float64), 2.0)


observed = redshift_map(*TRUTH)
calls = []


def misfit(p):
    spin, theta = p
    if not (-0.99 < spin < 0.99 and 1.0 < theta < 179.0):
        return 1e3  # outside the parameters' range
    calls.append(p)
    return float(np.mean((redshift_map(spin, theta) - observed) ** 2))


start = time.monotonic()
fit = scipy.optimize.minimize(misfit, x0=[0.3, 60.0], method="Nelder-Mead",
                              options=dict(xatol=1e-3, fatol=1e-12, initial_simplex=[[0.3, 60], [0.6, 60], [0.3, 68]]))
seconds = time.monotonic() - start
spin_fit, theta_fit = fit.x
print(f"fit: spin {spin_fit:.4f} (true {TRUTH[0]}), inclination {theta_fit:.3f} deg (true {TRUTH[1]}); "
      f"{len(calls)} renders in {seconds:.1f} s")
assert abs(spin_fit - TRUTH[0]) < 0.02 and abs(theta_fit - TRUTH[1]) < 0.5, "the fit did not recover the parameters"

# %%
fig, axes = plt.subplots(1, 2, figsize=(10, 4.2))
axes[0].imshow(np.ma.masked_equal(observed, 0.0), cmap="coolwarm_r")
axes[0].set_title(f"observed: blurred redshift map (a = {TRUTH[0]}, {TRUTH[1]} deg)")
axes[0].set_axis_off()
trials = np.array(calls)
axes[1].plot(trials[:, 0], trials[:, 1], ".-", color="tab:gray", lw=0.5, ms=3, label="Nelder-Mead's trials")
axes[1].plot(*TRUTH, "r*", ms=14, label="truth")
axes[1].plot(spin_fit, theta_fit, "kx", ms=10, label=f"fit ({spin_fit:.4f}, {theta_fit:.3f} deg)")
axes[1].set_xlabel("spin a / M")
axes[1].set_ylabel("inclination (camera theta, degrees)")
axes[1].legend()
fig.tight_layout()
if AS_SCRIPT:
    fig.savefig("kerr_disk_fit.png", dpi=100)
