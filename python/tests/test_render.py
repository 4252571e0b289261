"""grtrace.render against grtrace-render: the same request gives the same channels, bit for bit; the same bad request
the same refusal (ValueError with the tool's message); renders in threads, in loops and interrupted behave."""

import gc
import json
import os
import signal
import threading
import time

import numpy as np
import pytest

import grtrace

from conftest import command_line

KERR_DISK = dict(metric="kerr", spin=0.9, scene="disk", camera_r=50, camera_theta=80, fov=30, width=96, height=64)
MAIN_FRAME = dict(width=80, height=60)  # the seed's main frame, small: the planar tracer, mirrors
WORMHOLE = dict(metric="wormhole", throat=1.5, scene="checker", camera_r=-8, width=48, height=40, tracer="general")


def bits(a):
    """The array's bits (NaN payloads included), for comparisons bit for bit."""
    return np.ascontiguousarray(a).view(np.uint32)


@pytest.mark.parametrize("options", [KERR_DISK, MAIN_FRAME, WORMHOLE], ids=["kerr-disk", "main-frame", "wormhole"])
def test_channels_equal_the_tools_exr_bit_for_bit(options, run_tool):
    frame = grtrace.render(**options)
    code, out, err, exr = run_tool(options)
    assert code == 0, err
    tool = grtrace.read_exr(str(exr))
    assert frame.channel_names == tool.channel_names
    for name in frame.channel_names:
        assert np.array_equal(bits(frame[name]), bits(tool[name])), name
    # The report is the tool's JSON line's: the same keys' values (but the times).
    line = json.loads(out.strip().splitlines()[-1])
    report = frame.report
    for key in ("width", "height", "status_counts", "tracer", "tableau", "control", "device", "mirrors",
                "traced_rays", "rtol", "atol", "sky_continuation"):
        assert report[key] == line[key], key
    assert set(line) - {"out", "png"} <= set(report)
    # The header records the same request.
    for key in ("metric", "scene", "mass", "tableau", "rtol", "camera_position", "tetrad_e1", "tracer", "observer"):
        assert frame.header[key] == tool.header[key], key


def test_an_accretion_frame_is_the_tools_with_its_light_and_flux(run_tool):
    options = dict(scene="accretion", accretion_gas="rest", camera_r=100, fov=8, width=40, height=40)
    frame = grtrace.render(**options)
    code, out, err, exr = run_tool(options)
    assert code == 0, err
    tool = grtrace.read_exr(str(exr))
    assert "intensity" in frame.channel_names and "optical_depth" in frame.channel_names
    for name in frame.channel_names:
        assert np.array_equal(bits(frame[name]), bits(tool[name])), name
    line = json.loads(out.strip().splitlines()[-1])
    assert frame.report["flux"] == line["flux"] > 0
    assert frame.report["tracer"] == "planar"
    # The brightest ring is the photon ring's, around the dimmer shadow.
    intensity = frame["intensity"]
    assert intensity[20, 20] < 0.5 * intensity.max()


def test_a_line_profile_is_the_tools_and_its_orders_sum_to_it(run_tool):
    options = dict(metric="schwarzschild", camera_theta=60, disk_outer=15, energy_bins=30, line_finest=0.0625,
                   disk_transparent=True)
    profile = grtrace.line_profile(**options)
    code, out, err, csv = run_tool(dict(options, spectrum="line", scene="disk"), "line.csv")
    assert code == 0, err
    lines = [row for row in csv.read_text().splitlines() if not row.startswith("#")]
    columns = lines[0].split(",")
    table = np.array([[float(x) for x in row.split(",")] for row in lines[1:]])
    assert np.allclose(table[:, columns.index("flux")], profile["flux"], rtol=1e-9, atol=0)
    assert np.allclose(table[:, columns.index("energy_low")], profile["edges"][:-1], rtol=1e-9)
    assert len(profile["edges"]) == 31 and len(profile["flux_by_order"]) == 4
    assert np.allclose(sum(profile["flux_by_order"]), profile["flux"], rtol=1e-12, atol=0)
    line = json.loads(out.strip().splitlines()[-1])
    assert line["total_flux"] == profile["report"]["total_flux"] > 0
    assert profile["report"]["total_flux_n1"] > 0 and profile["report"]["disk_inner"] == 6
    with pytest.raises(ValueError, match="--fov describes a frame"):
        grtrace.line_profile(fov=30)
    with pytest.raises(ValueError, match="--spectrum asks for the disk's line profile"):
        grtrace.render(spectrum="line", scene="disk")


def test_a_ring_image_is_the_tools_and_its_orders_hold_their_flux(run_tool):
    options = dict(metric="kerr", spin=0.5, camera_theta=30, disk_outer=50, disk_transparent=True, width=40,
                   height=36, ring_field=7)
    rings = grtrace.ring_image(**options)
    code, out, err, exr = run_tool(dict(options, rings=True, scene="disk"), "ring.exr")
    assert code == 0, err
    tool = grtrace.read_exr(str(exr))
    for n, name in enumerate(["I_n0", "I_n1", "I_n2", "I_n3_up"]):
        assert rings["intensity"][n].shape == (36, 40)
        assert np.allclose(tool[name], rings["intensity"][n], rtol=1e-6, atol=1e-30), name
    pixel = 2 * 7 / 40
    assert np.allclose([plane.sum() * pixel**2 for plane in rings["intensity"]], rings["flux"], rtol=1e-9, atol=0)
    line = json.loads(out.strip().splitlines()[-1])
    assert line["flux_n2"] == rings["report"]["flux_n2"] > 0
    assert line["ring_diameter_n1"] == rings["ring_diameter"][0] > 0
    assert rings["ring_width"][2] < 0.2 * rings["ring_width"][1] < rings["ring_width"][0]
    with pytest.raises(ValueError, match="--fov describes a frame"):
        grtrace.ring_image(fov=30)
    with pytest.raises(ValueError, match="--rings asks for the disk's photon ring"):
        grtrace.render(rings=True, scene="disk")


def test_a_riaf_frame_is_the_tools_in_physical_units(run_tool):
    options = dict(scene="riaf", metric="kerr", spin=0.9, source="sgr-a", camera_r=1000, camera_theta=17,
                   fov=2.3, width=12, height=12, sky_radius=2000, rtol=1e-8)
    frame = grtrace.render(**options)
    code, out, err, exr = run_tool(options)
    assert code == 0, err
    tool = grtrace.read_exr(str(exr))
    assert np.array_equal(bits(frame["intensity"]), bits(tool["intensity"]))
    line = json.loads(out.strip().splitlines()[-1])
    assert frame.report["flux_jy"] == line["flux_jy"]
    assert 1.0 < line["flux_jy"] < 5.0  # Sgr A* at 230 GHz: 2.4 Jy measured
    assert frame.report["microarcseconds_per_pixel"] == pytest.approx(4.84 * 1000 * 2 * np.tan(np.radians(1.15)) / 11,
                                                                      rel=1e-3)
    assert tool.header["source"] == "sgr-a" and tool.header["medium"] == "riaf"
    # Its light by image order: the tool's channels, summing to the intensity, and the same fluxes by order.
    total = np.zeros_like(frame["intensity"])
    for n in ("n0", "n1", "n2", "n3_up"):
        assert np.array_equal(bits(frame["intensity_" + n]), bits(tool["intensity_" + n])), n
        total += frame["intensity_" + n]
        assert frame.report["flux_" + n] == line["flux_" + n] == float(tool.header["flux_" + n])
    assert np.array_equal(total, frame["intensity"])
    assert line["flux_n0"] > line["flux_n1"] > 0
    assert sum(line["flux_" + n] for n in ("n0", "n1", "n2", "n3_up")) == pytest.approx(line["flux"], rel=1e-6)


def test_a_riaf_spectrum_in_one_pass_is_the_tools(run_tool):
    # Several frequencies as a sequence: a channel and a flux each, as the tool's comma-separated list gives them.
    options = dict(scene="riaf", metric="kerr", spin=0.9, source="sgr-a", camera_r=1000, camera_theta=17,
                   fov=2.3, width=8, height=8, sky_radius=2000, rtol=1e-8)
    frame = grtrace.render(frequency=[86, 230, 345.5], **options)
    code, out, err, exr = run_tool(dict(options, frequency="86,230,345.5"))
    assert code == 0, err
    tool = grtrace.read_exr(str(exr))
    line = json.loads(out.strip().splitlines()[-1])
    for band in ("86GHz", "230GHz", "345p5GHz"):
        assert np.array_equal(bits(frame["intensity_" + band]), bits(tool["intensity_" + band])), band
        assert frame.report["flux_jy_" + band] == line["flux_jy_" + band] == float(tool.header["flux_jy_" + band])
    assert np.array_equal(bits(frame["intensity"]), bits(frame["intensity_86GHz"]))  # the first band's picture
    assert tool.header["frequencies_ghz"] == "86,230,345.5"
    assert line["flux_jy_86GHz"] < line["flux_jy_230GHz"] > line["flux_jy_345p5GHz"]


def test_channels_are_views_of_the_frames_memory():
    frame = grtrace.render(**MAIN_FRAME)
    a = frame["redshift"]
    assert a.shape == (60, 80) and a.dtype == np.float32
    assert a.base is not None and not a.flags["OWNDATA"]
    b = frame.channel("redshift")
    assert a.__array_interface__["data"][0] == b.__array_interface__["data"][0]  # the same buffer, twice
    del frame
    gc.collect()
    assert np.isfinite(a[0, 0]) or np.isnan(a[0, 0])  # the array keeps the frame alive
    assert sorted(grtrace.render(**MAIN_FRAME).channels) == sorted(
        ["R", "G", "B", "object", "status", "redshift", "sky_theta", "sky_phi", "steps", "order"])


# Each bad argument kind, as a keyword and as the tool's command line: the same refusal, word for word.
def test_a_disk_drawn_by_its_light_is_the_tools_and_its_orders_sum_to_it(run_tool):
    options = dict(KERR_DISK, width=32, height=24, disk_transparent=True, redshift_power=4)
    frame = grtrace.render(**options)
    code, out, err, exr = run_tool(options)
    assert code == 0, err
    tool = grtrace.read_exr(str(exr))
    for name in frame.channel_names:
        assert np.array_equal(bits(frame[name]), bits(tool[name])), name
    orders = ["intensity_n0", "intensity_n1", "intensity_n2", "intensity_n3_up"]
    total = np.zeros_like(frame["intensity"])
    for name in orders:
        total += frame[name]  # the frame's own float additions, in the same order
    assert np.array_equal(total, frame["intensity"])
    line = json.loads(out.strip().splitlines()[-1])
    flux = [line["flux_" + n] for n in ("n0", "n1", "n2", "n3_up")]
    assert frame.report["flux_n1"] == flux[1] > 0
    assert sum(flux) == pytest.approx(line["flux"], rel=1e-12)
    assert tool.header["disk_transparent"] == "true"


BAD = [
    dict(metric="teapot"),
    dict(spin=0.5),
    dict(metric="kerr", spin=1.2),
    dict(camera_r=1.5),
    dict(camera_r=500),
    dict(camera_theta=-1),
    dict(fov=180),
    dict(fov="wide"),
    dict(camera_phi=float("inf")),
    dict(look=(1, 0)),
    dict(up=(1, 0, 0), look=(1, 0, 0), width=8, height=8),
    dict(width=0),
    dict(height=20000),
    dict(rtol=2),
    dict(atol=-1),
    dict(tableau="rkf45"),
    dict(tableau="dopri5", control="i"),
    dict(control="fixed", tableau="rk4"),
    dict(tracer="planar", metric="kerr"),
    dict(tracer="teapot"),
    dict(device="tpu"),
    dict(scene="teapot"),
    dict(disk_outer=30),
    dict(scene="disk", metric="kerr", spin=0.9, disk_inner=1.5),
    dict(scene="disk", metric="minkowski"),
    dict(threads=-1),
    dict(table_rays=3),
    dict(max_steps=0),
    dict(sky_radius=1e200),
    dict(angle_correction="some"),
    dict(observer="moving"),
    dict(metric="schwarzschild", chart="ks"),
    dict(error_map=True, metric="kerr"),
    dict(sky_texture="/nonexistent/texture.exr", scene="sky"),
    dict(scene="disk", checker_squares=4),
    dict(control="fixed", tableau="rk4", step=0.5, rtol=1e-3),
    dict(tracer="general", table_rays=100),
    dict(accretion_gas="rest"),
    dict(scene="accretion", metric="kerr"),
    dict(scene="riaf", metric="kerr", camera_r=50),
    dict(scene="riaf", metric="kerr", camera_r=1000, sky_radius=2000, source="m31"),
    dict(source="sgr-a"),
    dict(scene="riaf", metric="schwarzschild"),
    dict(scene="riaf", metric="kerr", camera_r=1000, sky_radius=2000, frequency=[230, 345, 230]),
    dict(scene="torus", metric="kerr", torus_inner=12),
    dict(torus_opacity=1),
    dict(scene="disk", redshift_power=4),
    dict(scene="disk", metric="kerr", spin=0.9, disk_light=True, tracer="general"),
    dict(scene="disk", metric="rn", disk_light=True),
    dict(scene="disk", disk_light=True, rtol=1e-6),
]


@pytest.mark.parametrize("options", BAD, ids=[repr(b) for b in BAD])
def test_bad_arguments_raise_value_error_with_the_tools_message(options, run_tool):
    with pytest.raises(ValueError) as raised:
        grtrace.render(**options)
    code, out, err, exr = run_tool(options)
    assert code == 2, (out, err)
    assert not exr.exists()
    tool_message = err.strip().splitlines()[-1].removeprefix("grtrace-render: error: ")
    assert str(raised.value) == tool_message


def test_python_only_mistakes_raise_value_error_too():
    for options, says in [
        (dict(camera_radius=20), "unknown option 'camera_radius'"),
        (dict(look="sideways"), "--look expects a number"),
        (dict(look=[1, "a", 0]), "look expects numbers"),
        (dict(no_mirrors="yes"), "no_mirrors is a flag"),
        (dict(width=object()), "width expects a number"),
    ]:
        with pytest.raises(ValueError, match=says.replace("(", r"\(")):
            grtrace.render(**options)
    with pytest.raises(ValueError, match="progress must be"):
        grtrace.render(progress="yes", **MAIN_FRAME)
    with pytest.raises(ValueError, match="pixel .* is outside"):
        grtrace.trace_ray(pixel=(80, 0), **MAIN_FRAME)
    with pytest.raises(ValueError, match="pixel expects"):
        grtrace.trace_ray(pixel=(1.5, "x"), **MAIN_FRAME)
    with pytest.raises(ValueError, match="position expects 4 numbers"):
        grtrace.trace_ray(position="abc", momentum=(1, 2, 3, 4))
    with pytest.raises(ValueError, match="samples_per_step must be"):
        grtrace.trace_ray(pixel=(1, 1), samples_per_step=0, **MAIN_FRAME)


def test_lambda_is_spelt_lambda_underscore():
    frame = grtrace.render(metric="sds", lambda_=1.5e-5, width=16, height=12)
    assert float(frame.header["lambda"]) == 1.5e-5
    with pytest.raises(ValueError, match="--lambda must lie in"):
        grtrace.render(metric="sds", lambda_=1.0, width=8, height=8)


def test_progress_reaches_every_pixel():
    seen = []
    frame = grtrace.render(progress=lambda done, total: seen.append((done, total)), **KERR_DISK)
    assert seen, "the callback was never called"
    assert all(t == 96 * 64 for _, t in seen)
    assert [d for d, _ in seen] == sorted(d for d, _ in seen)
    assert seen[-1][0] == 96 * 64
    assert frame.report["status_counts"]["hit"] > 0


def test_an_exception_in_the_progress_callback_stops_the_render():
    def fail(done, total):
        raise RuntimeError("stop here")

    with pytest.raises(RuntimeError, match="stop here"):
        grtrace.render(progress=fail, **dict(KERR_DISK, width=512, height=512, tracer="general"))


def thread_count():
    return len(os.listdir("/proc/self/task"))


def test_ctrl_c_stops_a_render_within_a_fifth_of_a_second_and_leaves_nothing_behind(tmp_path):
    # A render first: the module keeps its render thread and that thread's OpenMP team for the next render.
    grtrace.render(**dict(KERR_DISK, width=8, height=8))
    before = thread_count()
    fired = []

    def interrupt():
        fired.append(time.monotonic())
        os.kill(os.getpid(), signal.SIGINT)

    # A frame of several seconds on two cores (every pixel integrated).
    big = dict(KERR_DISK, width=1024, height=1024, tracer="general")
    timer = threading.Timer(0.5, interrupt)
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        grtrace.render(**big)
    stopped = time.monotonic()
    timer.join()
    assert fired, "the render ended before the interrupt"
    assert stopped - fired[0] <= 0.2
    # Nothing left behind: no thread more than before (the render's thread waits for the next one), no file was
    # written, and the next render works.
    deadline = time.monotonic() + 2.0
    while thread_count() > before and time.monotonic() < deadline:
        time.sleep(0.05)  # (the timer's thread may linger a moment)
    assert thread_count() <= before
    assert list(tmp_path.iterdir()) == []
    assert grtrace.render(**dict(KERR_DISK, width=16, height=16)).report["width"] == 16


def test_the_gil_is_released_while_tracing():
    ticks = []
    stop = threading.Event()

    def count():
        while not stop.is_set():
            ticks.append(1)
            time.sleep(0.001)

    counter = threading.Thread(target=count)
    counter.start()
    try:
        grtrace.render(**dict(KERR_DISK, width=256, height=256, tracer="general"))
    finally:
        stop.set()
        counter.join()
    assert len(ticks) > 20  # the other thread ran while the frame was traced


def test_two_threads_rendering_at_once_give_the_arrays_of_one():
    alone = grtrace.render(**KERR_DISK)
    results = [None, None]

    def work(i):
        results[i] = grtrace.render(**KERR_DISK)

    threads = [threading.Thread(target=work, args=(i,)) for i in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for r in results:
        for name in alone.channel_names:
            assert np.array_equal(bits(r[name]), bits(alone[name])), name


def rss_bytes():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")


def test_two_hundred_renders_do_not_grow_the_process_by_more_than_one_frame():
    options = dict(KERR_DISK, width=128, height=128)
    frame_bytes = 128 * 128 * 9 * 4
    for _ in range(20):  # the allocator's and the OpenMP runtime's first growth, outside the measure
        grtrace.render(**options)
    gc.collect()
    before = rss_bytes()
    for _ in range(200):
        frame = grtrace.render(**options)
        del frame
    gc.collect()
    grown = rss_bytes() - before
    assert grown <= frame_bytes, f"grew by {grown} bytes over 200 renders (one frame: {frame_bytes})"
