"""grtrace.trace_ray: a ray's path keeps the geodesic's conserved quantities, ends where the frame's pixel says it
ends, and in flat space is a straight line."""

import numpy as np
import pytest

import grtrace

SCHWARZSCHILD_DISK = dict(scene="disk", camera_r=40, camera_theta=80, fov=40, width=64, height=48, tracer="general")


def test_a_schwarzschild_ray_keeps_its_energy_angular_momentum_and_null_norm():
    # One sample a step: the accepted steps' ends, which the tolerance holds (points between them come from the
    # tableau's interpolant, a lower order).
    ray = grtrace.trace_ray(pixel=(10, 20), rtol=1e-10, atol=1e-12, samples_per_step=1, **SCHWARZSCHILD_DISK)
    assert ray.chart == "spherical" and len(ray) > 10
    assert np.all(np.diff(ray.step) == 1)
    t, r, theta, phi = ray.x.T
    kt, kr, kth, kph = ray.k.T
    f = 1.0 - 2.0 / r
    energy = f * kt
    angular_momentum = r**2 * np.sin(theta) ** 2 * kph
    carter = (r**2 * kth) ** 2 + angular_momentum**2 / np.sin(theta) ** 2  # total L^2 (spherical symmetry)
    assert np.max(np.abs(energy / energy[0] - 1)) < 1e-7
    assert np.max(np.abs(angular_momentum / angular_momentum[0] - 1)) < 1e-7
    assert np.max(np.abs(carter / carter[0] - 1)) < 1e-7
    norm = f * kt**2 - kr**2 / f - r**2 * kth**2 - r**2 * np.sin(theta) ** 2 * kph**2
    assert np.max(np.abs(norm)) < 1e-8 * np.max(f * kt**2)
    assert np.all(np.diff(ray.lambda_) >= 0)


def test_a_ray_ends_where_its_pixel_says():
    frame = grtrace.render(**SCHWARZSCHILD_DISK)
    objects = {0: "sky", 1: "horizon", 2: "disk"}
    checked = 0
    for col, row in [(32, 24), (5, 5), (60, 30), (32, 12), (20, 30)]:
        ray = grtrace.trace_ray(pixel=(col, row), **SCHWARZSCHILD_DISK)
        assert ray.outcome["object"] == objects[int(frame["object"][row, col])]
        assert ray.outcome["steps"] == int(frame["steps"][row, col])
        if np.isfinite(frame["redshift"][row, col]):
            assert np.float32(ray.outcome["redshift"]) == frame["redshift"][row, col]
        checked += 1
        # The path's last point lies on the surface that ended it: the crossing as the tracer located it.
        if ray.outcome["object"] == "disk":
            assert ray.x[-1, 2] == pytest.approx(np.pi / 2, abs=1e-12)
            assert ray.x[-1, 1] == ray.outcome["radius"]
    assert checked == 5


def test_scene_objects_off_lets_a_ray_through_the_disk():
    frame = grtrace.render(**SCHWARZSCHILD_DISK)
    rows, cols = np.nonzero(frame["object"] == 2)
    pixel = (int(cols[len(cols) // 2]), int(rows[len(rows) // 2]))  # a pixel that sees the disk
    ray = grtrace.trace_ray(pixel=pixel, **SCHWARZSCHILD_DISK)
    through = grtrace.trace_ray(pixel=pixel, scene_objects=False, **SCHWARZSCHILD_DISK)
    assert ray.outcome["object"] == "disk"
    assert through.outcome["object"] != "disk"
    assert len(through) > len(ray)


def test_a_state_of_ones_own_in_kerr_schild_coordinates():
    # A photon from (x, y, z) = (30, 0, 0) heading in -x and a little +y, past-directed as a camera's.
    ray = grtrace.trace_ray(position=(0, 30, 0, 0), momentum=(-1.0, 0.99, -0.1, 0.0), metric="kerr", spin=0.5,
                            chart="ks")
    assert ray.chart == "cartesian"
    assert ray.status in ("escaped", "captured")
    assert ray.cartesian.shape == (len(ray), 3)
    assert np.allclose(ray.cartesian[0], [30, 0, 0])
    with pytest.raises(ValueError, match="give pixel"):
        grtrace.trace_ray(position=(0, 30, 0, 0))


def test_flat_space_rays_are_straight_lines():
    ray = grtrace.trace_ray(pixel=(7, 5), metric="minkowski", camera_r=30, width=16, height=12, fov=60)
    assert ray.outcome["object"] == "sky"
    p = ray.cartesian
    direction = (p[-1] - p[0]) / np.linalg.norm(p[-1] - p[0])
    off_line = (p - p[0]) - np.outer((p - p[0]) @ direction, direction)
    assert np.max(np.linalg.norm(off_line, axis=1)) < 1e-9 * np.linalg.norm(p[-1] - p[0])
    assert np.linalg.norm(p[-1]) == pytest.approx(400, rel=1e-9)  # it ends on the sky sphere
    assert ray.x[-1, 1] == pytest.approx(400, rel=1e-9)
